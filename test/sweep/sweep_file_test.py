#!/usr/bin/python3
"""Sweep files are validated strictly: each broken file below is refused by `scripts/sweep
--check` with exit status 2 and a message naming the key; the shipped sweeps and the test sweep
are valid and expand into runs with stable names.

  test/sweep/sweep_file_test.py [--ehd-sim PATH]
"""
import argparse
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SWEEP = os.path.join(REPO, "scripts", "sweep")

VALID = """
scene: shear_field
set: {N: 32, M: 32}
grid:
  product:
    Ca_E: [0.1, 0.3]
  zip:
    sigma_r: [1.75, 3.25]
    tag.case: [A, B]
stop: {t_end: 1}
"""

# (what is broken, replacement of VALID's text (old, new), text the message must contain)
BROKEN = [
    ("unknown top-level key", ("stop:", "stpo: 1\nstop:"), "unknown key 'stpo'"),
    ("unknown key in stop", ("{t_end: 1}", "{t_end: 1, steady_tol: 1e-3}"),
     "stop: unknown key 'steady_tol'"),
    ("missing stop.t_end", ("{t_end: 1}", "{steady: 1e-3}"), "stop: missing key 't_end'"),
    ("t_end a string", ("{t_end: 1}", "{t_end: long}"), "stop.t_end: must be a number"),
    ("t_end <= 0", ("{t_end: 1}", "{t_end: 0}"), "stop.t_end: 0 is out of range"),
    ("empty product list", ("Ca_E: [0.1, 0.3]", "Ca_E: []"), "grid.product.Ca_E: empty list"),
    ("values not a list", ("Ca_E: [0.1, 0.3]", "Ca_E: 0.1"),
     "grid.product.Ca_E: must be a list"),
    ("zip lists of different lengths", ("tag.case: [A, B]", "tag.case: [A, B, C]"),
     "grid.zip.tag.case: 3 values, but grid.zip.sigma_r has 2"),
    ("duplicate value", ("Ca_E: [0.1, 0.3]", "Ca_E: [0.1, 0.1]"),
     "grid.product.Ca_E[1]: 0.1 appears twice"),
    ("empty grid", ("  product:\n    Ca_E: [0.1, 0.3]\n  zip:\n    sigma_r: [1.75, 3.25]\n"
                    "    tag.case: [A, B]\n", "  {}\n"), "grid: empty"),
    ("key both fixed and swept", ("{N: 32, M: 32}", "{N: 32, M: 32, Ca_E: 1}"),
     "grid: 'Ca_E' is also fixed in 'set'"),
    ("unknown record key", ("stop: {t_end: 1}", "stop: {t_end: 1}\nrecord: {vtk: true}"),
     "record: unknown key 'vtk'"),
    ("plot of an unknown quantity", ("stop: {t_end: 1}", "stop: {t_end: 1}\nplots:\n"
                                     "  - {file: a.png, type: series, y: D}"),
     "plots[0].y: 'D' is not a series quantity"),
    ("plot against a key not in the grid", ("stop: {t_end: 1}", "stop: {t_end: 1}\nplots:\n"
                                            "  - {file: a.png, type: final, x: Ca, y: dxy}"),
     "plots[0].x: 'Ca' is not a grid key"),
    ("unknown base scene", ("scene: shear_field", "scene: no_such_scene"),
     "scene: 'no_such_scene' not found"),
    ("unknown scene key (found by ehd_sim)", ("Ca_E: [0.1, 0.3]", "Ca_EE: [0.1, 0.3]"),
     "'Ca_EE' unknown key"),
    ("unknown nested scene key (found by ehd_sim)", ("{N: 32, M: 32}",
                                                     "{N: 32, M: 32, geometry.shap: circle}"),
     "unknown key"),
]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--ehd-sim", default=os.path.join(REPO, "build", "bin", "ehd_sim"))
    args = p.parse_args()
    failures = 0
    with tempfile.TemporaryDirectory(prefix="ehd_sweep_file_test_") as tmp:
        def check(text):
            path = os.path.join(tmp, "s.yaml")
            with open(path, "w") as f:
                f.write(text)
            proc = subprocess.run([SWEEP, path, "--check", "--ehd-sim", args.ehd_sim],
                                  capture_output=True, text=True)
            return proc.returncode, proc.stdout + proc.stderr

        rc, text = check(VALID)
        if rc != 0 or "4 runs, valid" not in text:
            print("FAIL: the valid sweep file: exit %d: %s" % (rc, text.strip()))
            failures += 1
        for what, (old, new), expect in BROKEN:
            assert old in VALID, what
            rc, text = check(VALID.replace(old, new, 1))
            if rc != 2 or expect not in text:
                print("FAIL: %s: exit %d (expected 2), message: %s (expected to contain: %s)" % (
                    what, rc, text.strip(), expect))
                failures += 1
            else:
                print("ok: %s -> %s" % (what, text.strip().split(": ", 2)[-1]))
        # A bad value of a key every run shares (here from --set) stops the sweep before it
        # starts, naming the key; the same bad value on a grid key is one failed run instead.
        proc = subprocess.run([SWEEP, os.path.join(HERE, "tiny.yaml"), "--set", "N=8",
                               "--check", "--ehd-sim", args.ehd_sim], capture_output=True,
                              text=True)
        if proc.returncode != 2 or "'N' = 8 is out of range" not in proc.stderr:
            print("FAIL: --set N=8: exit %d: %s" % (proc.returncode, proc.stderr.strip()))
            failures += 1
        else:
            print("ok: --set N=8 -> " + proc.stderr.strip().split(": ", 2)[-1])
        proc = subprocess.run([SWEEP, os.path.join(HERE, "tiny.yaml"), "--list"],
                              capture_output=True, text=True)
        if "   4  Ca_E=5+sigma_r=1.75+case=A" not in proc.stdout:
            print("FAIL: tiny.yaml run names changed:\n" + proc.stdout)
            failures += 1
        shipped = os.path.join(REPO, "config", "sweeps")
        for name in sorted(os.listdir(shipped)) if os.path.isdir(shipped) else []:
            if not name.endswith(".yaml"):
                continue
            proc = subprocess.run([SWEEP, os.path.join(shipped, name), "--check", "--ehd-sim",
                                   args.ehd_sim], capture_output=True, text=True)
            ok = proc.returncode == 0
            print("%s: shipped sweep %s %s" % ("ok" if ok else "FAIL", name,
                                               (proc.stdout + proc.stderr).strip()))
            failures += not ok
    print("sweep file test: %s" % ("passed" if not failures else "%d failure(s)" % failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
