#!/usr/bin/env python3
"""The node prints the measures that mean something for the scene (issue #32 point 9): the
field-along-z drop electric_drop_3d (no shear) prints D_z, the deformation along the field, and
the volume drift, not D_xy = 0.00000 theta/pi = 0.5000 and an 'area drift'; sphere_shear_field
(shear and field) prints D_xy, theta and D_z. Checked on the summary of 3-step launches.
Exit status 0 when every check passes."""
import re
import sys

from ehd_test_helpers import check, finish, master_env, run

# A master of its own (roslaunch starts one on this port), away from any running roscore.
ENV = master_env(11393)


def summary(launch):
    _, out = run(["roslaunch", "ehd_capsule", launch, "steps:=3", "progress_period:=0"], env=ENV,
                 timeout=240)
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
    return finish()


if __name__ == "__main__":
    sys.exit(main())
