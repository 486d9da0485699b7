#!/usr/bin/env python3
"""scripts/run's output comes live through a pipe (issue #32 point 1):
  - a long run (steps:=10000000) started through a pipe, as `scripts/run ... | tee` or a CI log
    reads it: every progress line arrives within a few seconds of the wall time rosconsole
    stamped it with (a block-buffered stdout held them until the node exited), and the first
    ones come while the node still runs; then SIGINT to the process group (Ctrl-C) ends it with
    the summary;
  - scripts/run with nothing changed since the last build prints no cmake output (the build
    check is quiet when up to date).
Exit status 0 when every check passes."""
import os
import re
import select
import signal
import subprocess
import sys
import time

from ehd_test_helpers import ROOT, check, failures, finish, master_env

# A master of its own (roslaunch starts one on this port), away from any running roscore.
ENV = master_env(11398)
PROGRESS = re.compile(r"\[ INFO\] \[(\d+\.\d+)(?:, [0-9.]+)?\]: [^ ]+: step \d+ ")
CMAKE_LINE = re.compile(r"^\[ *\d+%\]|Built target|^-- |Scanning dependencies|"
                        r"Consolidate compiler generated|^make(\[\d+\])?: ")


def live_progress():
    proc = subprocess.Popen(
        [os.path.join(ROOT, "scripts", "run"), "steps:=10000000", "progress_period:=1",
         "use_sim_time:=false", "set:={N: 32, M: 32}"],
        cwd=ROOT, env=dict(ENV, EHD_SKIP_SETUP="1"), stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT, start_new_session=True)
    lags, buffered, lines = [], b"", []
    deadline = time.time() + 90
    try:
        while time.time() < deadline and len(lags) < 4:
            ready, _, _ = select.select([proc.stdout], [], [], 1.0)
            if not ready:
                if proc.poll() is not None:
                    break
                continue
            chunk = os.read(proc.stdout.fileno(), 65536)
            if not chunk:
                break
            now = time.time()
            buffered += chunk
            *complete, buffered = buffered.split(b"\n")
            for raw in complete:
                line = raw.decode(errors="replace")
                lines.append(line)
                m = PROGRESS.search(line)
                if m:
                    lags.append(now - float(m.group(1)))
        running = proc.poll() is None
        check(len(lags) >= 4 and running,
              f"4 progress lines came through the pipe while the node ran (got {len(lags)}, "
              f"node running: {running})")
        check(lags and max(lags) < 3.0,
              "each progress line arrived within 3 s of its rosconsole stamp (lags: " +
              ", ".join(f"{x:.1f} s" for x in lags) + ")")
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C in a terminal: the whole group
        try:
            rest, _ = proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            rest, _ = proc.communicate()
    tail = (buffered + rest).decode(errors="replace")
    check("summary: stopped (SIGINT)" in tail and proc.returncode == 0,
          f"Ctrl-C ended it with the summary, status 0 (got {proc.returncode})")
    if failures:
        print("\n".join(lines[-30:]) + tail[-3000:])


def quiet_when_up_to_date():
    # The first scripts/setup brings the build up to date (whatever it prints); a scripts/run
    # after it has nothing to rebuild.
    setup = subprocess.run([os.path.join(ROOT, "scripts", "setup")], cwd=ROOT, env=ENV,
                           capture_output=True, text=True, timeout=1200)
    check(setup.returncode == 0, f"scripts/setup: status {setup.returncode}")
    if setup.returncode != 0:
        print(setup.stdout[-3000:] + setup.stderr[-3000:])
        return
    run = subprocess.run([os.path.join(ROOT, "scripts", "run"), "steps:=1", "set:={N: 32, M: 32}",
                          "progress_period:=0"], cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, timeout=300)
    cmake_lines = [l for l in run.stdout.splitlines() if CMAKE_LINE.search(l)]
    check(run.returncode == 0 and "summary: ran after 1 steps" in run.stdout,
          f"scripts/run steps:=1 ran (status {run.returncode})")
    check(not cmake_lines,
          f"scripts/run with nothing to rebuild printed no cmake lines (got {len(cmake_lines)}: "
          f"{cmake_lines[:3]})")
    if failures:
        print(run.stdout[-3000:])


def main():
    live_progress()
    quiet_when_up_to_date()
    return finish()


if __name__ == "__main__":
    sys.exit(main())
