"""The table of scripts/campaigns/validate_3d.yaml (docs/validation_3d.md): the report of the
former scripts/validate_3d, from each run's CSV time series and summary.

The steady D_xy and theta are the means over the last unit of time (t in [T-1, T]) with their
band (max deviation from the mean: D relative in %, theta in units of pi). Theory (unbounded,
Stokes, first order in Ca):

  capsule (neo-Hookean, Barthes-Biesel & Rallison 1981)  D = (25/4) mu k a / E_s, E_s = 3 G_s,
          i.e. D = (25/12) Ca with the scenes' Ca = mu k a / G_s; theta -> pi/4 as Ca -> 0
  drop (viscosity ratio 1, Taylor 1934)                   D = (35/32) Ca, Ca = mu k a / gamma;
          theta = pi/4 - (2l+3)(19l+16)/(80(l+1)) Ca = pi/4 - (35/32) Ca   (l = 1)

For each series with three or more resolutions: the observed order p from the last three
(D(a) = D_inf + C a^-p solved exactly, no theory used), the extrapolated D_inf and its ratio to
the theory, and the order of the error against the theory from the last two. Then the box effect
(L/a = 3 against 5, and the wall-free value of an (a/L)^3 extrapolation), the capsule's dD/dCa
from the two small Ca at each resolution (the tank-treading fluctuation cancels in the
difference), the published finite-Ca values and the long runs.

A run's case comes from its variant name (group-...: capsule, drop, box, mesh, published, long),
its membrane, Ca, a = N / (2 L/a), L/a, mesh level and immersed boundary from its overrides
(numerics.ib_retraction 0: at the points; not set: the default, retracted). The vertices and
the mean edge are the icosphere's (10 4^level + 2 vertices; edge ~ a (8 pi / (sqrt(3) (M - 2)))
^ 1/2, the estimate ehd_sim prints). Runs not finished or not run are shown as such, their
values as '-', and are left out of the series (a running one is tabulated with its mean so
far)."""
import math

LONG_FROM = 2.0     # long runs: statistics over t in [LONG_FROM, T]

# Steady D of the neo-Hookean capsule at Ca_E = mu k a / E_s = Ca / 3 (E_s = 3 G_s, the modulus
# of Ramanujan & Pozrikidis 1998 and Doddi & Bagchi 2008), read off the end of the curves
# digitized from their figures in D. Huet's Basilisk sandbox (github comphy-lab/basilisk-C,
# basilisk-wiki/sandbox/huet/tests/lagrangian_caps/data/nh_shear_3d/{bagchi_ca*,
# pozrikidis1998_ca_*}.csv; his neo-Hookean law there is dW/dl1 = E_S/(3 l1)(l1^2 - 1/(l1 l2)^2),
# i.e. E_S = 3 G_s, and it is plotted against both at the same Ca). Second-hand values (figure
# digitization, about +-0.003): to be checked against the papers' own tables.
PUBLISHED = {
    0.0375: [("Doddi & Bagchi 2008", 0.083)],
    0.075: [("Doddi & Bagchi 2008", 0.162), ("Ramanujan & Pozrikidis 1998", 0.150)],
    0.15: [("Doddi & Bagchi 2008", 0.278), ("Ramanujan & Pozrikidis 1998", 0.261)],
}
SLOPE_THEORY = 25.0 / 12.0


def subdivisions(a):
    """Icosphere level keeping the mean edge at 0.45-0.6 cells (0.15 a at level 3, halved
    per level)."""
    return 3 if a <= 4 else (4 if a <= 8 else 5)


def theory(membrane, ca):
    """(D, theta/pi) of the unbounded small-deformation theory; theta None where only the
    leading order pi/4 is known here."""
    if membrane == "capsule":
        return 25.0 / 12.0 * ca, 0.25
    return 35.0 / 32.0 * ca, 0.25 - 35.0 / 32.0 * ca / math.pi


def _fmt(x, spec, none="-"):
    return none if x is None else spec % x


def _boundary(at_points):
    return "at the points" if at_points else "retracted (default)"


