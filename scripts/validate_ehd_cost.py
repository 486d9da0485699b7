#!/usr/bin/env python3
"""Error against run time (docs/error_vs_time.md, docs/img/error_vs_time.png).

1. Grid refinement with `ehd_sim converge` (N and M refined together):
   electric_drop (Case A, Ca_E = 0.2, to t = 15 mu a / gamma; D against Feng and the finest grid)
   and shear_field (capsule, Ca = 0.04, Case A, Ca_E = 0.3; D_xy at t = T against the finest grid).
2. Electric sub-stepping at a fixed grid (N = M = 64): numerics.electric_every = 1, 2, 5, 10, and
   the move tolerance (solve when a marker moved more than tol cells, electric_every large),
   on shear_field (D_xy, theta at t = T against electric_every = 1) and electric_drop (D at
   t = 15 against electric_every = 1). Cost: wall s, ms/step, solves.

    python3 scripts/validate_ehd_cost.py [--work DIR] [--shear-until T] [--no-plot]
"""
import math
import os
import re
import subprocess
import time

import validate_ehd_common as common

IMG = os.path.join(common.REPO, "docs", "img", "error_vs_time.png")


def converge(args, scene, grids, until, sets=()):
    log = os.path.join(args.work, "converge_%s_%s.log" % (scene, grids.replace(",", "-")))
    if args.fresh or not os.path.exists(log) or "differences to the finest" not in open(log).read():
        cmd = [args.ehd_sim, "converge", scene, "--grids", grids, "--until", str(until),
               "--set", "numerics.threads=1", "--set", "numerics.ib_kernel=cosine",
               "--set", "numerics.ib_retraction=0"]
        for s in sets:
            cmd += ["--set", s]
        start = time.time()
        p = subprocess.run(cmd, cwd=common.REPO, env=dict(os.environ, OMP_NUM_THREADS="1"),
                           capture_output=True, text=True)
        with open(log, "w") as f:
            f.write("$ " + " ".join(cmd) + "\n" + p.stdout + p.stderr +
                    "\nprocess wall %.1f s, load %s\n" % (time.time() - start,
                                                           " ".join(common.load_average())))
    text = open(log).read()
    lines = text.splitlines()
    start = next(i for i, l in enumerate(lines) if l.split()[:2] == ["N", "M"])
    table = [l for l in lines[start:] if l.strip()]
    rows = []
    for l in table[1:]:
        parts = l.split()
        if not parts[0].isdigit():
            break
        rows.append(parts)
    return text, table, rows


def substep_runs(scene, until, n, every_list, tolerances, extra=()):
    runs = []
    for e in every_list:
        runs.append(("every=%d" % e, common.Run(
            "cost_%s_N%d_every%d" % (scene, n, e), scene,
            # Move tolerance off: the shipped scenes set 0.02, which would add solves.
            ["N=%d" % n, "M=%d" % n, "numerics.electric_every=%d" % e,
             "numerics.electric_move_tolerance=0"] + list(extra),
            ["--until", str(until)], csv_every=1)))
    for tol in tolerances:
        runs.append(("move tol=%g" % tol, common.Run(
            "cost_%s_N%d_tol%g" % (scene, n, tol), scene,
            ["N=%d" % n, "M=%d" % n, "numerics.electric_every=100000",
             "numerics.electric_move_tolerance=%g" % tol] + list(extra),
            ["--until", str(until)], csv_every=1)))
    return runs


