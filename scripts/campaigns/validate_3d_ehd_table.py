"""The table of scripts/campaigns/validate_3d_ehd.yaml (docs/validation_3d_ehd.md):

    D = 9 Ca_E Phi / (16 (2 + R)^2),
    Phi = R^2 + 1 - 2 Q + 3 (R - Q)(2 + 3 lambda) / (5 (1 + lambda)),
    U = 9 Ca_E (Q - R) / (5 (1 + lambda) (2 + R)^2)   (surface flow U sin(theta) cos(theta))

with R = sigma_r, Q = eps_r = 3.5, lambda = 1. D is the end value of d_field (ehd_sim's
--summary-json); the drift over the last unit, and U (the mean of surface_flow over the last
unit: it is small and noisy step to step), come from the CSV time series."""
EPS_R = 3.5


def taylor(r, q, lam=1.0):
    phi = r * r + 1 - 2 * q + 3 * (r - q) * (2 + 3 * lam) / (5 * (1 + lam))
    return phi, phi * 9.0 / (16.0 * (2 + r) ** 2)


def taylor_flow(r, q, lam=1.0):
    """U / Ca_E of the surface flow U sin(theta) cos(theta)."""
    return 9.0 * (q - r) / (5.0 * (1 + lam) * (2 + r) ** 2)


def table(runs):
    t_end = max((r.final.get("t", 0) for r in runs if r.status == "ok"), default=0)
    header = ["case", "sigma_r", "Ca_E", "L/a", "a (cells)", "Phi", "D Taylor",
              "D (t = %g)" % t_end, "error", "drift last unit", "volume drift", "U Taylor", "U",
              "error"]
    body = []
    for run in runs:
        sigma_r, ca = run.overrides["sigma_r"], run.overrides["Ca_E"]
        box, n = run.overrides["geometry.half_width"], run.overrides["N"]
        radius = n / (2.0 * box)
        phi, slope = taylor(sigma_r, EPS_R)
        cells = [run.label, "%g" % sigma_r, "%g" % ca, "%g" % box, "%g" % radius, "%.3f" % phi,
                 "%.5f" % (slope * ca)]
        if run.status != "ok":
            body.append(cells + ["%s: %s" % (run.status, run.error) if run.error
                                 else run.status] + [""] * 6)
            continue
        rows = run.series()
        end = run.final["t"]
        d = run.final["d_field"]
        earlier = [r["d_field"] for r in rows if r["t"] <= end - 1.0]
        drift = abs(d - earlier[-1]) / max(abs(d), 1e-12) if earlier else float("nan")
        flows = [r["surface_flow"] for r in rows if r["t"] > end - 1.0]
        flow = sum(flows) / len(flows)
        u = taylor_flow(sigma_r, EPS_R) * ca
        body.append(cells + ["%.5f" % d, "%+.1f %%" % (100 * (d / (slope * ca) - 1)),
                             "%.1e" % drift, "%.1e" % run.final["area_drift"], "%+.5f" % u,
                             "%+.5f" % flow, "%+.0f %%" % (100 * (flow / u - 1))])
    return header, body
