#!/usr/bin/env python3
"""Speed of the coupled step for shear_field (docs/validation_ehd.md section 5).

1. bench/ehd_step_bench (CPU time per stage, inside the electric solve, and Simulation::Step
   with the field off / on / sub-stepped) at N = 64 (the scene's default) and N = 128.
2. Wall and CPU time to steady D_xy (`ehd_sim run --until-steady 1e-3`) for:
   no field and no solver (a copy of the scene without the `electric:` block), Ca_E = 0 with the
   solver built (the shipped scene: its `electric:` block builds it), Ca_E = 0.3 solved every
   step, every 10 steps, on a marker move of 0.02 cells, and with the scene's shipped numerics
   (electric_every 100 and move tolerance 0.02). The bench runs with the move tolerance off, so
   that its electric_every = n rows solve exactly every n steps.

    python3 scripts/validate_ehd_speed.py [--bench PATH] [--work DIR]
"""
import os
import re
import subprocess

import validate_ehd_common as common


def main():
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--bench", default=os.path.join(os.path.dirname(
        os.environ.get("EHD_SIM", "/tmp/build-ehd/bin/ehd_sim")), "bench", "ehd_step_bench"))
    p.add_argument("--skip-bench", action="store_true")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    if not args.skip_bench:
        for n, steps, warm in ((64, 2000, 500), (128, 500, 200)):
            print("load average: %s" % " ".join(common.load_average()))
            out = subprocess.run([args.bench, "shear_field", "--steps", str(steps), "--warmup",
                                  str(warm), "--set", "numerics.threads=1", "--set", "N=%d" % n,
                                  "--set", "M=%d" % n,
                                  # electric_every = n rows mean exactly that: the scene's move
                                  # tolerance (0.02 shipped) would add solves in between.
                                  "--set", "numerics.electric_move_tolerance=0"],
                                 cwd=common.REPO, env=env,
                                 capture_output=True, text=True).stdout
            print("```\n" + out.strip() + "\n```\n")

    # Scene without the electric block (Ca_E = 0): the solver is not built at all.
    text = open(os.path.join(common.REPO, "config", "scenes", "shear_field.yaml")).read()
    text = re.sub(r"\nelectric:\n(  .*\n)+", "\n", text).replace("Ca_E: 0.3", "Ca_E: 0")
    text = text.replace("name: shear_field", "name: shear_field_no_electric")
    no_field = os.path.join(args.work, "shear_field_no_electric.yaml")
    with open(no_field, "w") as f:
        f.write(text)
    configs = [
        ("no electric block, Ca_E = 0 (no solver)", no_field, []),
        ("electric block, Ca_E = 0 (solver built, never solved)", "shear_field", ["Ca_E=0"]),
        ("Ca_E = 0.3, electric_every = 1", "shear_field",
         ["numerics.electric_every=1", "numerics.electric_move_tolerance=0"]),
        ("Ca_E = 0.3, electric_every = 10", "shear_field",
         ["numerics.electric_every=10", "numerics.electric_move_tolerance=0"]),
        ("Ca_E = 0.3, move tolerance 0.02 cells", "shear_field",
         ["numerics.electric_every=1000000", "numerics.electric_move_tolerance=0.02"]),
        ("Ca_E = 0.3, shipped default (every 100 steps or a 0.02-cell move)", "shear_field", []),
    ]
    runs = []
    for i, (label, scene, sets) in enumerate(configs):
        runs.append((label, common.Run("speed_%d" % i, scene, sets, ["--until-steady", "1e-3"],
                                       csv_every=1)))
    print("load average before: %s" % " ".join(common.load_average()))
    common.run_all(args, [r for _, r in runs])
    print("load average after: %s\n" % " ".join(common.load_average()))
    header = ["configuration", "pipeline step 1", "steady at t (1/k)", "D_xy", "theta/pi",
              "steps", "GMRES it./step", "wall s", "cpu s", "cpu ms/step", "vs no solver"]
    body = []
    base = None
    for label, r in runs:
        cmd = [args.ehd_sim, "run", r.scene, "--steps", "1"]
        for x in r.sets:
            cmd += ["--set", x]
        shown = subprocess.run(cmd, cwd=common.REPO, env=env, capture_output=True, text=True)
        pipe = re.search(r"1\. electric: (.*)", shown.stdout)
        pipe = pipe.group(1).split(",")[0].split(" (")[0] if pipe else "?"
        if not r.rows or r.error:
            body.append([label, pipe, "failed: " + r.error] + [""] * 8)
            continue
        last = r.rows[-1]
        gm = sum(row["gmres_iterations"] for row in r.rows[1:]) / max(1, len(r.rows) - 1)
        ms = 1e3 * r.cpu / r.steps
        if base is None:
            base = ms
        body.append([label, pipe, "%.3f%s" % (last["t"], "" if r.steady else " (not steady)"),
                     "%.5f" % last["dxy"], "%.4f" % (last["inclination"] / 3.141592653589793),
                     r.steps, "%.2f" % gm, "%.1f" % r.wall, "%.1f" % r.cpu, "%.3f" % ms,
                     "%.2f" % (ms / base)])
    print(common.table(header, body))


if __name__ == "__main__":
    main()
