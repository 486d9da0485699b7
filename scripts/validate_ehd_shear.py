#!/usr/bin/env python3
"""Drop (song2019 sec. 4.3, Figs. 27-30) and capsule (sec. 5.1, Figs. 31-51) in simple shear
u = (k y, 0) and a DC field E_inf = (0, -E): Cases A, B, C (sigma_r = 1.75, 3.25, 4.75;
eps_r = 3.5) over Ca_E.

Expected (sec. 4.3, 5.1): D_xy grows with Ca_E; Case A (oblate in a field alone) tilts toward
the flow (theta below its Ca_E = 0 value), Cases B and C (prolate) toward the field (theta above
it, at least initially for C); the time to steady state shortens as Ca_E grows.

Per run: steady D_xy and theta/pi (mean of the last 10% of the run), the time to steady (first
t after which D_xy stays within 1% of its final value and theta within 0.005 pi), and the
tank-treading angular velocity omega / k: the mean over ALL markers of their angular velocity
about the centroid between membrane frames 1/4 time unit apart, averaged over the frames of the
last 40% of the run (< 0: clockwise, the sense of the shear vorticity -k). For a steady shape
whose material markers all follow the same orbit, marker k+1 reaches marker k's position T/M
later, so the mean over markers of the angle advanced in dt is exactly 2 pi dt / T (the phase of
one marker over part of a period is not: its speed varies along the orbit). Tank-treading
period T = 2 pi / |omega| and the normalised frequency of sec. 5.1, f = 4 pi / (k T) =
2 |omega| / k.

Regenerates the tables of docs/validation_ehd.md section 2:
    python3 scripts/validate_ehd_shear.py [--work DIR] [--jobs 2]
"""
import math
import os
import re

import validate_ehd_common as common

CASES = {"A": 1.75, "B": 3.25, "C": 4.75}
EPS_R = 3.5


def analyse(rows):
    t_end = rows[-1]["t"]
    tail = [r for r in rows if r["t"] >= 0.9 * t_end]
    d = sum(r["dxy"] for r in tail) / len(tail)
    theta = sum(r["inclination"] for r in tail) / len(tail)
    t_steady = float("nan")
    for r in reversed(rows):
        if abs(r["dxy"] - d) > 0.01 * abs(d) or abs(r["inclination"] - theta) > 0.005 * math.pi:
            t_steady = r["t"]
            break
    # A steady time in the last 10% of the run means it has not settled: report it as such.
    settled = t_steady < 0.9 * t_end
    drift = max(abs(r["dxy"] - d) for r in tail)
    return d, theta, t_steady, settled, drift


def read_markers(path):
    block = re.search(r"<Points>\s*<DataArray[^>]*>\n(.*?)</DataArray>", open(path).read(),
                      re.S).group(1)
    v = [float(x) for x in block.split()]
    return [(v[3 * k], v[3 * k + 1]) for k in range(len(v) // 3)]


def polygon_centroid(pts):
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    return cx / (3 * a), cy / (3 * a)


def tank_treading(vtk_dir, t_end):
    """Mean over markers of the angular velocity about the centroid (units of k), averaged over
    consecutive frame pairs with t >= 0.6 t_end."""
    pvd = open(os.path.join(vtk_dir, "membrane.pvd")).read()
    frames = [(float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd)]
    frames = [(t, os.path.join(vtk_dir, f)) for t, f in frames if t >= 0.6 * t_end]
    rates = []
    prev = None
    for t, f in frames:
        pts = read_markers(f)
        cx, cy = polygon_centroid(pts)
        ang = [math.atan2(y - cy, x - cx) for x, y in pts]
        if prev is not None and t > prev[0]:
            total = 0.0
            for a0, a1 in zip(prev[1], ang):
                d = a1 - a0
                d -= 2 * math.pi * round(d / (2 * math.pi))
                total += d
            rates.append(total / len(ang) / (t - prev[0]))
        prev = (t, ang)
    return sum(rates) / len(rates) if rates else float("nan")


def main():
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--ca-e", default="0,0.1,0.2,0.3")
    p.add_argument("--drop-extra-ca-e", default="1", help="also run the drop at these Ca_E "
                   "(1: the value of song2019 Figs. 27-29); empty for none")
    p.add_argument("--drop-until", type=float, default=10.0)
    p.add_argument("--capsule-until", type=float, default=8.0)
    p.add_argument("--n", type=int, default=64)
    p.add_argument("--only", choices=["drop", "capsule"], default=None)
    args = p.parse_args()
    ca_list = [float(v) for v in args.ca_e.split(",")]
    runs = {}
    for kind, scene, until in (("drop", "drop_shear_field", args.drop_until),
                               ("capsule", "shear_field", args.capsule_until)):
        if args.only and kind != args.only:
            continue
        a = args.n / 8.0  # L/a = 4
        steps_per_unit = 6.0 * a * a / (0.3 if kind == "drop" else 0.05)  # 1/k = a^2 / (Re nu)
        extra = [float(v) for v in args.drop_extra_ca_e.split(",") if v] if kind == "drop" else []
        for case, sigma in CASES.items():
            for ca in ca_list + extra:
                k = "%s_%s_CaE%g_N%d_tt" % (kind, case, ca, args.n)
                runs[(kind, case, ca)] = common.Run(
                    k, scene, ["sigma_r=%g" % sigma, "eps_r=%g" % EPS_R, "Ca_E=%g" % ca,
                               "N=%d" % args.n, "M=%d" % args.n],
                    ["--until", str(until)], csv_every=20,
                    vtk_every=int(round(steps_per_unit / 4)))
    print("load average before: %s" % " ".join(common.load_average()))
    common.run_all(args, list(runs.values()))
    print("load average after: %s\n" % " ".join(common.load_average()))

    for kind in ("drop", "capsule"):
        keys = [k for k in runs if k[0] == kind]
        if not keys:
            continue
        print("\n%s in shear and field (%s), N = M = %d:\n" % (
            kind, "drop_shear_field: Ca = Re = 0.3" if kind == "drop" else
            "shear_field: Ca = 0.04, Re = 0.05", args.n))
        header = ["case", "Ca_E", "D_xy", "theta/pi", "tilt vs Ca_E=0", "t steady (1/k)",
                  "omega_tt/k", "tt period kT", "f = 4pi/(kT)", "steps", "cpu s"]
        body = []
        cas = sorted(set(k[2] for k in keys))
        for case in CASES:
            base = None
            for ca in cas:
                r = runs[(kind, case, ca)]
                if r.error:
                    body.append([case, ca, "failed: " + r.error] + [""] * 8)
                    continue
                d, theta, ts, settled, _ = analyse(r.rows)
                slope = tank_treading(r.vtk_dir, r.rows[-1]["t"])
                if ca == 0:
                    base = theta
                tilt = "-" if base is None or ca == 0 else (
                    "toward field (+%.4f)" % ((theta - base) / math.pi) if theta > base else
                    "toward flow (%.4f)" % ((theta - base) / math.pi))
                body.append([case, ca, "%.5f" % d, "%.4f" % (theta / math.pi), tilt,
                             ("%.2f" % ts) if settled else "> %.1f (not settled)" % (
                                 0.9 * r.rows[-1]["t"]),
                             "%+.4f" % slope, "%.2f" % (2 * math.pi / abs(slope)) if slope else "-",
                             "%.4f" % (2 * abs(slope)),
                             r.steps, "%.1f" % r.cpu])
        print(common.table(header, body))


if __name__ == "__main__":
    main()
