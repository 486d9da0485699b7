#!/usr/bin/python3
"""Every shipped scene against its reference CSV (issue #47; the short form of the restructuring
check scripts/reference_csvs, which compares long runs and checkpoints by hand).

Runs each scene of config/scenes/*.yaml with `ehd_sim run SCENE --steps N --csv` (N = 120 in 2D,
past the first electric re-solve of the 2D field scenes at step 100; N = 60 in 3D, past
electric_drop_3d's at step 50; one OpenMP thread, in a temporary folder) and compares its CSV row
by row with test/data/scene_references/SCENE.csv: the same header, the same rows, each value
within 1e-9 relative (one unit in the 10th significant digit the CSV prints) or 1e-13 absolute
(round-off of O(1) quantities that are near zero, e.g. D_xy at step 0). A rebuild on the same
machine gives the same bits, so the same text. A scene without a reference, or a reference
without a scene, fails the test.

Shown to fail once (2026-12-08), a parameter off by 1e-6 relative: `--only capsule_shear --set
Ca=0.0125000125` moves tt_phase by 1e-6 relative from step 15 and dxy by 2e-9 from step 76 (the
column ca prints 6 digits and does not show it; a short run is mostly the shear's kinematics);
sphere_shear with Ca=0.05000005 moves tt_phase, dxy, d_field and surface_flow; electric_drop_3d
with Ca_E=0.1000001 moves d_field by 1e-6 relative from step 1. Each fails the test.

Regenerate the references (after a change that is meant to move the numbers; say why in the
commit):

  scripts/reference_csvs --test-references

  test/cli/scene_references_test.py [--ehd-sim PATH] [--only SCENE ...] [--set KEY=VALUE ...]
                                    [--update]
"""
import argparse
import csv
import glob
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCENES = os.path.join(REPO, "config", "scenes")
REFERENCES = os.path.join(REPO, "test", "data", "scene_references")
REGENERATE = "scripts/reference_csvs --test-references"
STEPS = {2: 120, 3: 60}
REL_TOL = 1e-9
ABS_TOL = 1e-13


def scene_names(folder, ext):
    return {os.path.basename(p)[: -len(ext)] for p in glob.glob(os.path.join(folder, "*" + ext))}


def steps_of(scene):
    with open(os.path.join(SCENES, scene + ".yaml")) as f:
        return STEPS[int(yaml.safe_load(f).get("dimension", 2))]


def run_scene(ehd_sim, scene, csv_path, sets):
    cmd = [ehd_sim, "run", os.path.join(SCENES, scene + ".yaml"), "--steps",
           str(steps_of(scene)), "--quiet", "--csv", csv_path]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                       universal_newlines=True)
    if r.returncode != 0:
        return "`%s` exited with %d:\n%s" % (" ".join(cmd), r.returncode, r.stdout[-2000:])
    return None


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def compare(scene, ref_path, new_path):
    """The differences of new_path from ref_path, one line per column that moved."""
    ref_header, ref_rows = read_csv(ref_path)
    new_header, new_rows = read_csv(new_path)
    if ref_header != new_header:
        return ["%s: the header changed:\n    reference %s\n    now       %s"
                % (scene, ",".join(ref_header), ",".join(new_header))]
    if len(ref_rows) != len(new_rows):
        return ["%s: %d rows, the reference has %d" % (scene, len(new_rows), len(ref_rows))]
    moved = {}  # column -> [first row, its step, ref, new, largest |diff|, its row, its ref]
    for i, (a, b) in enumerate(zip(ref_rows, new_rows)):
        for col, x, y in zip(ref_header, a, b):
            if x == y:
                continue
            try:
                fx, fy = float(x), float(y)
            except ValueError:
                fx, fy = math.nan, math.nan
            diff = abs(fx - fy)
            if diff <= max(REL_TOL * abs(fx), ABS_TOL):  # false for nan
                continue
            if col not in moved:
                moved[col] = [i, a[0], x, y, diff, i, fx]
            elif diff > moved[col][4]:
                moved[col][4:7] = [diff, i, fx]
    return ["%s: column %s moved from row %d (step %s): %s -> %s; largest |diff| %.3g "
            "(%.3g relative) at row %d" % (scene, col, m[0], m[1], m[2], m[3], m[4],
                                           m[4] / abs(m[6]) if m[6] else math.inf, m[5])
            for col, m in moved.items()]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--ehd-sim", default=os.path.join(REPO, "build", "bin", "ehd_sim"))
    p.add_argument("--only", action="append", default=[], help="these scenes only")
    p.add_argument("--set", action="append", default=[], help="an override for every run")
    p.add_argument("--update", action="store_true",
                   help="write the references instead of comparing (" + REGENERATE + ")")
    args = p.parse_args()

    scenes = scene_names(SCENES, ".yaml")
    refs = scene_names(REFERENCES, ".csv")
    failures = []
    if not args.only and not args.update:
        for s in sorted(scenes - refs):
            failures.append("%s: a scene without a reference CSV" % s)
        for s in sorted(refs - scenes):
            failures.append("%s: a reference CSV (%s.csv) without a scene" % (s, s))
    if args.update and not args.only:
        for s in sorted(refs - scenes):
            os.remove(os.path.join(REFERENCES, s + ".csv"))
            print("removed %s.csv (no such scene)" % s)
    for s in args.only:
        if s not in scenes:
            p.error("no scene %s in %s" % (s, SCENES))
    os.makedirs(REFERENCES, exist_ok=True)

    with tempfile.TemporaryDirectory(prefix="scene_references_") as tmp:
        for scene in sorted(args.only or scenes):
            start = time.monotonic()
            out = os.path.join(tmp, scene + ".csv")
            error = run_scene(args.ehd_sim, scene, out, args.set)
            if error:
                failures.append("%s: %s" % (scene, error))
            elif args.update:
                shutil.copyfile(out, os.path.join(REFERENCES, scene + ".csv"))
                print("wrote test/data/scene_references/%s.csv (%d steps)"
                      % (scene, steps_of(scene)), flush=True)
            elif scene in refs:
                moved = compare(scene, os.path.join(REFERENCES, scene + ".csv"), out)
                failures += moved
                print("%s: %s (%d steps, %.1f s)" % (scene, "MOVED" if moved else "ok",
                                                    steps_of(scene), time.monotonic() - start),
                      flush=True)
    if failures:
        print("\nFAILED:\n  " + "\n  ".join(failures))
        if not args.update:
            print("\nIf the change is meant to move these numbers, regenerate the references "
                  "with\n  %s\nand say why in the commit." % REGENERATE)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
