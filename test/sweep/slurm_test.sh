#!/usr/bin/env bash
# Sweeps on a real Slurm: starts a one-node Slurm on this machine (Debian's slurm-wlm and munge:
# munged, slurmctld, slurmd, all from this script, on ports and folders of their own), submits
# test/sweep/tiny.yaml with `scripts/sweep --slurm --wait` (one job array, one task per run),
# collects, checks the table (4 runs ok, the 2 runs with an out-of-range Ca_E failed with their
# error, every task ran under Slurm), runs the same sweep locally and checks that it gives the
# same numbers, and tears Slurm down. If Slurm cannot start, the test says why and FAILS (it
# never skips): scripts/setup installs slurm-wlm and munge.
#
# What makes Slurm 22.05 run here (root, no systemd, a sandboxed cgroup hierarchy): munged
# started by this script with its socket in a world-executable folder and slurm.conf pointing at
# it (AuthInfo=socket=...); proctrack/linuxproc with task/none (the cgroup plugins start, but
# every job step then fails); no accounting (the sweep polls squeue); NodeName = hostname -s and
# RealMemory at most what `slurmd -C` reports.
#
#   test/sweep/slurm_test.sh [EHD_SIM]     (default build/bin/ehd_sim)
set -u
cd "$(dirname "$0")/../.."
repo=$PWD
ehd_sim=${1:-$repo/build/bin/ehd_sim}
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
start_time=$(date +%s.%N)
elapsed() { awk -v a="$start_time" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }
fail() {
  echo "FAIL: $*"
  exit 1
}

for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scancel; do
  command -v "$tool" >/dev/null ||
    fail "'$tool' not found: this test needs Debian's slurm-wlm and munge (scripts/setup installs them)"
done
[ -x "$ehd_sim" ] || fail "$ehd_sim is not built (scripts/setup)"

work=$(mktemp -d /tmp/ehd_sweep_slurm_test.XXXXXX)
chmod 755 "$work"  # world-executable: slurmd and munge clients reach the socket below
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/out"
chmod 755 "$work/munge"
keep=0
teardown() {
  local rc=$?
  [ -n "${SLURM_CONF:-}" ] && scancel --quiet -u root >/dev/null 2>&1
  for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
    if [ -f "$pidfile" ]; then
      pid=$(cat "$pidfile")
      kill "$pid" 2>/dev/null
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null
    fi
  done
  if [ "$rc" -ne 0 ] || [ "$keep" -ne 0 ]; then
    for log in "$work/munge/munged.log" "$work/slurmctld.log" "$work/slurmd.log"; do
      [ -f "$log" ] && { echo "--- tail of $log"; tail -15 "$log"; }
    done
    echo "slurm test: files kept in $work"
  else
    rm -rf "$work"
  fi
  exit "$rc"
}
trap teardown EXIT

# --- munge ------------------------------------------------------------------------------------
mungekey --create --keyfile="$work/munge/munge.key" >/dev/null 2>&1 ||
  fail "mungekey could not create a key in $work/munge"
socket="$work/munge/munge.socket"
munged --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" \
  --seed-file="$work/munge/munged.seed" ||
  fail "munged did not start (log: $(tail -3 "$work/munge/munged.log" 2>/dev/null))"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || fail "munged did not create its socket $socket"
munge -n --socket="$socket" | unmunge --socket="$socket" >/dev/null ||
  fail "munge round trip failed on $socket"

# --- slurm ------------------------------------------------------------------------------------
host=$(hostname -s)
read -r cpus mem < <(slurmd -C | awk '/^NodeName/ {
  for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
  print v["CPUs"], v["RealMemory"] }')
[ -n "${cpus:-}" ] && [ -n "${mem:-}" ] || fail "slurmd -C reported no CPUs/RealMemory: $(slurmd -C 2>&1)"
mem=$((mem > 2048 ? mem - 1024 : mem))  # at most what slurmd -C reports
port=$((17000 + ($$ % 1000) * 2))
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=ehdsweeptest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=sweeptest Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
state=""
for _ in $(seq 100); do
  state=$(sinfo -h -o %t 2>/dev/null | head -1)
  [ "$state" = "idle" ] && break
  sleep 0.1