def summarize(run):
    """The old script's summary of a run: its case, its status and, from t >= 1 on, the
    steady means over the last unit of time."""
    o = run.overrides
    half_width, n, level = o["geometry.half_width"], o["N"], o["mesh_subdivisions"]
    membrane = o.get("membrane", "capsule")
    vertices = 10 * 4 ** level + 2
    r = dict(group=run.values["variant"].split("-")[0], membrane=membrane, ca=o["Ca"],
             a=n / (2.0 * half_width), half_width=half_width, N=n, subdiv=level,
             at_points=o.get("numerics.ib_retraction") == 0, until=run.t_end,
             vertices=vertices, wall=run.wall_s, error=run.error, status=run.status,
             done=run.status == "ok")
    r["edge"] = r["a"] * math.sqrt(8.0 * math.pi / (math.sqrt(3.0) * (vertices - 2)))
    r["theory_d"], r["theory_th"] = theory(membrane, r["ca"])
    rows = run.series()
    r["t"] = rows[-1]["t"] if rows else 0.0
    if not rows or r["t"] < 1.0:
        r["d"] = None
        return r
    tail = [x for x in rows if x["t"] >= r["t"] - 1.0 - 1e-9]
    d = [x["dxy"] for x in tail]
    th = [x["inclination"] / math.pi for x in tail]
    r["d"] = sum(d) / len(d)
    r["th"] = sum(th) / len(th)
    r["d_band"] = max(abs(x - r["d"]) for x in d) / max(abs(r["d"]), 1e-12)
    r["th_band"] = max(abs(x - r["th"]) for x in th)
    # Drift of the mean between the second-last and the last unit: is it steady?
    prev = [x["dxy"] for x in rows if r["t"] - 2.0 - 1e-9 <= x["t"] < r["t"] - 1.0 - 1e-9]
    r["d_prev"] = sum(prev) / len(prev) if prev else None
    r["vol_drift"] = rows[-1]["area_drift"]
    r["rows"] = rows
    long_tail = [x["dxy"] for x in rows if x["t"] >= LONG_FROM - 1e-9]
    if r["t"] >= LONG_FROM + 4.0:
        r["d_long"] = sum(long_tail) / len(long_tail)
        r["d_min"], r["d_max"] = min(long_tail), max(long_tail)
    else:
        r["d_long"] = None
    r["err"] = r["d"] / r["theory_d"] - 1.0
    return r


def observed_order(a, d):
    """p, D_inf with D(a_i) = D_inf + C a_i^-p through three points (a increasing); None if the
    differences do not shrink monotonically."""
    (a1, a2, a3), (d1, d2, d3) = a, d
    if (d1 - d2) * (d2 - d3) <= 0:
        return "oscillates", None
    target = (d1 - d2) / (d2 - d3)

    def g(p):
        return (a1 ** -p - a2 ** -p) / (a2 ** -p - a3 ** -p) - target

    lo, hi = 1e-3, 12.0
    if g(lo) * g(hi) > 0:
        return "differences grow", None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    cst = (d2 - d3) / (a2 ** -p - a3 ** -p)
    return p, d3 - cst * a3 ** -p


def wall_free(d3, d5, l3=3.0, l5=5.0):
    """D without walls from two box sizes, assuming a wall effect ~ (a/L)^3."""
    w3, w5 = l3 ** -3, l5 ** -3
    return d5 - (d3 - d5) * w5 / (w3 - w5)


def paired_slope(r1, r2, t0, t1):
    """Mean and band (relative max deviation) of (D2(t) - D1(t)) / (Ca2 - Ca1) over t in
    [t0, t1], the two runs matched step by step (same a: same time step and csv rows)."""
    d1 = {x["step"]: x["dxy"] for x in r1["rows"] if t0 - 1e-9 <= x["t"] <= t1 + 1e-9}
    diffs = [(x["dxy"] - d1[x["step"]]) / (r2["ca"] - r1["ca"])
             for x in r2["rows"] if x["step"] in d1]
    if not diffs:
        return None, None
    mean = sum(diffs) / len(diffs)
    return mean, max(abs(x - mean) for x in diffs) / abs(mean)


def _label(r):
    label = r["membrane"] + {"capsule": "", "drop": "", "box": ", box", "mesh": ", mesh",
                             "published": " (finite Ca)",
                             "long": ", to t = %g" % r["until"]}.get(r["group"], "")
    return label + (", at the points" if r["at_points"] else "")