def main():
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--shear-until", type=float, default=4.0)
    p.add_argument("--drop-grids", default="32,64,128")
    p.add_argument("--drop-half-width", type=float, default=4.0,
                   help="walls of the electric_drop grid study at +-this many radii (4: the box "
                   "of the documented table, a = 4, 8, 16 cells on N = 32, 64, 128; the shipped "
                   "scene has 8)")
    p.add_argument("--shear-grids", default="32,48,64,96")
    p.add_argument("--no-plot", action="store_true")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print("load average before: %s" % " ".join(common.load_average()))

    every = [1, 2, 5, 10]
    tols = [0.02, 0.05, 0.1]
    shear = substep_runs("shear_field", args.shear_until, 64, every, tols)
    drop = substep_runs("electric_drop", 15, 64, every, tols,
                        ["geometry.half_width=%g" % args.drop_half_width])
    common.run_all(args, [r for _, r in shear + drop])

    import concurrent.futures
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        fd = pool.submit(converge, args, "electric_drop", args.drop_grids, 15,
                         ["geometry.half_width=%g" % args.drop_half_width])
        fs = pool.submit(converge, args, "shear_field", args.shear_grids, args.shear_until)
        drop_text, drop_table, drop_rows = fd.result()
        shear_text, shear_table, shear_rows = fs.result()
    print("load average after: %s\n" % " ".join(common.load_average()))

    m = re.search(r"Feng small-deformation D = ([-0-9.]+)", drop_text)
    print("### Grid refinement: electric_drop, Case A, Ca_E = 0.2, t = 15 (%s)\n" % (
        "Feng D = " + m.group(1) if m else ""))
    print("```\n" + "\n".join(drop_table) + "\n```\n")
    print("### Grid refinement: shear_field (capsule, Ca = 0.04, Case A, Ca_E = 0.3), D_xy at "
          "t = %g\n" % args.shear_until)
    print("```\n" + "\n".join(shear_table) + "\n```\n")

    plots = {}
    for title, runs, quantity in (("shear_field, N = M = 64, t = %g" % args.shear_until, shear,
                                   "D_xy"),
                                  ("electric_drop, Case A, Ca_E = 0.2, N = M = 64, t = 15",
                                   drop, "D")):
        ref = runs[0][1]
        ref_d = ref.rows[-1]["dxy"]
        ref_t = ref.rows[-1]["inclination"]
        print("### Electric sub-stepping: %s\n" % title)
        # "solves >= 1 it.": steps whose solve ran at least one GMRES iteration. With the
        # extrapolated warm start about half of the solves need none, so at electric_every = n
        # (move tolerance off) the number of solves is steps / n, more than this column.
        header = ["setting", quantity, "|diff| to every=1", "rel. diff", "|theta diff|/pi",
                  "solves >= 1 it.", "steps", "wall s", "ms/step", "speed-up"]
        body = []
        pts = []
        for label, r in runs:
            if r.error:
                body.append([label, "failed: " + r.error] + [""] * 8)
                continue
            d = r.rows[-1]["dxy"]
            th = r.rows[-1]["inclination"]
            # Steps that ran GMRES (gmres_iterations > 0 only on a step that solved; a warm start
            # that needs no iteration is not counted).
            solves = sum(1 for row in r.rows[1:] if row["gmres_iterations"] > 0)
            diff = abs(d - ref_d)
            body.append([label, "%.6f" % d, "%.2e" % diff, "%.2e" % (diff / abs(ref_d)),
                         "%.2e" % (abs(th - ref_t) / math.pi) if quantity == "D_xy" else "-",
                         "%d" % solves, r.steps, "%.1f" % r.wall, "%.3f" % r.ms_per_step,
                         "%.2f" % (ref.wall / r.wall)])
            pts.append((label, r.wall, diff / abs(ref_d)))
        print(common.table(header, body) + "\n")
        plots[title] = pts

    # Grid series for the plot: relative difference to the finest grid against wall s.
    def grid_points(rows, col_d, feng=None):
        pts = []
        finest = float(rows[-1][col_d])
        for r in rows[:-1]:
            d = float(r[col_d])
            wall = float(r[-2]) if r[-1] != "steady" else float(r[-3])
            pts.append(("N=%s" % r[0], wall, abs(d - finest) / abs(finest)))
        return pts

    drop_grid = grid_points(drop_rows, 4)
    shear_grid = grid_points(shear_rows, 3)
    if args.no_plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for a, grid_pts, (title, sub_pts), name in (
            (ax[0], drop_grid, list(plots.items())[1], "electric_drop"),
            (ax[1], shear_grid, list(plots.items())[0], "shear_field")):
        xs = [p[1] for p in grid_pts]
        ys = [max(p[2], 1e-7) for p in grid_pts]
        a.loglog(xs, ys, "o-", label="grid refinement (vs finest grid)")
        for lab, x, y in grid_pts:
            a.annotate(lab, (x, max(y, 1e-7)), textcoords="offset points", xytext=(4, 4),
                       fontsize=8)
        sx = [p[1] for p in sub_pts[1:]]
        sy = [max(p[2], 1e-7) for p in sub_pts[1:]]
        a.loglog(sx, sy, "s", label="electric sub-stepping at N=64 (vs every=1)")
        for lab, x, y in sub_pts[1:]:
            a.annotate(lab, (x, max(y, 1e-7)), textcoords="offset points", xytext=(4, -10),
                       fontsize=7)
        a.axvline(sub_pts[0][1], color="gray", ls=":", label="N=64, every=1 (wall)")
        a.set_xlabel("wall time [s] (1 thread, shared 2-core machine)")
        a.set_ylabel("relative difference of %s" % ("D" if name == "electric_drop" else "D_xy"))
        a.set_title(name, fontsize=10)
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    os.makedirs(os.path.dirname(IMG), exist_ok=True)
    fig.savefig(IMG, dpi=110)
    print("plot: %s" % os.path.relpath(IMG, common.REPO))


if __name__ == "__main__":
    main()
