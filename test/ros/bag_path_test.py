#!/usr/bin/env python3
"""A relative bag path is taken from the directory the user started from, never silently from
ROS_HOME, where roslaunch runs the node (issue #32 point 7):
  - roslaunch shear_field.launch record:=true bag:=runs/a.bag, started in a scratch directory,
    writes <scratch>/runs/a.bag and logs that absolute path (before: $ROS_HOME/runs/a.bag);
  - scripts/run ... bag:=b.bag started there writes <scratch>/b.bag (scripts/run works in the
    repository, but roslaunch runs from the caller's directory);
  - replay.launch bag:=runs/a.bag plays <scratch>/runs/a.bag (rosbag play runs in ROS_HOME too).
Exit status 0 when every check passes."""
import os
import sys
import tempfile

import ehd_test_helpers as helpers
from ehd_test_helpers import ROOT, check, finish, master_env

# A master of its own (roslaunch starts one on this port), away from any running roscore.
ENV = master_env(11395, EHD_SKIP_SETUP="1")
ARGS = ["steps:=3", "record:=true", "progress_period:=0", "set:={N: 32, M: 32}"]


def run(cmd, cwd):
    return helpers.run(cmd, env=dict(ENV, PWD=cwd), cwd=cwd)  # PWD: as a shell started there


def main():
    with tempfile.TemporaryDirectory(prefix="ehd_bag_path_") as scratch:
        scratch = os.path.realpath(scratch)
        os.mkdir(os.path.join(scratch, "runs"))
        status, out = run(["roslaunch", "ehd_capsule", "shear_field.launch", "bag:=runs/a.bag",
                           *ARGS], scratch)
        bag = os.path.join(scratch, "runs", "a.bag")
        check(status == 0 and os.path.isfile(bag), f"roslaunch wrote {bag}", out)
        check(f"recording to {bag} " in out and f"bag {bag} closed" in out,
              "the node logged the bag's absolute path", out)
        ros_home = os.environ.get("ROS_HOME", os.path.expanduser("~/.ros"))
        stray = os.path.join(ros_home, "runs", "a.bag")
        check(not os.path.exists(stray), f"nothing went to {stray}", out)

        status, out = run([os.path.join(ROOT, "scripts", "run"), "bag:=b.bag", *ARGS], scratch)
        bag = os.path.join(scratch, "b.bag")
        check(status == 0 and os.path.isfile(bag) and f"recording to {bag} " in out,
              f"scripts/run started in the scratch directory wrote {bag}", out)

        status, out = run(["roslaunch", "--args", "/player", "ehd_capsule", "replay.launch",
                           "bag:=runs/a.bag"], scratch)
        check(status == 0 and out.split()[-2:-1] == [os.path.join(scratch, "runs", "a.bag")],
              "replay.launch plays the bag from the scratch directory", out)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
