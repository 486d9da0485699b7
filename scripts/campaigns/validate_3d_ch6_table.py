"""The table of scripts/campaigns/validate_3d_ch6.yaml (docs/validation_3d_ehd.md, song2019
ch. 6 in 3D): the report of the former scripts/validate_3d_ch6, from each run's CSV time series.

Per case and the text's Ca_E (the scene's / 3): the steady D_xy and theta/pi (means over the last
unit of time, with the band: the largest deviation from the mean), the time at which D_xy first
comes within 2 % of its steady value, the tank-treading frequency f (turns of the tracked vertex
about the centroid per unit time, from the least-squares slope of its unwrapped phase over the
second half of the run), the deformation along the field D_z and the largest GMRES count of a
solve in the last unit (of the CSV rows; 0: no solve fell on a row), the volume drift and the
time reached. A failed run shows where and why it stopped.

With runs that recorded their sections (record.sections_every), the table also draws, per case,
the section z = z_c in the shear plane at a few times, one panel per Ca_E (Figs. 97-101), into
figures/ch6_shapes_case_<case>.png of the campaign's folder. The reference's statements to
check: a stronger field deforms the capsule more and brings it to its steady shape sooner, and
it tank-treads slightly slower."""
import csv
import math
import os

MODULUS_RATIO = 3.0  # E_s / G_s of the neo-Hookean law: the text's Ca_E times this is the scene's
EPS_R = 3.5
SHAPE_TIMES = (0.1, 0.25, 0.5, 1.0, 2.0)  # and the end of the run


def summarize(rows):
    t = [r["t"] for r in rows]
    t_end = t[-1]
    last = [r for r in rows if r["t"] >= t_end - 1.0]
    d = sum(r["dxy"] for r in last) / len(last)
    th = sum(r["inclination"] for r in last) / len(last) / math.pi
    d_band = max(abs(r["dxy"] - d) for r in last) / max(d, 1e-12)
    th_band = max(abs(r["inclination"] / math.pi - th) for r in last)
    reach = next((r["t"] for r in rows if abs(r["dxy"] - d) <= 0.02 * d), float("nan"))
    half = [r for r in rows if r["t"] >= t_end / 2]
    n = len(half)
    mt = sum(r["t"] for r in half) / n
    mp = sum(r["tt_phase"] for r in half) / n
    slope = sum((r["t"] - mt) * (r["tt_phase"] - mp) for r in half) / sum(
        (r["t"] - mt) ** 2 for r in half)
    return {"d": d, "d_band": d_band, "th": th, "th_band": th_band, "reach": reach,
            "freq": abs(slope) / (2 * math.pi), "d_field": rows[-1]["d_field"],
            "gmres": int(max(r["gmres_iterations"] for r in last)),
            "volume": rows[-1]["area_drift"], "t_end": t_end}


def _sections(run):
    """{t: [(x, y), ...]} of the run's sections.csv (in units of a), {} if none."""
    frames = {}
    path = os.path.join(run.folder, "sections.csv")
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                frames.setdefault(float(r["t"]), []).append((float(r["x"]), float(r["y"])))
    return frames


def draw_shapes(case, runs):
    """One panel per Ca_E: the section z = z_c at a few times (song2019 Figs. 97-101)."""
    frames = [_sections(run) for run in runs]
    if not any(frames):
        return None
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(runs), figsize=(3.2 * len(runs), 3.4), squeeze=False)
    for ax, run, sections in zip(axes[0], runs, frames):
        times = sorted(set(SHAPE_TIMES) | {run.t_end})
        drawn = set()
        for t in times:
            if not sections:
                break
            near = min(sections, key=lambda f: abs(f - t))
            if abs(near - t) > 0.05 or near in drawn:
                continue
            drawn.add(near)
            pts = sections[near] + sections[near][:1]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], lw=1, label="t = %.2g" % near)
        ax.set_title("Ca_E = %s%s" % (run.label, " (stopped)" if run.status == "failed" else ""),
                     fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(-1.5, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=7, loc="lower right")
    fig.suptitle("case %s, Ca = 0.025: the section z = z_c in the shear plane (x, y in a)"
                 % case, fontsize=10)
    fig.tight_layout()
    folder = os.path.join(os.path.dirname(os.path.dirname(runs[0].folder)), "figures")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "ch6_shapes_case_%s.png" % case.lower())
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def table(runs):
    header = ["case", "sigma_r", "Ca_E (text)", "D_xy (steady)", "band", "theta/pi", "band",
              "t to 2 % of D", "f (turns / unit)", "D_z", "GMRES (max, last unit)",
              "volume drift", "t_end"]
    notes = ["Ca = 0.025 (text; 0.075 in the scene's G_s), eps_r = %g; Ca_E the text's (the "
             "scene's is %gx)" % (EPS_R, MODULUS_RATIO), ""]
    body = []
    by_case = {}
    for run in runs:
        case = run.values["case"]
        by_case.setdefault(case, []).append(run)
        cells = [case, "%g" % run.overrides["sigma_r"], run.label]
        rows = run.series()
        if run.status != "ok" or not rows:
            where = " at t = %.3g" % rows[-1]["t"] if rows and run.status == "failed" else ""
            body.append(cells + ["%s%s%s" % (run.status, where, ": " + run.error if run.error
                                             else "")] + ["-"] * 9)
            continue
        s = summarize(rows)
        body.append(cells + ["%.4f" % s["d"], "%.1f %%" % (100 * s["d_band"]), "%.4f" % s["th"],
                             "%.4f" % s["th_band"], "%.2f" % s["reach"], "%.4f" % s["freq"],
                             "%+.4f" % s["d_field"], "%d" % s["gmres"], "%+.1e" % s["volume"],
                             "%g" % s["t_end"]])
    after = []
    for case, case_runs in by_case.items():
        path = draw_shapes(case, case_runs)
        if path:
            after.append("shapes: %s" % path)
    if after:
        after.insert(0, "")
    return header, body, notes, after
