"""One run of a sweep: its folder, its chunks, resuming, its summary.

A run is simulated in chunks: chunk k is one `ehd_sim run` process from t_(k-1) to
t_k = k * record.checkpoint_every (the last one to the run's t_end) that restarts from the
checkpoint of chunk k-1 and writes its own time series and checkpoint. `ehd_sim` continues
a run bit for bit from a checkpoint, so the chunked run gives the same numbers as one process.
Chunk k's files are written under a .tmp name and renamed when the process has exited cleanly:
the rename of chunks/<k>.ckpt is the commit point. A killed chunk leaves only .tmp files, which
the next attempt deletes before redoing that chunk from the previous checkpoint, so a kill
costs at most one chunk. (Chunks with their own files are needed because ehd_sim overwrites
its checkpoint in place and buffers its CSV: a process killed in the middle of either would
otherwise leave a broken checkpoint or a time series with a gap.)

Run folder (<out>/runs/<name>/):
  scene.yaml     the exact scene the run used (base scene + overrides)
  settings.json  the sweep settings that decide the result (compared on resume)
  run.log        the output of every chunk, with a header line each
  chunks/        while running: <k>.csv per chunk, the last committed <k>.ckpt
  series.csv     when done: the whole time series
  sections.csv   with record.sections_every: the membrane's sections (ehd_sim run --sections)
  summary.json   when done: status, why it stopped, error, final values (from the last
                 chunk's `ehd_sim run --summary-json`), wall and CPU time; a run is finished
                 when its summary.json has an end reason (is_finished; summary.csv: the same
                 as one CSV row)
  checkpoint.bin the final state, with record.keep_checkpoint
  vtk/           ParaView files of the final state, with record.vtk_final
"""
import ctypes
import csv
import fcntl
import json
import os
import re
import shutil
import signal
import subprocess
import threading
import time

from . import analysis
from .spec import TAG_PREFIX, format_value

SUMMARY_FIELDS = ["run", "status", "stopped", "t", "steps", "dxy", "theta", "tt_frequency",
                  "steady_time", "area_drift", "wall_s", "cpu_s", "chunks", "resumed", "error"]


class Interrupted(Exception):
    """The sweep is being stopped (signal): the run is left to be resumed."""


class Busy(Exception):
    """Another process holds the run's lock."""


class Children:
    """The ehd_sim processes started by this process, so a signal can stop them all."""

    def __init__(self):
        self.lock = threading.Lock()
        self.procs = set()
        self.stopping = threading.Event()

    def add(self, p):
        with self.lock:
            self.procs.add(p)

    def remove(self, p):
        with self.lock:
            self.procs.discard(p)

    def stop_all(self):
        self.stopping.set()
        with self.lock:
            for p in list(self.procs):
                try:
                    p.send_signal(signal.SIGTERM)
                except OSError:
                    pass


CHILDREN = Children()


def _die_with_parent():
    """In the child, before exec: SIGKILL when the thread that started it dies (the sweep was
    killed), so no ehd_sim outlives its sweep and writes into a folder being resumed."""
    try:
        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except OSError:
        pass


def run_dir(out, run):
    return os.path.join(out, "runs", run.name)


# Why a finished run stopped (summary.json "stopped"): the only "is it finished" check of the
# sweeps and campaigns (is_finished). t_end and steady: ok; error: failed.
END_REASONS = ("t_end", "steady", "error")

# ehd_sim run --summary-json statuses that end a chunk cleanly; any other is an error whose
# "reason" is the run's error message.
CLEAN_STATUSES = ("completed", "steady", "not_steady")


def is_finished(summary):
    """True for the summary of a finished run (ok or failed): it names why the run stopped."""
    return isinstance(summary, dict) and summary.get("stopped") in END_REASONS and \
        summary.get("status") in ("ok", "failed")


def read_summary(out, run):
    path = os.path.join(run_dir(out, run), "summary.json")
    if not os.path.exists(path):
        return None
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError):
        return None  # written atomically, so this is a foreign or damaged file: redo the run
    return s if is_finished(s) else None


