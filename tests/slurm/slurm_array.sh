#!/usr/bin/env bash
# ctest slurm_array: a real Slurm on localhost in a temporary folder (munged, slurmctld, slurmd of
# Debian's munge and slurm-wlm; its own key, sockets, slurm.conf, state and spool; one node with
# this machine's cores; no cgroups), a 4-task array of path ranges through
# scripts/slurm/submit_paths.sh and the merge depending on it, then the merged image against a
# single-process render; then a 2-task array of walkthrough frame ranges (submit_frames.sh). Every daemon it started is stopped on any exit.
# Usage: slurm_array.sh IRAD SOURCE_DIR   (as root: SlurmUser=root)
set -euo pipefail
irad="$1" src="$2"
fail() { echo "slurm_array: FAIL: $*" >&2; exit 1; }
for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol; do
  command -v "$tool" >/dev/null || fail "$tool is not installed (scripts/setup.sh installs munge and slurm-wlm)"
done
if [ "$(id -u)" -ne 0 ]; then echo "slurm_array: skipped: needs root (SlurmUser=root, as in CI)"; exit 77; fi

dir="$(mktemp -d /tmp/irad-slurm.XXXXXX)"
pids=()
stop() {
  local pid
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  [ "${IRAD_KEEP_SLURM_DIR:-0}" = 1 ] || rm -rf "$dir"
}
trap stop EXIT

# Ports from the process id, so that two runs (or another Slurm) do not collide.
port=$((20000 + ($$ % 20000)))
host="$(hostname -s)"
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/out"
chmod 711 "$dir/munge"
mungekey --create --keyfile="$dir/munge/munge.key" 2>/dev/null ||
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged -F --force --socket="$dir/munge/socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
  --seed-file="$dir/munge/munged.seed" >"$dir/munge/munged.out" 2>&1 &
pids+=($!)

cat >"$dir/slurm.conf" <<CONF
ClusterName=irad-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=irad Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
for _ in $(seq 50); do [ -S "$dir/munge/socket" ] && break; sleep 0.1; done
[ -S "$dir/munge/socket" ] || fail "munged did not start: $(tail -3 "$dir/munge/munged.log")"
slurmctld -D -i >"$dir/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N "$host" >"$dir/slurmd.out" 2>&1 &
pids+=($!)
deadline=$((SECONDS + 240)) # the one bound on every wait below
until sinfo -h -N -o '%T' 2>/dev/null | grep -q -E '^(idle|mixed|allocated)'; do
  [ $SECONDS -lt $deadline ] || fail "the node did not come up: $(tail -3 "$dir/slurmctld.log")"
  sleep 0.5
done

# 64x64, N = 64: the parts and the single render of the same options.
scene="$src/data/cornell_box.gltf"
opts=(--size 64x64 --gl osmesa)
merge=$(IRAD="$irad" bash "$src/scripts/slurm/submit_paths.sh" "$scene" 64 4 "$dir/out" "${opts[@]}")
while squeue -h -j "$merge" 2>/dev/null | grep -q .; do
  [ $SECONDS -lt $deadline ] || fail "the jobs did not finish in 240 s: $(squeue 2>&1 | tail -5)"
  sleep 1
done
state=$(scontrol show job "$merge" | grep -o 'JobState=[A-Z_]*' || true)
[ "$state" = JobState=COMPLETED ] ||
  fail "merge job $merge: $state; $(cat "$dir"/out/slurm-*.out 2>/dev/null | tail -5)"
[ "$(ls "$dir"/out/part_*.exr | wc -l)" -eq 4 ] || fail "not 4 parts: $(ls "$dir/out")"
"$irad" render "$scene" --paths 64 "${opts[@]}" --quiet -o "$dir/single.exr"
# The bound: docs/cluster.md (4 parts against one process at 64x64: measured max |diff| 1.9e-6,
# one float ulp of the emitter's radiance (16..32), elsewhere ~1e-7: float accumulation order);
# 1e-5 is five such ulps, and a lost or doubled VPL moves pixels by ~1e-3.
"$irad" compare "$dir/out/merged.exr" "$dir/single.exr" --json "$dir/compare.json" >/dev/null
python3 - "$dir/compare.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
print("slurm_array: merged vs single:", {k: c[k] for k in c if k in ("max_abs_error", "relmse", "rmse")})
bad = c["max_abs_error"]
sys.exit(0 if bad <= 1e-5 else 1)
PY

# Frames: a 2-task array of frame ranges of a walkthrough (scripts/slurm/submit_frames.sh), each
# task its share of 0:6.
frames=$(IRAD="$irad" bash "$src/scripts/slurm/submit_frames.sh" "$scene" 0:6 2 "$dir/frames" \
  --paths 8 --size 32x32 --gl osmesa)
while squeue -h -j "$frames" 2>/dev/null | grep -q .; do
  [ $SECONDS -lt $deadline ] || fail "the frame jobs did not finish in 240 s"
  sleep 1
done
for f in 0 1 2 3 4 5; do
  [ -s "$dir/frames/frame_000$f.png" ] || fail "frame $f missing: $(ls "$dir/frames")"
done
echo "slurm_array: OK (4 path-range tasks, the merge and 2 frame-range tasks on $host)"
