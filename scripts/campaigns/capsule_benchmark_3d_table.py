"""The table of scripts/campaigns/capsule_benchmark_3d.yaml (docs/validation_3d.md): D_xy at
t = 1, 2, 3, 4 (1/k) from the run's CSV time series (linear interpolation between rows) and its
relative error against Ramanujan & Pozrikidis (1998), boundary-integral, unbounded shear, at the
papers' Ca = mu k a / E_s (the scene's Ca / 3). The reference values are read at those times off
the curves that D. Huet digitized from the paper's figure for his Basilisk capsule tests
(github.com/comphy-lab/basilisk-C, basilisk-wiki/sandbox/huet/tests/lagrangian_caps/data/
nh_shear_3d/pozrikidis1998_ca_*.csv), accurate to about +-0.003; the Ca = 0.025 curve ends at
t = 1.4. Walls at +-4a here (Doddi & Bagchi 2008 and Huet use the same; R&P are unbounded)."""

TIMES = (1.0, 2.0, 3.0, 4.0)
# Papers' Ca -> D at t = 1, 2, 3, 4 (None: beyond the digitized curve).
RAMANUJAN_POZRIKIDIS_1998 = {
    0.025: (0.1437, None, None, None),
    0.05: (0.2299, 0.2610, 0.2638, 0.2613),
    0.1: (0.3055, 0.3765, 0.3857, 0.3857),
    0.2: (0.3613, 0.4804, 0.5063, 0.5063),
}


def _at(rows, t):
    for a, b in zip(rows, rows[1:]):
        if a["t"] <= t <= b["t"]:
            w = (t - a["t"]) / (b["t"] - a["t"]) if b["t"] > a["t"] else 0.0
            return a["dxy"] + w * (b["dxy"] - a["dxy"])
    return None


def table(runs):
    header = ["immersed boundary", "Ca (papers')", "a (cells)"]
    for t in TIMES:
        header += ["D(%g)" % t, "R&P", "error"]
    header += ["theta/pi (4)", "wall s"]
    body = []
    for run in runs:
        ca = run.overrides["Ca"] / 3.0
        radius = run.overrides["N"] / (2.0 * run.overrides["geometry.half_width"])
        retraction = run.overrides["numerics.ib_retraction"]
        kernel = run.overrides.get("numerics.ib_kernel", "roma3")
        cells = ["%s, retracted %g h" % (kernel, retraction) if retraction > 0
                 else "%s, at the points (song2019)" % kernel, "%g" % ca, "%g" % radius]
        if run.status != "ok":
            body.append(cells + ["%s: %s" % (run.status, run.error) if run.error
                                 else run.status] + [""] * (3 * len(TIMES) + 1))
            continue
        rows = run.series()
        reference = RAMANUJAN_POZRIKIDIS_1998.get(round(ca, 6), (None,) * len(TIMES))
        for t, ref in zip(TIMES, reference):
            d = _at(rows, t)
            cells += ["%.4f" % d if d is not None else "-",
                      "%.4f" % ref if ref is not None else "-",
                      "%+.1f %%" % (100 * (d / ref - 1)) if d is not None and ref else "-"]
        cells += ["%.4f" % run.final["inclination_over_pi"], "%.0f" % run.wall_s]
        body.append(cells)
    return header, body
