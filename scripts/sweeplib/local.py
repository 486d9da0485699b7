"""Running a sweep's runs on this machine: `jobs` runs at a time, a progress line, a summary."""
import concurrent.futures
import os
import signal
import sys
import time

from . import runner


def _duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return "%ds" % seconds
    if seconds < 3600:
        return "%dm%02ds" % (seconds // 60, seconds % 60)
    return "%dh%02dm" % (seconds // 3600, seconds % 3600 // 60)


def run_local(sweep, out, ehd_sim, jobs, threads, retry_failed=False, progress_every=30.0,
              stream=sys.stdout):
    """Runs every unfinished run; returns (summaries by run name, interrupted signal or 0).
    A failed run is recorded and the others go on."""
    def say(text):
        stream.write(text + "\n")
        stream.flush()

    total = len(sweep.runs)
    summaries, pending = {}, []
    for run in sweep.runs:
        s = runner.read_summary(out, run)
        if s is not None and (s["status"] == "ok" or not retry_failed):
            summaries[run.name] = s
        else:
            pending.append(run)
    resumable = sum(1 for r in pending if runner.progress_of(out, r, sweep)[0] > 0)
    say("sweep %s: %d runs, %d finished, %d to run%s; %d at a time, %d thread%s each -> %s" % (
        sweep.name, total, len(summaries), len(pending),
        " (%d resumed from a checkpoint)" % resumable if resumable else "", jobs, threads,
        "s" if threads > 1 else "", out))
    if not pending:
        return summaries, 0

    received = []

    def on_signal(signum, _frame):
        if not received:
            say("sweep %s: %s received, stopping the runs (rerun the same command to resume)" % (
                sweep.name, signal.Signals(signum).name))
        received.append(signum)
        runner.CHILDREN.stop_all()

    old = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    start = time.time()
    done_here, failed = 0, sum(1 for s in summaries.values() if s["status"] != "ok")
    last_line = start
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = {pool.submit(runner.execute, sweep, r, out, ehd_sim, threads,
                                   retry_failed): r for r in pending}
            remaining = set(futures)
            while remaining:
                finished, remaining = concurrent.futures.wait(
                    remaining, timeout=1.0, return_when=concurrent.futures.FIRST_COMPLETED)
                for f in finished:
                    run = futures[f]
                    try:
                        s = f.result()
                    except runner.Interrupted:
                        continue
                    except runner.Busy as e:
                        say("sweep %s: %s" % (sweep.name, e))
                        continue
                    summaries[run.name] = s
                    done_here += 1
                    if s["status"] != "ok":
                        failed += 1
                    say("[%d/%d] %s %s: %s (%.1f s)" % (
                        len(summaries), total, run.name, s["status"],
                        s["error"] if s["error"] else "t = %.4g, D_xy = %.5f, theta/pi = %.4f" % (
                            s["t"], s["dxy"], s["theta"]), s["wall_s"]))
                now = time.time()
                if remaining and not received and (finished and done_here or
                                                   now - last_line >= progress_every):
                    last_line = now
                    running = min(jobs, len(remaining))
                    left = total - len(summaries)
                    eta = "ETA %s" % _duration((now - start) / done_here * left) if done_here \
                        else "ETA after the first run"
                    say("sweep %s: %d/%d done%s, %d running, %s elapsed, %s" % (
                        sweep.name, len(summaries), total,
                        " (%d failed)" % failed if failed else "", running,
                        _duration(now - start), eta))
    finally:
        for s, h in old.items():
            signal.signal(s, h)
    if received:
        say("sweep %s: interrupted after %s: %d/%d runs finished; rerun to resume" % (
            sweep.name, _duration(time.time() - start), len(summaries), total))
        return summaries, received[0]
    say("sweep %s: all %d runs finished in %s, %d ok, %d failed%s" % (
        sweep.name, total, _duration(time.time() - start), total - failed, failed,
        "" if not failed else ":"))
    for s in summaries.values():
        if s["status"] != "ok":
            say("  FAILED %s: %s" % (s["run"], s["error"]))
    return summaries, 0


def default_jobs():
    """One run per core (each single-threaded): measured faster than fewer threaded runs
    (docs/sweeps.md, "Local parallelism")."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:
        return max(1, os.cpu_count() or 1)
