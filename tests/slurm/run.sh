#!/usr/bin/env bash
# A sweep through a real SLURM: starts munged, slurmctld and slurmd (Debian's
# slurm-wlm and munge) as a single-node cluster on this machine, submits `rootsim sweep --shard K/4` as
# a job array of 4, waits for it, rebuilds table.csv (`rootsim sweep` without --shard skips every
# completed point) and compares it row for row with a local `rootsim sweep -j 2` of the same sweep.
# Every daemon it starts is stopped on exit (by its pid). Needs root (the daemons run as root here).
# Usage: tests/slurm/run.sh ROOTSIM_BINARY
# Exit 0: identical tables; 1: the cluster run or the comparison failed; 77: SLURM cannot run here
# (the reason is printed; ctest shows the test as skipped; with ROOTSIM_REQUIRE_SLURM=1 this is exit 1).
set -euo pipefail
# CI sets ROOTSIM_REQUIRE_SLURM=1: there a cluster that does not start is a failure, not a skip
skip=77
[ "${ROOTSIM_REQUIRE_SLURM:-0}" = 1 ] && skip=1
rootsim=$(realpath "${1:?usage: run.sh ROOTSIM_BINARY}")
here=$(cd "$(dirname "$0")" && pwd)
sweep="$here/sweep.toml"
for tool in munged slurmctld slurmd sbatch squeue scontrol; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool not installed (Debian packages slurm-wlm, munge)"; exit $skip; }
done
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root to start munged/slurmctld/slurmd"; exit $skip; }

work=$(mktemp -d /tmp/rootsim-slurm-XXXXXX)
chmod 755 "$work"
pids=()
cleanup() {
  local rc=$?
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$p" 2>/dev/null || true
  done
  if [ $rc -ne 0 ]; then
    for f in "$work"/*.log; do [ -f "$f" ] && { echo "--- $f"; tail -20 "$f"; }; done
  fi
  rm -rf "$work"
  exit $rc
}
trap cleanup EXIT
trap 'exit 1' INT TERM

host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool" "$work/munge"
chown munge:munge "$work/munge" 2>/dev/null || true
cat >"$work/slurm.conf" <<CONF
ClusterName=rootsimtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
# no cgroups and no systemd in a container: track processes through /proc, no task confinement
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MaxArraySize=16
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=10 State=UP
CONF
export SLURM_CONF="$work/slurm.conf"

# munge with its own socket (a system munged, if any, is left alone)
munged --force --socket="$work/munge/munge.socket" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/munged.log" --seed-file="$work/munge/seed" --key-file=/etc/munge/munge.key \
  || { echo "SKIP: munged did not start"; cat "$work/munged.log" 2>/dev/null; exit $skip; }
for _ in $(seq 50); do [ -s "$work/munge/munged.pid" ] && break; sleep 0.1; done
pids+=("$(cat "$work/munge/munged.pid")")

slurmctld -D -f "$work/slurm.conf" >"$work/slurmctld.out.log" 2>&1 &
pids+=($!)
slurmd -D -f "$work/slurm.conf" >"$work/slurmd.out.log" 2>&1 &
pids+=($!)
up=""
for _ in $(seq 100); do
  if state=$(sinfo -h -o %T 2>/dev/null) && [ "$state" = idle ]; then up=1; break; fi
  for p in "${pids[@]:1}"; do
    kill -0 "$p" 2>/dev/null || { echo "SKIP: a SLURM daemon exited at start:"; tail -5 "$work"/slurm*.log; exit $skip; }
  done
  sleep 0.2
done
[ -n "$up" ] || { echo "SKIP: the node did not become idle in 20 s (sinfo: $(sinfo -h -o %T 2>&1))"; exit $skip; }
echo "slurm: single-node cluster $host up ($cpus CPUs)"

start=$(date +%s)
out="$work/cluster"
# the job array: task K runs shard K/4 (what docs/cli.md's SLURM example shows)
sbatch --wait --array=1-4 --output="$work/job_%A_%a.log" --chdir="$work" \
  --wrap "$rootsim sweep $sweep --shard \${SLURM_ARRAY_TASK_ID}/4 --out $out --quiet" >"$work/sbatch.log" 2>&1 || {
  echo "FAIL: sbatch --wait failed"; cat "$work/sbatch.log" "$work"/job_*.log; exit 1; }
echo "slurm: job array of 4 done in $(( $(date +%s) - start )) s: $(head -1 "$work/sbatch.log")"
ran=$(cat "$work"/job_*.log | grep -c . || true)
[ "$ran" -eq 0 ] || { echo "FAIL: array tasks wrote output (errors?):"; cat "$work"/job_*.log; exit 1; }
# every point done by exactly one task: rebuild the table without --shard (nothing left to run)
"$rootsim" sweep "$sweep" --out "$out" 2>&1 | tee "$work/collect.log" | tail -1
grep -q "0 ran, 8 already complete, 0 failed" "$work/collect.log" || { echo "FAIL: the array left points undone"; exit 1; }

"$rootsim" sweep "$sweep" -j 2 --out "$work/local" --quiet
if ! diff "$work/local/table.csv" "$out/table.csv"; then echo "FAIL: tables differ"; exit 1; fi
rows=$(($(wc -l <"$out/table.csv") - 1))
[ "$rows" -eq 8 ] || { echo "FAIL: expected 8 rows, table has $rows"; exit 1; }
echo "slurm: table.csv of the job array equals the local -j 2 table row for row ($rows rows)"
