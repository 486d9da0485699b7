#!/usr/bin/env bash
# scripts/run returns the node's exit status (roslaunch alone returns 0 whatever its nodes do):
# 0 for a run that reaches its steps or its steady state (until_steady), 1 for a simulation that stops on an error (a capsule
# touching the wall, batch run: ~exit_on_error), 1 for an invalid scene or node parameter.
set -u
cd "$(dirname "$0")/../.."
export EHD_SKIP_SETUP=1
# A master of its own (roslaunch starts one on this port), away from any running roscore.
export ROS_MASTER_URI=http://localhost:11397
export ROS_HOSTNAME=localhost
fail=0
check() {
  local expect=$1; shift
  scripts/run "$@" >/tmp/ehd_exit_codes.log 2>&1
  local got=$?
  if [ "$got" != "$expect" ]; then
    echo "FAIL: scripts/run $* exited $got, expected $expect"; tail -20 /tmp/ehd_exit_codes.log
    fail=1
  else
    echo "ok: scripts/run $* -> $got"
  fi
}
check 0 steps:=20 set:="{N: 32, M: 32}"
check 0 until_steady:=1e-2 set:="{N: 32, M: 32}"  # ends on its own at the steady state
check 1 scene:="$PWD/test/ros/wall_touching.yaml" steps:=100
check 1 scene:=no_such_scene steps:=10
check 1 steps:=10 surface_colour:=bogus  # an invalid node parameter
exit $fail
