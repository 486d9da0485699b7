#!/usr/bin/python3
"""A killed local sweep resumes without redoing finished runs, and ends with the table of an
uninterrupted sweep (test/sweep/tiny.yaml, one run at a time):

  1. the sweep uninterrupted (reference table and time series);
  2. the sweep killed with SIGKILL once a run has finished and the next has committed a chunk;
     no ehd_sim outlives it; the rerun skips the finished runs (their files untouched, no new
     chunk in their logs), resumes the partial run from its checkpoint (chunk 1 not redone)
     and gives the reference table and series;
  3. the same with SIGTERM: the sweep stops its runs and exits 143, and the rerun finishes.

  test/sweep/resume_test.py [--ehd-sim PATH] [--work DIR]
"""
import argparse
import csv
import os
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SWEEP = os.path.join(REPO, "scripts", "sweep")
SWEEP_FILE = os.path.join(HERE, "tiny.yaml")
failures = []


def check(ok, what):
    print("%s: %s" % ("ok" if ok else "FAIL", what), flush=True)
    if not ok:
        failures.append(what)


def sweep_cmd(args, out):
    return [SWEEP, SWEEP_FILE, "--out", out, "--ehd-sim", args.ehd_sim, "--jobs", "1"]


def table(out, drop=("wall_s",)):
    with open(os.path.join(out, "table.csv")) as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in r.items() if k not in drop} for r in rows]


def runs_dir(out):
    return os.path.join(out, "runs")


def state(out):
    """(finished runs, runs with a committed chunk but not finished)."""
    done, partial = [], []
    if not os.path.isdir(runs_dir(out)):
        return done, partial
    for name in sorted(os.listdir(runs_dir(out))):
        folder = os.path.join(runs_dir(out), name)
        if os.path.exists(os.path.join(folder, "summary.json")):
            done.append(name)
        elif os.path.isdir(os.path.join(folder, "chunks")) and any(
                f.endswith(".ckpt") for f in os.listdir(os.path.join(folder, "chunks"))):
            partial.append(name)
    return done, partial


def ehd_sims_writing_to(out):
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            cmdline = open("/proc/%s/cmdline" % pid, "rb").read().decode(errors="replace")
        except OSError:
            continue
        if "ehd_sim" in cmdline and out in cmdline and "resume_test" not in cmdline:
            found.append(pid)
    return found


def interrupted_sweep(args, out, sig, log_path):
    """Starts the sweep, waits for a finished run and a partial one, sends sig; returns the
    sweep's exit status and the files of the finished runs at that moment."""
    with open(log_path, "w") as log:
        proc = subprocess.Popen(sweep_cmd(args, out), stdout=log, stderr=subprocess.STDOUT)
        deadline = time.time() + 60
        while time.time() < deadline and proc.poll() is None:
            done, partial = state(out)
            if done and partial:
                proc.send_signal(sig)
                break
            time.sleep(0.01)
        rc = proc.wait(timeout=60)
    return rc, done, partial


def snapshot(out, names):
    snap = {}
    for name in names:
        folder = os.path.join(runs_dir(out), name)
        for f in ("summary.json", "series.csv", "run.log"):
            st = os.stat(os.path.join(folder, f))
            snap[(name, f)] = (st.st_ino, st.st_mtime_ns, st.st_size)
    return snap


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--ehd-sim", default=os.path.join(REPO, "build", "bin", "ehd_sim"))
    p.add_argument("--work", default="/tmp/ehd_sweep_resume_test")
    args = p.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    start = time.time()

    ref = os.path.join(args.work, "uninterrupted")
    rc = subprocess.run(sweep_cmd(args, ref), stdout=open(os.path.join(args.work, "ref.log"), "w"),
                        stderr=subprocess.STDOUT).returncode
    check(rc == 1, "uninterrupted sweep exits 1 (two runs fail by design), got %d" % rc)
    reference = table(ref)
    statuses = [r["status"] for r in reference]
    check(statuses.count("ok") == 4 and statuses.count("failed") == 2,
          "reference table: 4 ok and 2 failed runs (%s)" % statuses)
    check(all("'Ca_E' = 5 is out of range" in r["error"] for r in reference
              if r["status"] == "failed"), "failed runs carry their error in the table")

    for sig, expect_rc in ((signal.SIGKILL, -9), (signal.SIGTERM, 128 + signal.SIGTERM)):
        name = signal.Signals(sig).name
        out = os.path.join(args.work, name.lower())
        rc, done, partial = interrupted_sweep(args, out, sig, os.path.join(args.work,
                                                                           name + ".log"))
        check(rc == expect_rc, "%s: the sweep exits %d, got %d" % (name, expect_rc, rc))
        check(bool(done) and bool(partial),
              "%s: stopped with %d finished run(s) and a partial run %s" % (name, len(done),
                                                                            partial))
        time.sleep(0.5)
        left = ehd_sims_writing_to(out)
        check(not left, "%s: no ehd_sim left running after the sweep died (pids %s)" % (
            name, left))
        before = snapshot(out, done)
        log = os.path.join(args.work, name + "_resume.log")
        rc = subprocess.run(sweep_cmd(args, out), stdout=open(log, "w"),
                            stderr=subprocess.STDOUT).returncode
        text = open(log).read()
        check(rc == 1, "%s: resumed sweep exits 1 (the two failing runs), got %d" % (name, rc))
        check("%d finished" % len(done) in text and "resumed from a checkpoint" in text,
              "%s: the rerun reports %d finished runs and a resumed one" % (name, len(done)))
        after = snapshot(out, done)
        check(before == after, "%s: finished runs were not redone (summary, series and log "
              "untouched)" % name)
        for run in partial:
            folder = os.path.join(runs_dir(out), run)
            run_log = open(os.path.join(folder, "run.log")).read()
            summary = open(os.path.join(folder, "summary.json")).read()
            check(run_log.count("=== chunk 1/") == 1 and '"resumed": 1' in summary,
                  "%s: %s resumed from its checkpoint (chunk 1 run once)" % (name, run))
        check(table(out) == reference,
              "%s: the final table equals the uninterrupted sweep's (all but wall time)" % name)
        same_series = all(
            open(os.path.join(runs_dir(out), r, "series.csv")).read() ==
            open(os.path.join(runs_dir(ref), r, "series.csv")).read()
            for r in os.listdir(runs_dir(ref)))
        check(same_series, "%s: every run's time series equals the uninterrupted one" % name)
    print("resume test: %.1f s, %s" % (time.time() - start,
                                       "%d failure(s)" % len(failures) if failures else "passed"))
    if not failures:
        shutil.rmtree(args.work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
