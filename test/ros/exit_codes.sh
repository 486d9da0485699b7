#!/usr/bin/env bash
# scripts/run returns the node's exit status (roslaunch alone returns 0 whatever its nodes do):
# 0 for a run that reaches its steps or its steady state (until_steady), 1 for a simulation that stops on an error (a capsule
# touching the wall, batch run: ~exit_on_error), 1 for an invalid scene or node parameter, 1 for a
# batch run whose bag cannot be written.
set -u
cd "$(dirname "$0")/../.."
export EHD_SKIP_SETUP=1
# A master of its own (roslaunch starts one on this port), away from any running roscore.
export ROS_MASTER_URI=http://localhost:11397
export ROS_HOSTNAME=localhost
fail=0
# The master of the previous run may still be shutting down (slower on a loaded machine): wait
# until nothing listens on the port, or the next roslaunch fails with "Address already in use".
wait_for_free_port() {
  for _ in $(seq 100); do
    (exec 3<>/dev/tcp/localhost/11397) 2>/dev/null || return 0
    sleep 0.2
  done
  echo "FAIL: port 11397 still in use after 20 s"; fail=1
}
check() {
  local expect=$1; shift
  wait_for_free_port
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
# A batch run whose bag cannot be written (a 300 kB file size limit for a full disk) ends with
# status 1 (on_record_error stop, the default with steps) instead of waiting paused forever.
bag=$(mktemp -u /tmp/ehd_exit_codes_XXXXXX.bag)
wait_for_free_port
timeout 120 bash -c 'ulimit -f 300; exec scripts/run "$@"' scripts/run steps:=1000000 record:=true \
  bag:="$bag" set:="{N: 32, M: 32}" progress_period:=0 >/tmp/ehd_exit_codes.log 2>&1
got=$?
if [ "$got" != 1 ] || ! grep -q "File too large" /tmp/ehd_exit_codes.log; then
  echo "FAIL: a batch run with a failing bag exited $got (expected 1, naming 'File too large')"
  tail -20 /tmp/ehd_exit_codes.log
  fail=1
else
  echo "ok: a batch run with a failing bag -> 1"
fi
rm -f "$bag" "$bag.active"
exit $fail