def main_rows(results):
    body = []
    for r in results:
        theory_th = "%.4f" % r["theory_th"] if r["membrane"] == "drop" else "0.25 (Ca -> 0)"
        cells = [_label(r), "%g" % r["ca"], "%g" % r["a"], "%g" % r["half_width"], "%d" % r["N"],
                 "%d" % r["vertices"], "%.2f" % r["edge"]]
        if r["d"] is None:
            if r["status"] == "ok":
                status = "ok, t = %.3g: no unit of time to average" % r["t"]
            else:
                status = "%s: %s" % (r["status"], r["error"]) if r["error"] else r["status"]
            body.append(cells + [status, "-", "%.5f" % r["theory_d"], theory_th, "-", "-",
                                 _fmt(r["wall"], "%.0f")])
            continue
        note = "" if r["done"] else " (t = %.3g, %s)" % (r["t"], r["status"].split(" ")[0])
        if r["error"]:
            note = " (stopped: %s)" % r["error"]
        body.append(cells + ["%.5f (%.2f)" % (r["d"], 100 * r["d_band"]),
                             "%.4f (%.4f)" % (r["th"], r["th_band"]), "%.5f" % r["theory_d"],
                             theory_th, "%+.1f %%" % (100 * r["err"]), "%.1e" % r["vol_drift"],
                             _fmt(r["wall"], "%.0f") + note])
    return body


