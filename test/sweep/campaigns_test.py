#!/usr/bin/python3
"""The validation campaigns (scripts/campaigns/*.yaml, docs/campaigns.md):

1. every campaign spec expands and passes `scripts/sweep FILE --check` (ehd_sim runs one step of
   its first scene), and long_runs lists every shipped scene; validate_3d's long runs have their
   own t_end (and chunks), which --t-end replaces, and its drops have no law (`law: ~`);
2. broken campaign specs are refused with exit status 2 and a message naming the key;
3. validate_3d_substeps runs end to end on a tiny override (N = 16, 162 vertices, t = 0.01:
   7 runs of a few steps) and its collected table has the old script's columns and rows, the
   reference's differences zero, solves in every run with a field and none without, D_z of
   the run without a field near 0; a rerun runs nothing (the runs are finished).

  test/sweep/campaigns_test.py [--ehd-sim PATH]
"""
import argparse
import csv
import glob
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SWEEP = os.path.join(REPO, "scripts", "sweep")
CAMPAIGNS = os.path.join(REPO, "scripts", "campaigns")
sys.path.insert(0, os.path.join(REPO, "scripts"))

from sweeplib.spec import Sweep  # noqa: E402

FAILURES = []


def check(condition, what):
    print("%s: %s" % ("ok" if condition else "FAILED", what), flush=True)
    if not condition:
        FAILURES.append(what)


def sweep(args, *extra):
    return subprocess.run([SWEEP] + list(extra) + ["--ehd-sim", args.ehd_sim],
                          capture_output=True, text=True)


