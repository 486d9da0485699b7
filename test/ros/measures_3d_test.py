#!/usr/bin/env python3
"""The node prints the measures that mean something for the scene (issue #32 point 9): the
field-along-z drop electric_drop_3d (no shear) prints D_z, the deformation along the field, and
the volume drift, not D_xy = 0.00000 theta/pi = 0.5000 and an 'area drift'; sphere_shear_field
(shear and field) prints D_xy, theta and D_z. Checked on the summary of 3-step launches.
Exit status 0 when every check passes."""
import os
import re
import subprocess
import sys

# A master of its own (roslaunch starts one on this port), away from any running roscore.
ENV = dict(os.environ, ROS_MASTER_URI="http://localhost:11393", ROS_HOSTNAME="localhost")
failures = []


def check(ok, what, output=""):
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)
        print(output[-3000:])


def summary(launch):
    out = subprocess.run(["roslaunch", "ehd_capsule", launch, "steps:=3", "progress_period:=0"],
                         env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         timeout=240).stdout
    m = re.search(r"summary: ran after 3 steps, t = \S+ [^:]+: ([^;]*);", out)
    return (m.group(1) if m else ""), out


def main():
    line, out = summary("electric_drop_3d.launch")
    check(re.fullmatch(r"D_z = -?[0-9.]+, volume drift = \S+", line) is not None,
          f"electric_drop_3d's summary: D_z and the volume drift only (got '{line}')", out)
    line, out = summary("sphere_shear_field.launch")
    check(re.fullmatch(r"D_xy = [0-9.]+, theta/pi = -?[0-9.]+, D_z = -?[0-9.]+, "
                       r"volume drift = \S+", line) is not None,
          f"sphere_shear_field's summary: D_xy, theta, D_z, volume drift (got '{line}')", out)
    print(f"{len(failures)} failure(s)" if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
