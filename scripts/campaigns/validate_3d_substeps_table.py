"""The table of scripts/campaigns/validate_3d_substeps.yaml (docs/validation_3d_ehd.md): per
variant D_xy, theta/pi and D_z at the end (from ehd_sim's --summary-json), their differences
from the reference (the first variant), the number of solves (steps whose CSV row has GMRES
iterations > 0), wall seconds, ms per step, and the cost against the run without the field
(the last variant)."""


def _solves(run):
    return sum(1 for r in run.series() if r["gmres_iterations"] > 0)


def table(runs):
    header = ["variant", "D_xy", "dD_xy / D_xy", "theta/pi", "d theta/pi", "D_z", "dD_z / D_z",
              "solves", "wall s", "ms/step", "x no field"]
    done = [r for r in runs if r.status == "ok"]
    ref = runs[0] if runs[0].status == "ok" else None
    free = runs[-1] if runs[-1].status == "ok" else None
    notes = []
    if ref is not None:
        notes = ["sphere_shear_field to t = %g (%d steps)" % (ref.final["t"], ref.final["step"]),
                 ""]
    body = []
    for r in runs:
        if r not in done:
            body.append([r.label, r.status + (": " + r.error if r.error else "")] + [""] * 9)
            continue
        f = r.final
        ms = 1000 * r.wall_s / f["step"]
        if ref is not None:
            rf = ref.final
            rel_d = "%+.1e" % (f["dxy"] / rf["dxy"] - 1)
            d_th = "%+.1e" % (f["inclination_over_pi"] - rf["inclination_over_pi"])
            rel_z = "%+.1e" % (f["d_field"] / rf["d_field"] - 1) if rf["d_field"] else "nan"
        else:
            rel_d = d_th = rel_z = "-"
        x_free = "%.2f" % (ms / (1000 * free.wall_s / free.final["step"])) if free else "-"
        body.append([r.label, "%.5f" % f["dxy"], rel_d, "%.5f" % f["inclination_over_pi"], d_th,
                     "%+.5f" % f["d_field"], rel_z, "%d" % _solves(r), "%.0f" % r.wall_s,
                     "%.2f" % ms, x_free])
    return header, body, notes