BROKEN = [  # (what, spec text, text the message must contain)
    ("variant without a name", "scene: shear_field\ngrid:\n  variants:\n    - {set: {N: 32}}\n"
     "stop: {t_end: 1}\n", "grid.variants[0]: missing key 'name'"),
    ("variant key also in set", "scene: shear_field\nset: {N: 32}\ngrid:\n  variants:\n"
     "    - {name: a, set: {N: 64}}\nstop: {t_end: 1}\n",
     "grid.variants: 'N' is also fixed in 'set'"),
    ("two variants with one name", "scene: shear_field\ngrid:\n  variants:\n    - {name: a}\n"
     "    - {name: a}\nstop: {t_end: 1}\n", "grid.variants[1].name: 'a' appears twice"),
    ("unknown scene in the grid", "grid:\n  product:\n    scene: [shear_field, no_such]\n"
     "stop: {t_end: 1}\n", "grid.product.scene[1]: scene: 'no_such' not found"),
    ("no scene at all", "grid:\n  product:\n    N: [32]\nstop: {t_end: 1}\n",
     "missing key 'scene'"),
    ("table file missing", "scene: shear_field\ngrid:\n  product:\n    N: [32]\n"
     "stop: {t_end: 1}\ntable: nothing.py\n", "table: 'nothing.py' is not a Python file"),
    ("jobs not an integer", "scene: shear_field\ngrid:\n  product:\n    N: [32]\n"
     "stop: {t_end: 1}\njobs: 1.5\n", "jobs: must be an integer"),
    ("variant t_end not positive", "scene: shear_field\ngrid:\n  variants:\n"
     "    - {name: a, t_end: 0}\nstop: {t_end: 1}\n", "grid.variants[0].t_end: 0 is out of range"),
    ("sections_every not an integer", "scene: shear_field\ngrid:\n  product:\n    N: [32]\n"
     "stop: {t_end: 1}\nrecord: {sections_every: 9.5}\n",
     "record.sections_every: must be an integer"),
]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--ehd-sim", default=os.environ.get(
        "EHD_SIM", os.path.join(REPO, "build", "bin", "ehd_sim")))
    args = p.parse_args()

    specs = sorted(glob.glob(os.path.join(CAMPAIGNS, "*.yaml")))
    check(len(specs) >= 3, "scripts/campaigns holds the campaign specs (%d)" % len(specs))
    for path in specs:
        s = Sweep(path)
        check(len(s.runs) > 0 and s.table is not None,
              "%s expands (%d runs) and has its table" % (os.path.basename(path), len(s.runs)))
        proc = sweep(args, path, "--check")
        check(proc.returncode == 0, "%s --check%s" % (os.path.basename(path), "" if
                                                      proc.returncode == 0 else ": " + proc.stderr))
    shipped = sorted(f[:-5] for f in os.listdir(os.path.join(REPO, "config", "scenes"))
                     if f.endswith(".yaml"))
    listed = sorted(r.values["scene"] for r in Sweep(os.path.join(CAMPAIGNS, "long_runs.yaml")).runs)
    check(listed == shipped, "long_runs.yaml lists every shipped scene (missing: %s)" % (
        ", ".join(sorted(set(shipped) - set(listed))) or "none"))
    v3d = Sweep(os.path.join(CAMPAIGNS, "validate_3d.yaml"))
    longs = [r for r in v3d.runs if r.values["tag.variant"].startswith("long-")]
    check(len(longs) == 4 and all(r.t_end == 15 for r in longs) and
          v3d.chunk_ends(longs[0]) == [10, 15] and v3d.chunk_ends(v3d.runs[0]) == [3] and
          v3d.run_settings(longs[0])["t_end"] == 15,
          "validate_3d: the long runs to t = 15 in chunks of 10, the others to 3")
    short = Sweep(os.path.join(CAMPAIGNS, "validate_3d.yaml"), t_end=0.2)
    check(all(r.t_end == 0.2 for r in short.runs), "--t-end replaces the variants' t_end")
    drops = [r for r in v3d.runs if r.overrides.get("membrane") == "drop"]
    check(drops and all("law" not in r.scene and "law" in r.overrides for r in drops),
          "validate_3d: a drop's scene has no law (law: ~ removes the base scene's)")

    with tempfile.TemporaryDirectory(prefix="campaigns_test_") as tmp:
        for what, text, expected in BROKEN:
            path = os.path.join(tmp, "broken.yaml")
            with open(path, "w") as f:
                f.write(text)
            proc = sweep(args, path, "--check")
            check(proc.returncode == 2 and expected in proc.stderr,
                  "%s: exit 2 naming the key (got %d: %s)" % (what, proc.returncode,
                                                               proc.stderr.strip()))
        spec = os.path.join(CAMPAIGNS, "validate_3d_substeps.yaml")
        proc = sweep(args, spec, "--set", "Ca_E=0.5", "--check")
        check(proc.returncode == 2 and "grid.variants: 'Ca_E' is also fixed in 'set'" in
              proc.stderr, "--set of a key a variant sets is refused (%s)" % proc.stderr.strip())

        out = os.path.join(tmp, "substeps")
        tiny = ["--set", "N=16", "--set", "mesh_subdivisions=2", "--t-end", "0.01", "--out", out]
        proc = sweep(args, spec, *tiny)
        check(proc.returncode == 0, "validate_3d_substeps on a tiny override runs (exit %d)%s" % (
            proc.returncode, "" if proc.returncode == 0 else ": " + proc.stdout[-800:] +
            proc.stderr[-800:]))
        with open(os.path.join(out, "campaign.csv")) as f:
            rows = list(csv.reader(f))
        header, body = rows[0], rows[1:]
        check(header == ["variant", "D_xy", "dD_xy / D_xy", "theta/pi", "d theta/pi", "D_z",
                         "dD_z / D_z", "solves", "wall s", "ms/step", "x no field"],
              "the table has the old script's columns (%s)" % header)
        check([r[0] for r in body] == [
            "reference: every 5", "every 50", "move 0.05, every 50 (shipped before)",
            "move 0.05, every 500", "move 0.05 + shape 0.02, every 1000",
            "move 0.05 + shape 0.05, every 1000", "no field (Ca_E = 0)"],
            "one row per variant, in order, with its label")
        ok = all(len(r) == 11 and r[1] not in ("", "failed") for r in body)
        check(ok, "every variant has its values")
        if ok:
            ref = body[0]
            check(float(ref[2]) == 0 and float(ref[4]) == 0 and float(ref[6]) == 0,
                  "the reference's differences are zero")
            check(all(int(r[7]) >= 1 for r in body[:-1]) and int(body[-1][7]) == 0,
                  "solves: at least one with the field, none without (%s)" % [r[7] for r in body])
            check(abs(float(body[-1][5])) < 0.1 * abs(float(ref[5])),
                  "D_z without the field (%s) is far below the reference's (%s)" % (
                      body[-1][5], ref[5]))
            check(float(body[-1][10]) == 1.0, "the run without a field costs 1.00 x itself")
        with open(os.path.join(out, "table.csv")) as f:
            table = list(csv.DictReader(f))
        check(len(table) == 7 and all(r["status"] == "ok" and r["stopped"] == "t_end"
                                      for r in table),
              "sweep table: 7 runs ok, stopped at t_end")
        summary = os.path.join(out, "runs", "variant=every5", "summary.json")
        before = os.path.getmtime(summary)
        proc = sweep(args, spec, *tiny)
        check(proc.returncode == 0 and os.path.getmtime(summary) == before,
              "a rerun of the finished campaign runs nothing")
    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
