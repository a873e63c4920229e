#!/usr/bin/env bash
# The Slurm job array of docs/sweeps.md, run for real on a one-node cluster
# started here: slurmctld, slurmd and munged from Debian's
# packages, on the loopback address only, with their state in a temporary
# folder. It submits scripts/slurm/t7.sbatch (the docs' script) on a small
# grid, kills one task mid-run with scancel, resubmits it (its finished runs
# must be kept), merges by dependency as the docs say, and checks that the
# merged sweep.csv is byte-identical to the same sweep on one machine.
#
# Usage: scripts/slurm_test.sh [TAUT_BINARY]   (default target/release/taut)
# Skips with a clear message (exit 0) where a cluster cannot be started: not
# root, no package manager, packages that will not install, daemons that do
# not come up. Stops only the daemons it started, by their pid files.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TAUT_BIN="$(realpath "${1:-$ROOT/target/release/taut}")"
START=$SECONDS

skip() {
  echo "slurm test: SKIPPED: $*"
  exit 0
}
fail() {
  echo "slurm test: FAILED: $*" >&2
  exit 1
}

[ -x "$TAUT_BIN" ] || fail "no taut binary at $TAUT_BIN (build it first)"
[ "$(id -u)" = 0 ] || skip "needs root to install and start slurmctld, slurmd and munged"

# --- packages -------------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
  || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  command -v apt-get >/dev/null || skip "no apt-get to install Slurm from Debian's packages"
  echo "slurm test: installing slurmctld, slurmd, slurm-client and munge (apt-get)"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
    --no-install-recommends slurmctld slurmd slurm-client munge) >/tmp/taut-slurm-apt.log 2>&1 \
    || skip "the Slurm packages did not install (log: /tmp/taut-slurm-apt.log)"
fi

WORK="$(mktemp -d /tmp/taut-slurm.XXXXXX)"
PIDS=()
cleanup() {
  # this cluster's jobs first (SLURM_CONF names it), then its daemons
  if [ -n "${SLURM_CONF:-}" ] && [ -s "$WORK/slurmctld.pid" ]; then
    jobs=$(squeue -h -o %i 2>/dev/null || true)
    [ -z "$jobs" ] || scancel $jobs 2>/dev/null || true
    sleep 1
  fi
  local pids=()
  for f in "${PIDS[@]}"; do
    [ -s "$f" ] && pids+=("$(cat "$f")")
  done
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.2; done
  done
  # the folder only once its daemons are gone (their pid files are in it)
  cd / && rm -rf "$WORK"
}
trap cleanup EXIT

# --- munge: the authentication Slurm's daemons and clients use ------------
if [ ! -S /run/munge/munge.socket.2 ]; then
  mkdir -p /etc/munge /run/munge /var/lib/munge /var/log/munge
  if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge
  chmod 0700 /etc/munge && chmod 0400 /etc/munge/munge.key
  runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/taut-test-munged.pid \
    || skip "munged did not start"
  PIDS+=(/run/munge/taut-test-munged.pid)
fi

# --- a one-node cluster on the loopback address ---------------------------
HOST="$(hostname -s)"
CPUS="$(nproc)"
mkdir -p "$WORK/ctld" "$WORK/d" "$WORK/job"
export SLURM_CONF="$WORK/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=taut
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$WORK/ctld
SlurmdSpoolDir=$WORK/d
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=taut-node NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=debug Nodes=taut-node Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF" || skip "slurmctld did not start (log: $WORK/slurmctld.log)"
PIDS+=("$WORK/slurmctld.pid")
slurmd -f "$SLURM_CONF" -N taut-node || skip "slurmd did not start (log: $WORK/slurmd.log)"
PIDS+=("$WORK/slurmd.pid")
for _ in $(seq 60); do
  state="$(sinfo -h -o %t 2>/dev/null || true)"
  [ "$state" = idle ] && break
  sleep 1
done
[ "$state" = idle ] || skip "the node did not come up (state '$state'; logs in $WORK)"
echo "slurm test: one-node cluster up ($CPUS CPUs) after $((SECONDS - START)) s"

