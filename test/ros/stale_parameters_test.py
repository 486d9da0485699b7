#!/usr/bin/env python3
"""No parameter of an earlier run changes a later one silently (issue #32 point 2). With one
roscore kept running:
  - roslaunch shear_field.launch 'set:={Ca_E: 0.5, ...}' runs at Ca_E = 0.5;
  - the same launch without Ca_E in set runs at the scene's Ca_E = 0.3 (the launch clears the
    node's private namespace first; roslaunch used to merge the new ~set into the old one);
  - after a launch, /use_sim_time (which the launch set for the node's clock) is gone, so a
    later plain `rostopic echo` does not wait for a /clock nobody publishes (issue #44 item 4);
  - a rosrun of the node after them takes the parameters the launch left (~steps, ~set/N, ...)
    and says so in a warning that names each with its value, but not the ones given on its own
    command line (_progress_period:=0).
Exit status 0 when every check passes."""
import re
import sys

from ehd_test_helpers import Roscore, check, finish, master_env, run

PORT = 11396
ENV = master_env(PORT)
SMALL = "N: 32, M: 32"


def main():
    with Roscore(PORT, ENV):
        launch = ["roslaunch", "ehd_capsule", "shear_field.launch", "steps:=3",
                  "progress_period:=0"]
        status, out = run([*launch, f"set:={{Ca_E: 0.5, {SMALL}}}"], ENV)
        check(status == 0 and "(Ca_E = 0.5)" in out, "the first launch runs at set's Ca_E = 0.5",
              out)
        status, out = run([*launch, f"set:={{{SMALL}}}"], ENV)
        check(status == 0 and "(Ca_E = 0.3)" in out and "(Ca_E = 0.5)" not in out,
              "the second launch, without Ca_E in set, runs at the scene's Ca_E = 0.3", out)
        check("grid 32 x 32" in out, "the second launch's own set (N: 32) applies", out)
        check("taken from the parameter server" not in out,
              "a launch warns of no parameter from the server (it set them all)", out)
        status, value = run(["rosparam", "get", "/use_sim_time"], ENV)
        check(status != 0 or value.strip() == "false",
              "no /use_sim_time = true left on the kept roscore after the launch", value)

        status, out = run(["rosrun", "ehd_capsule", "ehd_capsule_node", "_progress_period:=0"],
                          ENV)
        warning = next((l for l in out.splitlines() if "taken from the parameter server" in l), "")
        check(status == 0 and "ran after 3 steps" in out,
              "a rosrun after them takes the launch's ~steps = 3 left on the server", out)
        for name in ("~steps = 3", "~set/N = 32", "~scene = shear_field"):
            check(re.search(re.escape(name) + r"(,|$|\s)", warning) is not None,
                  f"its warning names {name}", out)
        check("~progress_period" not in warning,
              "its warning leaves out _progress_period:=0, given on its command line", out)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
