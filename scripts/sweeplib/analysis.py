"""Reading `ehd_sim run` time series and reducing them to the final values of a run.

Columns of the CSV (src/io/time_series.cpp): step,t,dxy,inclination,area,tt_phase,area_drift,
ca,ca_e,fe_x,fe_y,gmres_iterations,max_mach. Time t is in units of 1/k with shear.
"""
import collections
import csv
import math

STEADY_WINDOW = 1.0  # units of time, as ehd_sim's SteadyStateMonitor
DXY_FLOOR = 1e-3     # SteadyStateMonitor::kDefaultDxyFloor


def read_series(path):
    """Rows of a time-series CSV as dicts of floats (a truncated last line is dropped)."""
    rows = []
    with open(path) as f:
        reader = csv.DictReader(f)
        for r in reader:
            try:
                rows.append({k: float(v) for k, v in r.items()})
            except (TypeError, ValueError):
                break  # a line cut short by a killed process: only ever the last one
    return rows


def steady_time(rows, tolerance, window=STEADY_WINDOW, floor=DXY_FLOOR):
    """First time t at which D_xy and theta have been steady over [t - window, t]: the range
    of D_xy below tolerance * max(|D_xy(t)|, floor) and the range of theta below
    tolerance * pi. The rule of ehd_sim's `--until-steady` (src/coupling/steady_state.cpp),
    applied to the recorded samples (every csv_every steps) instead of every step. None if
    never."""
    if not rows:
        return None
    queues = {name: collections.deque() for name in ("dmin", "dmax", "tmin", "tmax")}
    first = rows[0]["t"]

    def push(q, t, v, keep_min):
        while q and (q[-1][1] >= v if keep_min else q[-1][1] <= v):
            q.pop()
        q.append((t, v))

    for r in rows:
        t, d, th = r["t"], r["dxy"], r["inclination"]
        push(queues["dmin"], t, d, True)
        push(queues["dmax"], t, d, False)
        push(queues["tmin"], t, th, True)
        push(queues["tmax"], t, th, False)
        cut = t - window
        for q in queues.values():
            while q and q[0][0] < cut:
                q.popleft()
        if first > cut:
            continue
        scale = max(abs(d), floor)
        if (queues["dmax"][0][1] - queues["dmin"][0][1] < tolerance * scale and
                queues["tmax"][0][1] - queues["tmin"][0][1] < tolerance * math.pi):
            return t
    return None


def tank_treading_frequency(rows):
    """f = 4 pi / (k T) (song2019 sec. 5.1, Figs. 49-51; T the period of a membrane point's
    turn) from the CSV column tt_phase (the unwrapped angle of one material marker about the
    centroid), t in units of 1/k: f = 2 |mean d tt_phase / dt|. A point on an elongated
    membrane does not turn at a uniform rate, so the mean is taken over whole turns: the last
    complete turn(s) of the second half of the run, or the last complete turn if the second half
    holds less than one. A run with less than one turn in all gets the least-squares slope
    over its second half (an estimate biased by the non-uniform rate). None if the run covers
    less than one unit of time."""
    if len(rows) < 3 or rows[-1]["t"] - rows[0]["t"] < 1.0:
        return None
    turn = 2.0 * math.pi
    end_t, end_phase = rows[-1]["t"], rows[-1]["tt_phase"]
    t_half = 0.5 * (rows[0]["t"] + end_t)
    half_phase = next(r["tt_phase"] for r in rows if r["t"] >= t_half)
    turns = max(1, int(abs(end_phase - half_phase) // turn))
    start = None
    for r in reversed(rows):  # latest sample that is `turns` whole turns before the end
        if abs(end_phase - r["tt_phase"]) >= turns * turn:
            start = r
            break
    if start is not None and end_t > start["t"]:
        return 2.0 * abs(end_phase - start["tt_phase"]) / (end_t - start["t"])
    tail = [r for r in rows if r["t"] >= t_half]
    if len(tail) < 2:
        return None
    n = len(tail)
    mt = sum(r["t"] for r in tail) / n
    mp = sum(r["tt_phase"] for r in tail) / n
    stt = sum((r["t"] - mt) ** 2 for r in tail)
    if stt <= 0:
        return None
    slope = sum((r["t"] - mt) * (r["tt_phase"] - mp) for r in tail) / stt
    return 2.0 * abs(slope)


def end_values(final):
    """The end-state values of the summary table from the last chunk's `ehd_sim run
    --summary-json` object (None when the process wrote none)."""
    if not final or "t" not in final:
        return {}
    return {"t": final["t"], "steps": final["step"], "dxy": final["dxy"],
            "theta": final["inclination_over_pi"], "area_drift": final["area_drift"]}


def series_values(rows, tolerance):
    """The values of the summary table that need the time series (not only the end state)."""
    return {"tt_frequency": tank_treading_frequency(rows),
            "steady_time": steady_time(rows, tolerance)}


def final_values(rows, tolerance):
    """The values of the summary table from a run's series (a run without a --summary-json of
    its last chunk, e.g. one killed by a signal, has only these)."""
    if not rows:
        return {"t": None, "steps": None, "dxy": None, "theta": None, "area_drift": None,
                "tt_frequency": None, "steady_time": None}
    last = rows[-1]
    return {
        "t": last["t"],
        "steps": int(last["step"]),
        "dxy": last["dxy"],
        "theta": last["inclination"] / math.pi,
        "area_drift": last["area_drift"],
        "tt_frequency": tank_treading_frequency(rows),
        "steady_time": steady_time(rows, tolerance),
    }
