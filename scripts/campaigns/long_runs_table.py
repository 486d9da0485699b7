"""The table of scripts/campaigns/long_runs.yaml (docs/validation_ehd.md section 7), from each
run's CSV time series (second half of the run) and its summary (error, wall time).

  steady     band within +-0.5 % (D) and +-0.002 pi (theta)
  periodic   a bounded oscillation (tumbling, swinging): its period from the zero crossings of
             theta - mean (or of D - mean)
  drifting   neither: the run ended but has not settled
  FAILED     the run stopped early (watchdog, solver error): the message

A 3D drop in a field without shear is judged by its deformation along the field, D_z (marked
so), its D_xy being zero."""
import math


def crossings_period(ts, values):
    """Mean period from the upward zero crossings of values (None if fewer than 3)."""
    ups = [ts[i] for i in range(1, len(values)) if values[i - 1] < 0 <= values[i]]
    if len(ups) < 3:
        return None
    return (ups[-1] - ups[0]) / (len(ups) - 1)


def summarize(run):
    rows = run.series()
    scene = run.values["scene"]
    wall = "%.1f" % run.wall_s if run.wall_s is not None else ""
    if not run.finished:
        return dict(scene=scene, t="%.4g" % rows[-1]["t"] if rows else "-",
                    verdict=run.status, error="", wall=wall)
    if not rows:
        return dict(scene=scene, t="-", verdict="FAILED", error=run.error or "no time series",
                    wall=wall)
    t_end = rows[-1]["t"]
    tail = [r for r in rows if r["t"] >= 0.5 * t_end]
    ts = [r["t"] for r in tail]
    key = "dxy"
    if "d_field" in tail[0]:
        def mean_abs(k):
            return sum(abs(r[k]) for r in tail) / len(tail)
        if mean_abs("d_field") > 10 * mean_abs("dxy"):
            key = "d_field"
    d = [r[key] for r in tail]
    th = [r["inclination"] / math.pi for r in tail]
    d_mean, th_mean = sum(d) / len(d), sum(th) / len(th)
    d_band = max(abs(x - d_mean) for x in d) / max(abs(d_mean), 1e-12)
    th_band = max(abs(x - th_mean) for x in th)
    if key == "d_field":
        # The shear-plane section is a circle to D_xy ~ 1e-4: its inclination is undefined (it
        # flips with rounding), so it neither judges the run nor is printed.
        th_band = 0.0
    if run.status == "failed":
        verdict = "FAILED"
    elif d_band <= 0.005 and th_band <= 0.002:
        verdict = "steady"
    else:
        period = crossings_period(ts, [x - th_mean for x in th]) or crossings_period(
            ts, [x - d_mean for x in d])
        # Bounded periodic motion: the band of the last quarter matches the band of the half.
        quarter = [r[key] for r in rows if r["t"] >= 0.75 * t_end]
        q_band = max(abs(x - d_mean) for x in quarter) / max(abs(d_mean), 1e-12)
        if period is not None and q_band > 0.5 * d_band:
            verdict = "periodic (period %.3g)" % period
        else:
            verdict = "drifting"
    label = "%.5f" % d_mean + (" (D_z)" if key == "d_field" else "")
    return dict(scene=scene, t="%.4g" % t_end, d=label, d_band="%.2f" % (100 * d_band),
                th="%.4f" % th_mean if key == "dxy" else "-",
                th_band="%.4f" % th_band if key == "dxy" else "-",
                drift="%.2e" % rows[-1]["area_drift"], wall=wall, verdict=verdict,
                error=run.error if run.status == "failed" else "")


def table(runs):
    header = ["scene", "t reached", "D_xy (mean, 2nd half)", "D band %", "theta/pi",
              "theta band (/pi)", "area drift", "wall s", "verdict"]
    body = []
    for run in runs:
        r = summarize(run)
        body.append([r["scene"], r["t"], r.get("d", "-"), r.get("d_band", "-"), r.get("th", "-"),
                     r.get("th_band", "-"), r.get("drift", "-"), r["wall"],
                     r["verdict"] + ((": " + r["error"]) if r["error"] else "")])
    return header, body
