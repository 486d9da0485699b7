#!/usr/bin/env python3
"""Feng's small-deformation theory for a 2D leaky-dielectric drop (song2019 sec. 4.2.2):

    D = (sigma_r^2 + sigma_r + 1 - 3 eps_r) / (3 (1 + sigma_r)^2) Ca_E

(first order in Ca_E, unbounded domain; D > 0: major axis along the field E_inf = (0, -E), i.e.
prolate; D < 0: across it, oblate). Runs scene electric_drop (Oh = 1, no shear) for Cases A, B, C
(sigma_r = 1.75, 3.25, 4.75; eps_r = 3.5) over Ca_E and grids, to t = 15 mu a / gamma (the
D relaxation time is about 2.5 units: D changes by < 0.1% over the last 5 units), and prints

  * the steady signed D against Feng (relative error, sign check),
  * the box-size check (L/a = 8 against L/a = 4 at the same a = 8 cells),
  * the sense of the induced circulation inside the drop in the first quadrant (sign of the
    vorticity integrated over x > 0, y > 0, r < 0.9 a of the last VTK frame).

Regenerates the tables of docs/validation_ehd.md section 1:
    python3 scripts/validate_ehd_feng.py [--work DIR] [--jobs 2]
"""
import math

import validate_ehd_common as common

CASES = {"A": 1.75, "B": 3.25, "C": 4.75}
EPS_R = 3.5
T_END = 15.0


def feng(sigma_r, ca_e, eps_r=EPS_R):
    return (sigma_r ** 2 + sigma_r + 1 - 3 * eps_r) / (3 * (1 + sigma_r) ** 2) * ca_e


def key(case, ca_e, n, half_width):
    return "feng_%s_CaE%g_N%d_L%g" % (case, ca_e, n, half_width)


def make_run(case, ca_e, n, half_width):
    a = n / (2 * half_width)
    steps = int(T_END * 6 * a * a)  # time unit mu a / gamma = 6 a^2 steps at tau = 1, Oh = 1
    return common.Run(key(case, ca_e, n, half_width), "electric_drop",
                      ["sigma_r=%g" % CASES[case], "eps_r=%g" % EPS_R, "Ca_E=%g" % ca_e,
                       "N=%d" % n, "M=%d" % n, "geometry.half_width=%g" % half_width],
                      ["--until", str(T_END)], vtk_every=max(1, steps // 3), csv_every=20)


def first_quadrant_circulation(run):
    nx, ny, origin, h, ux, uy = common.read_vti_velocity(common.last_vti(run.vtk_dir))
    total = 0.0
    for j in range(1, ny - 1):
        y = origin[1] + j * h
        for i in range(1, nx - 1):
            x = origin[0] + i * h
            if x > 0 and y > 0 and x * x + y * y < 0.81:
                w = (uy[j][i + 1] - uy[j][i - 1] - ux[j + 1][i] + ux[j - 1][i]) / (2 * h)
                total += w * h * h
    return total


def main():
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--ca-e", default="0.05,0.1,0.2,0.4")
    p.add_argument("--fine-ca-e", default="0.05,0.2", help="Ca_E values also run at N = 128")
    p.add_argument("--skip-fine", action="store_true")
    p.add_argument("--skip-256", action="store_true",
                   help="skip the N = 256 runs of Case C at Ca_E = 0.2 (L/a = 8 with a = 16 "
                   "cells: resolution in the large box; L/a = 16 with a = 8: box size)")
    args = p.parse_args()
    ca_list = [float(v) for v in args.ca_e.split(",")]
    fine_list = [] if args.skip_fine else [float(v) for v in args.fine_ca_e.split(",")]
    runs = {}
    for case in CASES:
        for ca in ca_list:
            runs[(case, ca, 64, 4)] = make_run(case, ca, 64, 4)
        for ca in fine_list:
            runs[(case, ca, 128, 4)] = make_run(case, ca, 128, 4)
            runs[(case, ca, 128, 8)] = make_run(case, ca, 128, 8)
    if not args.skip_256:
        runs[("C", 0.2, 256, 8)] = make_run("C", 0.2, 256, 8)
        runs[("C", 0.2, 256, 16)] = make_run("C", 0.2, 256, 16)
    print("load average before: %s" % " ".join(common.load_average()))
    common.run_all(args, list(runs.values()))
    print("load average after: %s\n" % " ".join(common.load_average()))

    header = ["case", "sigma_r", "Ca_E", "N", "L/a", "a (cells)", "D Feng", "D (t=15)",
              "D (t=10)", "sign", "rel. err", "steps", "wall s", "ms/step"]
    body = []
    for (case, ca, n, hw), r in sorted(runs.items(), key=lambda kv: (kv[0][0], kv[0][3],
                                                                      kv[0][2], kv[0][1])):
        theory = feng(CASES[case], ca)
        if r.error:
            body.append([case, CASES[case], ca, n, hw, n / (2 * hw), "%.5f" % theory,
                         "failed: " + r.error] + [""] * 6)
            continue
        d = common.signed_d(r.rows[-1])
        d10 = common.signed_d(common.row_at(r.rows, 10.0))
        sign_ok = "ok" if d * theory > 0 else "WRONG"
        shape = "prolate" if d > 0 else "oblate"
        body.append([case, CASES[case], ca, n, hw, "%g" % (n / (2 * hw)), "%+.5f" % theory,
                     "%+.5f" % d, "%+.5f" % d10, "%s %s" % (shape, sign_ok),
                     "%+.1f%%" % (100 * (d - theory) / theory), r.steps, "%.1f" % r.wall,
                     "%.3f" % r.ms_per_step])
    print(common.table(header, body))

    print("\nInduced circulation inside the drop, first quadrant (x > 0, y > 0, r < 0.9 a), "
          "at t = 15; sum of vorticity x area (lattice units), > 0 counter-clockwise:\n")
    header = ["case", "sigma_r vs eps_r", "Ca_E", "N", "L/a", "circulation", "sense",
              "Taylor: sign(sigma_r - eps_r)"]
    body = []
    for (case, ca, n, hw), r in sorted(runs.items()):
        if r.error or n != 64:
            continue
        c = first_quadrant_circulation(r)
        expect = "counter-clockwise" if CASES[case] > EPS_R else "clockwise"
        sense = "counter-clockwise" if c > 0 else "clockwise"
        body.append([case, "%g %s %g" % (CASES[case], "<" if CASES[case] < EPS_R else ">", EPS_R),
                     ca, n, hw, "%+.3e" % c, sense, expect + (" ok" if sense == expect else
                                                              " MISMATCH")])
    print(common.table(header, body))


if __name__ == "__main__":
    main()