done
[ "$state" = "idle" ] || fail "the node did not come up idle (sinfo state '$state')"
printf 'slurm test: one-node Slurm up in %s s (node %s, %s CPUs, %s MB)\n' \
  "$(elapsed)" "$host" "$cpus" "$mem"

# --- the sweep on Slurm -----------------------------------------------------------------------
sweep=(scripts/sweep test/sweep/tiny.yaml --ehd-sim "$ehd_sim")
"${sweep[@]}" --out "$work/out/slurm" --slurm --wait --time 00:05:00 --mem 100M \
  >"$work/slurm_sweep.log" 2>&1
rc=$?
cat "$work/slurm_sweep.log"
[ "$rc" -eq 1 ] || { keep=1; fail "scripts/sweep --slurm --wait exited $rc, expected 1 (two runs fail by design)"; }
grep -q "submitted 6 of 6 runs as Slurm job array" "$work/slurm_sweep.log" ||
  fail "the sweep was not submitted as one array of 6 tasks"
tasks=$(ls "$work/out/slurm/slurm/"*_*.out 2>/dev/null | wc -l)
[ "$tasks" -eq 6 ] || fail "expected 6 array task logs in $work/out/slurm/slurm, found $tasks"
ran=$(grep -l "^sweep tiny task [0-9]*: .* -> " "$work/out/slurm/slurm/"*_*.out | wc -l)
[ "$ran" -eq 6 ] || fail "only $ran of 6 task logs show the task running its run"

# --- the same sweep locally, and the comparison ---------------------------------------------------
"${sweep[@]}" --out "$work/out/local" >"$work/local_sweep.log" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "the local sweep exited $rc, expected 1 ($(tail -3 "$work/local_sweep.log"))"
/usr/bin/python3 - "$work/out/slurm/table.csv" "$work/out/local/table.csv" <<'EOF' || exit 1
import csv, sys
def rows(path):
    with open(path) as f:
        return [{k: v for k, v in r.items() if k != "wall_s"} for r in csv.DictReader(f)]
slurm, local = rows(sys.argv[1]), rows(sys.argv[2])
ok = [r for r in slurm if r["status"] == "ok"]
failed = [r for r in slurm if r["status"] == "failed"]
problems = []
if len(slurm) != 6 or len(ok) != 4 or len(failed) != 2:
    problems.append("table: %d rows, %d ok, %d failed (expected 6, 4, 2)" % (
        len(slurm), len(ok), len(failed)))
for r in ok:
    if not (r["t"] == "6" and 0.3 < float(r["D_xy"]) < 0.6 and r["tt_frequency"]):
        problems.append("run %s: t = %s, D_xy = %s, f_tt = %s" % (
            r["run"], r["t"], r["D_xy"], r["tt_frequency"]))
for r in failed:
    if "'Ca_E' = 5 is out of range" not in r["error"]:
        problems.append("failed run %s without its error: '%s'" % (r["run"], r["error"]))
if slurm != local:
    for a, b in zip(slurm, local):
        if a != b:
            problems.append("Slurm and local differ for %s: %s" % (a["run"], {
                k: (a[k], b[k]) for k in a if a[k] != b[k]}))
for p in problems:
    print("FAIL: " + p)
if not problems:
    print("ok: Slurm table: 6 runs, 4 ok, 2 failed with their error; the local sweep gives the "
          "same numbers")
sys.exit(1 if problems else 0)
EOF
for f in table.md figures/dxy_t_A.png figures/final_dxy.png; do
  [ -s "$work/out/slurm/$f" ] || fail "collect did not write $f"
done
echo "slurm test: passed in $(elapsed) s (before the teardown)"