def published_lines(results):
    pub = [r for r in results if r["membrane"] == "capsule" and r["ca"] in PUBLISHED
           and r["d"] is not None and r["half_width"] == 3]
    if not pub:
        return []
    lines = ["", "| Ca (G_s) | Ca_E = Ca/3 (E_s) | a (cells) | immersed boundary | steady D_xy "
             "| theta/pi | linear (25/12) Ca | published D (digitized) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in sorted(pub, key=lambda r: (r["ca"], r["at_points"], r["a"])):
        lines.append("| %g | %.4g | %g | %s | %.4f | %.4f | %.4f | %s |" % (
            r["ca"], r["ca"] / 3, r["a"], _boundary(r["at_points"]), r["d"], r["th"],
            r["theory_d"], "; ".join("%s %.3f" % (who, d) for who, d in PUBLISHED[r["ca"]])))
    return lines


def series_lines(results):
    """Convergence series: the capsule and drop groups at L/a = 3, by (membrane, Ca, immersed
    boundary)."""
    series = {}
    for r in results:
        if r["group"] in ("capsule", "drop") and r["d"] is not None and r["done"]:
            series.setdefault((r["membrane"], r["ca"], r["at_points"]), []).append(r)
    if not series:
        return []
    lines = ["", "| series | resolutions a | D_xy | observed order p (last three) | extrapolated "
             "D_inf | D_inf / theory | error order vs theory (last two) | steady? (last-unit "
             "mean change, %) |", "|---|---|---|---|---|---|---|---|"]
    for (membrane, ca, at_points), rs in sorted(series.items()):
        rs.sort(key=lambda r: r["a"])
        a = [r["a"] for r in rs]
        d = [r["d"] for r in rs]
        th_d = rs[0]["theory_d"]
        p = dinf = p_th = None
        if len(rs) >= 3:
            p, dinf = observed_order(a[-3:], d[-3:])
        if len(rs) >= 2:
            e2, e3 = d[-2] - th_d, d[-1] - th_d
            if e2 * e3 > 0 and abs(e3) < abs(e2):
                p_th = math.log(e2 / e3) / math.log(a[-1] / a[-2])
        changes = [abs(r["d"] / r["d_prev"] - 1.0) for r in rs if r["d_prev"]]
        if len(rs) >= 3 and not isinstance(p, str) and abs(d[-2] - d[-1]) < 2 * max(
                r["d_band"] * r["d"] for r in rs[-2:]):
            p = "%.2f (last difference below 2x the band: not meaningful)" % p
        lines.append("| %s Ca = %g%s | %s | %s | %s | %s | %s | %s | %s |" % (
            membrane, ca, ", at the points" if at_points else "",
            ", ".join("%g" % x for x in a), ", ".join("%.5f" % x for x in d),
            p if isinstance(p, str) else _fmt(p, "%.2f"), _fmt(dinf, "%.5f"),
            _fmt(dinf / th_d if dinf else None, "%.3f"), _fmt(p_th, "%.2f"),
            _fmt(100 * max(changes) if changes else None, "%.2f")))
    return lines


def box_lines(results):
    by = {}
    for r in results:
        if r["group"] in ("capsule", "drop", "box") and r["d"] is not None and r["done"] \
                and r["subdiv"] == subdivisions(r["a"]):
            by.setdefault((r["membrane"], r["ca"], r["a"], r["at_points"]), {})[
                r["half_width"]] = r
    rows = [(k, v) for k, v in sorted(by.items()) if 3 in v and 5 in v]
    if not rows:
        return []
    lines = ["", "| box effect | Ca | a (cells) | D_xy, L/a = 3 | D_xy, L/a = 5 | change | no "
             "walls, (a/L)^3 extrapolation | / theory |", "|---|---|---|---|---|---|---|---|"]
    for (membrane, ca, a, at_points), v in rows:
        d3, d5 = v[3]["d"], v[5]["d"]
        dw = wall_free(d3, d5)
        lines.append("| %s%s | %g | %g | %.5f | %.5f | %+.1f %% | %.5f | %.3f |" % (
            membrane, ", at the points" if at_points else "", ca, a, d3, d5,
            100 * (d5 / d3 - 1), dw, dw / v[3]["theory_d"]))
    return lines


def slope_lines(results, at_points):
    """dD/dCa of the capsule from the two small Ca at each resolution (same time window): the
    tank-treading fluctuation of D, the same at both Ca, cancels in the difference."""
    by_a = {}
    for r in results:
        if r["group"] in ("capsule", "box") and r["membrane"] == "capsule" \
                and r["at_points"] == at_points and r["d"] is not None and r["done"] \
                and r["ca"] in (0.005, 0.0125):
            by_a.setdefault((r["half_width"], r["a"]), {})[r["ca"]] = r
    rows = []
    for hw, a in sorted(by_a):
        cas = sorted(by_a[(hw, a)])
        if len(cas) < 2:
            continue
        r1, r2 = by_a[(hw, a)][cas[0]], by_a[(hw, a)][cas[-1]]
        t1 = min(r1["t"], r2["t"])
        slope, band = paired_slope(r1, r2, t1 - 1.0, t1)
        if slope is None:
            continue
        rows.append((hw, a, cas[0], cas[-1], slope, band, r1["edge"]))
    if not rows:
        return []
    theory_slope = SLOPE_THEORY
    lines = ["", "| capsule dD/dCa from Ca = %g and %g (mean over the last unit of time), "
             "immersed boundary %s | L/a | a (cells) | slope (band %%) | slope / (25/12) - 1 |" % (
                 rows[0][2], rows[0][3], _boundary(at_points)), "|---|---|---|---|---|"]
    for hw, a, c1, c2, slope, band, _ in rows:
        lines.append("| | %g | %g | %.4f (%.1f) | %+.1f %% |" % (
            hw, a, slope, 100 * band, 100 * (slope / theory_slope - 1)))
    walls = {}
    for hw, a, _, _, slope, _, _ in rows:
        walls.setdefault(a, {})[hw] = slope
    free = [(a, wall_free(v[3], v[5])) for a, v in sorted(walls.items()) if 3 in v and 5 in v]
    for a, sw in free:
        lines.append("| no walls, (a/L)^3 extrapolation from L/a = 3 and 5 | | %g | %.4f | "
                     "%+.1f %% |" % (a, sw, 100 * (sw / theory_slope - 1)))
    if len(free) >= 2:
        (a1, s1), (a2, s2) = free[-2:]
        e1, e2 = s1 / theory_slope - 1, s2 / theory_slope - 1
        e_inf = (a2 * e2 - a1 * e1) / (a2 - a1)
        lines.append("| no walls, first-order fit error = e_inf + C/a through a = %g, %g: "
                     "e_inf = %+.1f %% | | | | |" % (a1, a2, 100 * e_inf))
    rows = [x[1:] for x in rows if x[0] == 3]
    # Pairs a, 2a with the same mesh edge / h: the error order without the mesh-ratio change.
    for a1, _, _, s1, _, e1 in rows:
        for a2, _, _, s2, _, e2 in rows:
            if a2 == 2 * a1 and e1 and e2 and abs(e1 / e2 - 1) < 0.05:
                r1, r2 = s1 - theory_slope, s2 - theory_slope
                if r1 * r2 > 0:
                    lines.append("| equal edge/h = %.2f: a = %g -> %g, error order vs 25/12 "
                                 "%.2f; first-order fit error = e_inf + C/a: e_inf = %+.1f %% "
                                 "| | | | |" % (e1, a1, a2, math.log(r1 / r2) / math.log(2.0),
                                                100 * (2 * r2 - r1) / theory_slope))
    rows = [x[:5] for x in rows]
    if len(rows) >= 3:
        a = [x[0] for x in rows[-3:]]
        d = [x[3] for x in rows[-3:]]
        p, dinf = observed_order(a, d)
        e2, e3 = d[-2] - theory_slope, d[-1] - theory_slope
        p_th = math.log(e2 / e3) / math.log(a[-1] / a[-2]) if e2 * e3 > 0 and abs(e3) < abs(
            e2) else None
        lines.append("| last three: observed order %s, extrapolated slope %s (%s x 25/12); "
                     "error order vs 25/12 from the last two %s (L/a = 3) | | | | |" % (
                         p if isinstance(p, str) else _fmt(p, "%.2f"), _fmt(dinf, "%.4f"),
                         _fmt(dinf / theory_slope if dinf else None, "%.3f"),
                         _fmt(p_th, "%.2f")))
    return lines


def long_lines(results):
    longs = [r for r in results if r["group"] == "long" and r["d"] is not None
             and r.get("d_long") is not None]
    if not longs:
        return []
    lines = ["", "| capsule, long run | Ca | a (cells) | t reached | mean D_xy, t in [%g, T] "
             "| min .. max | half range / mean | theory D | mean / theory - 1 |" % LONG_FROM,
             "|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(longs, key=lambda r: (r["a"], r["ca"])):
        lines.append("|%s| %g | %g | %.3g | %.5f | %.5f .. %.5f | %.1f %% | %.5f | %+.1f %% |" % (
            " at the points " if r["at_points"] else " ", r["ca"], r["a"], r["t"], r["d_long"],
            r["d_min"], r["d_max"], 50 * (r["d_max"] - r["d_min"]) / r["d_long"],
            r["theory_d"], 100 * (r["d_long"] / r["theory_d"] - 1)))
    by_a = {}
    for r in longs:
        by_a.setdefault((r["a"], r["at_points"]), []).append(r)
    for (a, _), rs in sorted(by_a.items()):
        if len(rs) == 2:
            rs.sort(key=lambda r: r["ca"])
            slope, band = paired_slope(rs[0], rs[1], LONG_FROM, min(rs[0]["t"], rs[1]["t"]))
            if slope is None:
                continue
            lines.append("| dD/dCa, t in [%g, T] | %g, %g | %g | | %.4f | band %.1f %% | | "
                         "%.4f | %+.1f %% |" % (LONG_FROM, rs[0]["ca"], rs[1]["ca"], a, slope,
                                                100 * band, SLOPE_THEORY,
                                                100 * (slope / SLOPE_THEORY - 1)))
    return lines


def table(runs):
    results = [summarize(run) for run in runs]
    ends = sorted({r["until"] for r in results if r["group"] != "long"})
    long_ends = sorted({r["until"] for r in results if r["group"] == "long"})
    notes = ["sphere_shear to t = %s%s, means over the last unit of time; immersed boundary "
             "retracted (the default) unless the case says at the points; vertices and edge/h "
             "of the icosphere" % (", ".join("%g" % t for t in ends) or "-", (
                 " (long runs to %s)" % ", ".join("%g" % t for t in long_ends))
             if long_ends else ""), ""]
    header = ["case", "Ca", "a (cells)", "L/a", "N", "vertices", "edge/h", "steady D_xy (band %)",
              "theta/pi (band)", "theory D", "theory theta/pi", "D / theory - 1", "volume drift",
              "wall s"]
    after = published_lines(results) + series_lines(results) + box_lines(results)
    for at_points in (False, True):
        after += slope_lines(results, at_points)
    after += long_lines(results)
    return header, main_rows(results), notes, after
