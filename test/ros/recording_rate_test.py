#!/usr/bin/env python3
"""A recording says what it costs (issue #32 point 6): a run of the default scene with
record:=true and steps:=100000000 (far more than any disk holds at ~16 kB per state) logs, from
its first second, the bytes per state, the MB/s and the free space of the bag's filesystem, and
warns that the bag will fill the disk before the run ends, first from the first state's size,
before any rate is measured (issue #44 item 6: a disk that filled within the first second gave
no warning); the bytes per state it logs are within 10% of the closed bag's size per state.
Ended by SIGINT a few seconds in.
Exit status 0 when every check passes."""
import os
import re
import select
import signal
import subprocess
import sys
import tempfile
import time

from ehd_test_helpers import check, failures, finish, master_env

# A master of its own (roslaunch starts one on this port), away from any running roscore.
ENV = master_env(11394)
INFO = re.compile(r"recording: ([0-9.]+) (B|kB|MB) per state, ([0-9.]+) (kB|MB|GB)/s \(measured "
                  r"over the first \d+ states, [0-9.]+ s\); ([0-9.]+) (kB|MB|GB|TB) free on ([^\s\x1b]+)")
UNIT = {"B": 1, "kB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12}


def main():
    scratch = tempfile.mkdtemp(prefix="ehd_recording_rate_")
    bag = os.path.join(scratch, "rate.bag")
    proc = subprocess.Popen(
        ["roslaunch", "ehd_capsule", "shear_field.launch", "record:=true", f"bag:={bag}",
         "steps:=100000000", "progress_period:=0"],
        env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    out, info, warning, early, end = "", None, None, None, time.time() + 120
    try:
        while time.time() < end and proc.poll() is None:
            if select.select([proc.stdout], [], [], 0.5)[0]:
                chunk = os.read(proc.stdout.fileno(), 65536).decode(errors="replace")
                out += chunk
            info = info or INFO.search(out)
            warning = warning or re.search(r"WARN.*the bag will fill the disk before the run ends: "
                                           r"the \d+ states left need about [0-9.]+ [kMGTP]B", out)
            early = early or re.search(r"WARN.*the bag will fill the disk before the run ends: "
                                       r"the \d+ states left need about [0-9.]+ [kMGTP]B, .* "
                                       r"\(estimated from the first state, [0-9.]+ [kM]?B\)", out)
            if info and warning and early and end > time.time() + 3:
                end = time.time() + 3  # a few seconds more of recording, then Ctrl-C
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
        rest, _ = proc.communicate(timeout=60)
        out += rest.decode(errors="replace")
    check(info is not None, "the recording's cost (bytes per state, MB/s, free space) is logged")
    check(warning is not None, "a warning says the bag fills the disk before the run's steps")
    check(early is not None and (info is None or early.start() < info.start()),
          "the warning comes from the first state's size, before the rate is measured")
    closed = re.search(r"bag (\S+) closed with (\d+) states", out)
    check(closed is not None and closed.group(1) == bag, f"the bag {bag} was closed")
    if info and closed:
        per_state = float(info.group(1)) * UNIT[info.group(2)]
        actual = os.path.getsize(bag) / int(closed.group(2))
        check(abs(per_state - actual) < 0.1 * actual,
              f"logged {per_state:.0f} bytes per state, the bag holds {actual:.0f} per state")
        check(info.group(7) == scratch, f"the free space is the bag's filesystem's ({scratch})")
    for f in os.listdir(scratch):
        os.remove(os.path.join(scratch, f))
    os.rmdir(scratch)
    if failures:
        print(out[-5000:])
    return finish()


if __name__ == "__main__":
    sys.exit(main())