def progress_of(out, run, sweep):
    """(committed chunks, t reached) of an unfinished run."""
    chunks = os.path.join(run_dir(out, run), "chunks")
    ends = sweep.chunk_ends(run)
    k = _committed(chunks, len(ends))
    return k, (ends[k - 1] if k else 0.0)


def _committed(chunks, n_chunks):
    """Highest k such that chunks/<k>.ckpt exists and chunks 1..k have their CSV."""
    if not os.path.isdir(chunks):
        return 0
    best = 0
    for k in range(n_chunks, 0, -1):
        if os.path.exists(os.path.join(chunks, "%d.ckpt" % k)):
            best = k
            break
    while best and not all(os.path.exists(os.path.join(chunks, "%d.csv" % j))
                           for j in range(1, best + 1)):
        best -= 1
    return best


def _write_atomic(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def read_chunk_summary(path):
    """The JSON object `ehd_sim run --summary-json` wrote (None if the process wrote none: it
    was killed, or crashed). ehd_sim writes it to a .tmp file and renames it, so it is never
    partial."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def chunk_error(summary, returncode):
    """The error of a chunk that did not end cleanly, from its --summary-json (status and
    reason), or from the exit status when there is no summary; "" for a clean chunk."""
    if summary is not None:
        if summary.get("status") in CLEAN_STATUSES and returncode == 0:
            return ""
        reason = summary.get("reason") or "ehd_sim run ended with status %s" % summary.get(
            "status")
        if summary.get("status") == "simulation_error":
            return "simulation stopped: " + reason  # builds, not reads
        return reason
    if returncode < 0:
        return "ehd_sim killed by signal %d (no --summary-json written)" % -returncode
    return "ehd_sim exited %d without writing its --summary-json (see run.log)" % returncode


def merged_rows(chunks, k):
    rows = []
    for j in range(1, k + 1):
        rows.extend(analysis.read_series(os.path.join(chunks, "%d.csv" % j)))
    return rows


def _merge_chunks(chunks, k, suffix, path):
    """The chunks' CSV files (<j><suffix>) as one: the first header once, a restarted chunk's
    repeated header dropped, and a row cut short by a kill (fewer fields) left out."""
    header = None
    with open(path + ".tmp", "w") as out:
        for j in range(1, k + 1):
            p = os.path.join(chunks, "%d%s" % (j, suffix))
            if not os.path.exists(p):
                continue
            with open(p) as f:
                for line in f.read().splitlines():
                    if header is None:
                        header = line
                        out.write(header + "\n")
                    elif line != header and line.count(",") == header.count(","):
                        out.write(line + "\n")
    os.replace(path + ".tmp", path)


def execute(sweep, run, out, ehd_sim, threads=1, retry_failed=False):
    """Runs (or resumes) one run to its end and returns its summary; returns the stored summary
    of a finished run without running anything. Raises Interrupted when the sweep is stopped
    and Busy when another process works on the same run."""
    folder = run_dir(out, run)
    os.makedirs(folder, exist_ok=True)
    lock = open(os.path.join(folder, ".lock"), "w")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        lock.close()
        raise Busy("run %s is being worked on by another process (lock %s/.lock)" % (
            run.name, folder))
    try:
        return _execute_locked(sweep, run, out, folder, ehd_sim, threads, retry_failed)
    finally:
        lock.close()


def _execute_locked(sweep, run, out, folder, ehd_sim, threads, retry_failed):
    summary = read_summary(out, run)
    if summary is not None and (summary["status"] == "ok" or not retry_failed):
        return summary
    scene_text = run.scene_yaml(sweep)
    settings = sweep.run_settings(run)
    scene_path = os.path.join(folder, "scene.yaml")
    settings_path = os.path.join(folder, "settings.json")
    chunks = os.path.join(folder, "chunks")
    if summary is not None or (os.path.exists(scene_path) and (
            open(scene_path).read() != scene_text or not os.path.exists(settings_path) or
            json.load(open(settings_path)) != settings)):
        # A failed run being retried, or a folder made by another version of the sweep file
        # (the caller has checked with --fresh semantics; see check_compatible): start over.
        for name in os.listdir(folder):
            if name != ".lock":
                p = os.path.join(folder, name)
                shutil.rmtree(p) if os.path.isdir(p) else os.remove(p)
    if not os.path.exists(scene_path):
        _write_atomic(scene_path, scene_text)
        _write_atomic(settings_path, json.dumps(settings, indent=1) + "\n")
    os.makedirs(chunks, exist_ok=True)
    ends = sweep.chunk_ends(run)
    k = _committed(chunks, len(ends))
    resumed = 1 if k > 0 else 0
    # Clear what an interrupted attempt left: .tmp files, chunks past the commit point and the
    # checkpoints before it (only the last is needed).
    for name in os.listdir(chunks):
        stem = name.split(".")[0]
        if name.endswith(".tmp") or not stem.isdigit() or int(stem) > k or (
                name.endswith(".ckpt") and int(stem) < k):
            os.remove(os.path.join(chunks, name))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    error, stopped = "", ""
    rows = merged_rows(chunks, k)
    log_path = os.path.join(folder, "run.log")
    while True:
        if sweep.steady is not None and rows and analysis.steady_time(rows, sweep.steady) \
                is not None:
            stopped = "steady"
            break
        if k == len(ends):
            stopped = "t_end"
            break
        if CHILDREN.stopping.is_set():
            raise Interrupted()
        k += 1
        csv_tmp = os.path.join(chunks, "%d.csv.tmp" % k)
        ckpt_tmp = os.path.join(chunks, "%d.ckpt.tmp" % k)
        summary_path = os.path.join(chunks, "%d.summary.json" % k)
        sections_tmp = os.path.join(chunks, "%d.sections.csv.tmp" % k)
        if os.path.exists(summary_path):
            os.remove(summary_path)
        cmd = [ehd_sim, "run", scene_path, "--until", repr(ends[k - 1]), "--csv", csv_tmp,
               "--csv-every", str(sweep.csv_every), "--checkpoint", ckpt_tmp,
               "--summary-json", summary_path, "--progress", "60"]
        if k > 1:
            cmd += ["--restart", os.path.join(chunks, "%d.ckpt" % (k - 1))]
        if sweep.sections_every:
            cmd += ["--sections", sections_tmp, "--sections-every", str(sweep.sections_every)]
        with open(log_path, "a") as log:
            log.write("=== chunk %d/%d: t = %s -> %s%s, %s\n$ %s\n" % (
                k, len(ends), format_value(ends[k - 2]) if k > 1 else "0",
                format_value(ends[k - 1]), " (restart)" if k > 1 else "",
                time.strftime("%Y-%m-%d %H:%M:%S"), " ".join(cmd)))
            log.flush()
            start = time.time()
            proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=env,
                                    preexec_fn=_die_with_parent)
            CHILDREN.add(proc)
            try:
                _, status, usage = os.wait4(proc.pid, 0)
                proc.returncode = os.waitstatus_to_exitcode(status)
            finally:
                CHILDREN.remove(proc)
            wall = time.time() - start
            cpu = usage.ru_utime + usage.ru_stime
            log.write("=== chunk %d: exit %d, wall %.2f s, cpu %.2f s\n" % (
                k, proc.returncode, wall, cpu))
        if proc.returncode < 0 and CHILDREN.stopping.is_set():
            raise Interrupted()
        chunk_summary = read_chunk_summary(summary_path)
        if chunk_summary is not None:
            # ehd_sim's own times (from the start of the process, scene set-up included).
            wall, cpu = chunk_summary["wall_seconds"], chunk_summary["cpu_seconds"]
        with open(os.path.join(chunks, "%d.json" % k), "w") as f:
            json.dump({"wall_s": wall, "cpu_s": cpu,
                       "steps": (chunk_summary or {}).get("steps_taken", 0)}, f)
        if os.path.exists(csv_tmp):
            os.replace(csv_tmp, os.path.join(chunks, "%d.csv" % k))
        if os.path.exists(sections_tmp):
            os.replace(sections_tmp, os.path.join(chunks, "%d.sections.csv" % k))
        error = chunk_error(chunk_summary, proc.returncode).replace(folder + os.sep, "")
        if error:
            stopped = "error"
            if os.path.exists(ckpt_tmp):
                os.remove(ckpt_tmp)
            break
        os.replace(ckpt_tmp, os.path.join(chunks, "%d.ckpt" % k))  # commit chunk k
        previous = os.path.join(chunks, "%d.ckpt" % (k - 1))
        if os.path.exists(previous):
            os.remove(previous)
        rows.extend(analysis.read_series(os.path.join(chunks, "%d.csv" % k)))
    return _finish(sweep, run, folder, chunks, k, rows, stopped, error, resumed, ehd_sim, env)


def _finish(sweep, run, folder, chunks, k, rows, stopped, error, resumed, ehd_sim, env):
    walls = [json.load(open(os.path.join(chunks, n))) for n in os.listdir(chunks)
             if re.match(r"^[0-9]+\.json$", n)]
    final = read_chunk_summary(os.path.join(chunks, "%d.summary.json" % k)) if k else None
    _merge_chunks(chunks, k, ".csv", os.path.join(folder, "series.csv"))
    if sweep.sections_every:
        _merge_chunks(chunks, k, ".sections.csv", os.path.join(folder, "sections.csv"))
    last_ckpt = os.path.join(chunks, "%d.ckpt" % k)
    if not error and sweep.vtk_final and os.path.exists(last_ckpt):
        # Frame 0 of a one-step restart is the final state itself; the frame after the step
        # is removed again.
        vtk = os.path.join(folder, "vtk")
        with open(os.path.join(folder, "run.log"), "a") as log:
            log.write("=== VTK of the final state\n")
            log.flush()
            subprocess.run([ehd_sim, "run", os.path.join(folder, "scene.yaml"), "--restart",
                            last_ckpt, "--steps", "1", "--vtk", vtk, "--vtk-every", "1000000000",
                            "--quiet"], stdout=log, stderr=subprocess.STDOUT, env=env,
                           preexec_fn=_die_with_parent)
    if sweep.keep_checkpoint and os.path.exists(last_ckpt):
        os.replace(last_ckpt, os.path.join(folder, "checkpoint.bin"))
    values = analysis.final_values(rows, sweep.steady_tolerance)
    values.update(analysis.end_values(final))
    summary = {"run": run.name, "index": run.index,
               "parameters": {k2: v for k2, v in run.values.items()},
               "status": "failed" if error else "ok", "stopped": stopped}
    summary.update(values)
    summary.update({"wall_s": round(sum(w["wall_s"] for w in walls), 3),
                    "cpu_s": round(sum(w["cpu_s"] for w in walls), 3),
                    "chunks": k, "resumed": resumed, "error": error,
                    # The last chunk's `ehd_sim run --summary-json` object: every end value
                    # (d_field, surface_flow, ...), its status and reason.
                    "final": final})
    _write_atomic(os.path.join(folder, "summary.csv"), _summary_csv(summary))
    _write_atomic(os.path.join(folder, "summary.json"), json.dumps(summary, indent=1) + "\n")
    shutil.rmtree(chunks, ignore_errors=True)
    return summary


def _summary_csv(summary):
    import io
    buf = io.StringIO()
    keys = list(summary["parameters"]) + SUMMARY_FIELDS
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([k[len(TAG_PREFIX):] if k.startswith(TAG_PREFIX) else k for k in keys])
    w.writerow([format_value(summary["parameters"][k]) if k in summary["parameters"] else
                _cell(summary.get(k)) for k in keys])
    return buf.getvalue()


def _cell(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return "%.10g" % v
    return str(v)


def check_compatible(sweep, out):
    """Names the runs in `out` made with another version of the sweep (another scene or other
    settings): resuming them would mix results, so the caller refuses unless --fresh."""
    stale = []
    for run in sweep.runs:
        folder = run_dir(out, run)
        scene_path = os.path.join(folder, "scene.yaml")
        settings_path = os.path.join(folder, "settings.json")
        if not os.path.exists(scene_path):
            continue
        same_scene = open(scene_path).read() == run.scene_yaml(sweep)
        try:
            same_settings = json.load(open(settings_path)) == sweep.run_settings(run)
        except (OSError, ValueError):
            same_settings = False
        if not (same_scene and same_settings):
            stale.append(run.name)
    return stale
