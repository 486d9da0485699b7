#!/usr/bin/env python3
"""Damped tumbling of a biconcave capsule by a DC field (song2019 sec. 5.3.3, Fig. 86):
Ca = 0.0125, E_b = 0.005, Case A (sigma_r = 1.75, eps_r = 3.5). The reference: the capsule
tumbles at Ca_E = 0 (and still at Ca_E = 0.1); the tumbling is completely damped out at
Ca_E = 0.3 (the field aligns the capsule horizontally).

Scene biconcave_shear_field (N = M = 64 here, the shipped 128 is 16x more expensive) with
E_b = 0.005, run to t = T (units of 1/k). The inclination theta in (-pi/2, pi/2] is unwrapped
(a jump by more than pi/2 between samples is a flip through the vertical): a tumbling capsule
keeps turning (unwrapped rotation of several pi, flips), a damped one settles at a fixed theta.

    python3 scripts/validate_ehd_biconcave.py [--until 20] [--ca-e 0,0.1,0.3]
"""
import math

import validate_ehd_common as common


def analyse(rows):
    unwrapped = [rows[0]["inclination"]]
    flips = []
    for prev, r in zip(rows, rows[1:]):
        d = r["inclination"] - prev["inclination"]
        if d > math.pi / 2:
            d -= math.pi
            flips.append(r["t"])
        elif d < -math.pi / 2:
            d += math.pi
            flips.append(r["t"])
        unwrapped.append(unwrapped[-1] + d)
    t_end = rows[-1]["t"]
    late = [(r["inclination"], r["dxy"]) for r in rows if r["t"] >= 0.75 * t_end]
    return unwrapped, flips, late


def main():
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--until", type=float, default=20.0)
    p.add_argument("--ca-e", default="0,0.1,0.3")
    p.add_argument("--e-b", type=float, default=0.005)
    p.add_argument("--n", type=int, default=64)
    p.add_argument("--no-plot", action="store_true")
    args = p.parse_args()
    runs = {}
    for ca in [float(v) for v in args.ca_e.split(",")]:
        suffix = "" if args.until == 20.0 else "_t%g" % args.until
        runs[ca] = common.Run("biconcave_Eb%g_CaE%g_N%d%s" % (args.e_b, ca, args.n, suffix),
                              "biconcave_shear_field",
                              ["E_b=%g" % args.e_b, "Ca_E=%g" % ca, "N=%d" % args.n,
                               "M=%d" % args.n], ["--until", str(args.until)], csv_every=50)
    print("load average before: %s" % " ".join(common.load_average()))
    common.run_all(args, list(runs.values()))
    print("load average after: %s\n" % " ".join(common.load_average()))
    header = ["Ca_E", "flips through vertical", "flip times (1/k)", "net rotation / pi",
              "theta/pi range, last 25%", "D_xy range, last 25%", "motion", "steps", "ms/step"]
    body = []
    curves = {}
    for ca, r in sorted(runs.items()):
        if r.error:
            body.append([ca, "failed: " + r.error] + [""] * 7)
            continue
        unwrapped, flips, late = analyse(r.rows)
        curves[ca] = ([row["t"] for row in r.rows], [u / math.pi for u in unwrapped])
        th = [x[0] / math.pi for x in late]
        dx = [x[1] for x in late]
        rot = (unwrapped[-1] - unwrapped[0]) / math.pi
        # A flip through the vertical is a tumbling half-turn; without one the capsule either
        # settles (theta range < 0.02 pi over the last quarter) or swings without turning over.
        motion = ("tumbling (%d half-turns)" % len(flips) if flips else
                  "steady, no flip (tumbling damped)" if max(th) - min(th) < 0.02 else
                  "swinging, no flip")
        body.append([ca, len(flips), ", ".join("%.2f" % t for t in flips[:6]) or "-",
                     "%+.3f" % rot, "%.4f .. %.4f" % (min(th), max(th)),
                     "%.4f .. %.4f" % (min(dx), max(dx)), motion, r.steps,
                     "%.3f" % r.ms_per_step])
    print(common.table(header, body))
    if args.no_plot or not curves:
        return
    import os
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 3.8))
    for ca, (t, u) in sorted(curves.items()):
        ax.plot(t, u, label="Ca_E = %g" % ca)
    ax.set_xlabel("t k")
    ax.set_ylabel("unwrapped inclination theta / pi")
    ax.set_title("biconcave capsule, Ca = 0.0125, E_b = %g, Case A, N = %d" % (args.e_b, args.n),
                 fontsize=9)
    name = "biconcave_tumbling%s.png" % ("" if args.until == 20.0 else "_t%g" % args.until)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = os.path.join(common.REPO, "docs", "img", name)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    fig.savefig(out, dpi=110)
    print("plot: docs/img/" + name)


if __name__ == "__main__":
    main()