# --- the docs' job array, on a small grid ----------------------------------
cd "$WORK/job"
cp -r "$ROOT/scenes" .
cp "$ROOT/scripts/slurm/t7.sbatch" .
mkdir -p bin && ln -s "$TAUT_BIN" bin/taut
export PATH="$WORK/job/bin:$PATH"
# 12 points in 4 shards, each run about a second (so a task can be killed
# between its runs)
export SHARDS=4 TENSION=2.01e4:4.02e4:3 SPEED=50:230:4 ELEMENTS=800 STEP=1e-6 END=0.15
SWEEP_ARGS=(--vary beam.tension=$TENSION --vary carrier.speed.cruise=$SPEED
  --set mesh.elements=$ELEMENTS --set time.step=$STEP --set time.end=$END)

# as the docs say: the array, then the merge by dependency
jobid=$(sbatch --parsable --array=0-3 --cpus-per-task=1 t7.sbatch)
merge1=$(sbatch --parsable --dependency=afterok:$jobid --kill-on-invalid-dep=yes \
  --wrap 'taut merge shards/* --out map')

# kill task 3 once it has finished a run and before it finishes all three
for _ in $(seq 600); do
  n=$( (ls shards/3/runs/*.json 2>/dev/null || true) | wc -l)
  [ "$n" -ge 1 ] && break
  sleep 0.2
done
[ "$n" -ge 1 ] || fail "task 3 never finished a run"
[ "$n" -lt 3 ] || fail "task 3 finished before it could be killed (runs too short)"
scancel "${jobid}_3"
echo "slurm test: killed task 3 after $n of its 3 runs"
kept=$(ls shards/3/runs/*.json)
declare -A before
for f in $kept; do before[$f]=$(stat -c %Y.%y "$f"); done

# wait for the rest of the array; the merge's dependency can no longer be met
for _ in $(seq 600); do
  [ -z "$(squeue -h -j "$jobid" -o %i 2>/dev/null)" ] && break
  sleep 1
done
sleep 2
if squeue -h -j "$merge1" -o %T 2>/dev/null | grep -q .; then
  reason=$(squeue -h -j "$merge1" -o %r)
  scancel "$merge1"
  echo "slurm test: the first merge waited on a dependency never satisfied ($reason): cancelled"
else
  echo "slurm test: the first merge was dropped (its dependency can no longer be met)"
fi
[ ! -e map/sweep.csv ] || fail "a merge ran with a shard missing"

# resubmit the killed task (its finished runs are kept), merge after it
redo=$(sbatch --parsable --array=3 --cpus-per-task=1 t7.sbatch)
merge2=$(sbatch --parsable --dependency=afterok:$redo --wrap 'taut merge shards/* --out map')
for _ in $(seq 900); do
  [ -z "$(squeue -h -j "$redo,$merge2" -o %i 2>/dev/null)" ] && break
  sleep 1
done
[ -s map/sweep.csv ] || fail "the merge wrote no sweep.csv (see $WORK/job/slurm-$merge2.out)"
for f in $kept; do
  [ "$(stat -c %Y.%y "$f")" = "${before[$f]}" ] || fail "$f was run again after the resubmission"
done
grep -q "$((3 - n)) run now, $n kept from an earlier start" t7_3.out \
  || fail "the resubmitted task did not keep its $n finished runs: $(tr '\n' ' ' <t7_3.out)"
echo "slurm test: the resubmitted task kept its $n finished runs and ran $((3 - n))"

# the same sweep on one machine: byte-identical tables
taut sweep scenes/reference.toml "${SWEEP_ARGS[@]}" --out one --quiet >/dev/null
for f in sweep.csv sweep_force.csv sweep_loss.csv; do
  cmp -s one/$f map/$f || fail "map/$f differs from the one-machine sweep's"
done
echo "slurm test: merged sweep.csv, sweep_force.csv and sweep_loss.csv byte-identical to the one-machine sweep"
echo "slurm test: passed in $((SECONDS - START)) s"
