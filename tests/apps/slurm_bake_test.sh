#!/bin/bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# A real scheduler in the tests: starts a single-node Slurm cluster on this
# machine (munge with a fresh key, slurmctld and slurmd as child processes,
# a generated slurm.conf for localhost), submits examples/slurm/submit.sh for
# a small world (a job array of workers and an afterok finalize job), waits,
# and checks the result is byte-identical to a single-process bake. Then the
# faults: a worker killed with SIGKILL leaves no partial tile and its rerun
# completes the bake; an index out of range exits 2 naming it; finalize with
# a missing tile exits non-zero naming it; a Kubernetes-style worker takes
# JOB_COMPLETION_INDEX; the Kubernetes manifests have the structure a
# cluster needs. If the daemons cannot start the test fails with the reason.
#   slurm_bake_test.sh STRATA SOURCE_DIR WORK_DIR
set -euo pipefail
strata=$1 source=$2 work=$3
fail() { echo "slurm_bake_test: FAIL: $*" >&2; exit 1; }
note() { echo "slurm_bake_test: $*"; }

[[ $(id -u) -eq 0 ]] || fail "needs root (slurmd runs jobs as the submitting user, SlurmUser=root)"
for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo python3; do
  command -v "$tool" >/dev/null || fail "$tool is not installed (scripts/install-deps.sh installs slurm-wlm and munge)"
done

rm -rf "$work"
mkdir -p "$work"/{state,spool,log,run}
work=$(cd "$work" && pwd)
daemons=()
cleanup() {
  for pid in "${daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
  [[ -f $work/run/munged.pid ]] && kill "$(cat "$work/run/munged.pid")" 2>/dev/null || true
  for pid in "${daemons[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT

# munge with a fresh key.
dd if=/dev/urandom bs=1024 count=1 of="$work/munge.key" status=none
chmod 400 "$work/munge.key"
munged --key-file "$work/munge.key" --socket "$work/run/munge.socket" --pid-file "$work/run/munged.pid" \
  --log-file "$work/log/munged.log" --seed-file "$work/run/munge.seed" --force ||
  fail "munged did not start: $(tail -3 "$work/log/munged.log" 2>/dev/null)"

# slurm.conf for this host: free ports, this machine's CPUs and memory.
read -r ctld_port slurmd_port < <(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1",0)) for x in s]
print(*[x.getsockname()[1] for x in s])')
host=$(hostname -s)
cpus=$(nproc)
memory=$(( $(free -m | awk '/^Mem:/{print $2}') * 9 / 10 ))
cat > "$work/slurm.conf" <<CONF
ClusterName=strata-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/run/munge.socket
CredType=cred/munge
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MpiDefault=none
SchedulerType=sched/backfill
MinJobAge=600
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D -f "$SLURM_CONF" >"$work/log/slurmd.out" 2>&1 &
daemons+=($!)
for _ in $(seq 60); do
  state=$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)
  [[ $state == idle* ]] && break
  sleep 1
done
[[ ${state:-} == idle* ]] || fail "the node did not come up (state '${state:-none}'): $(tail -5 "$work/log/slurmctld.log" "$work/log/slurmd.log" 2>/dev/null)"
note "slurm up: $host, $cpus CPUs, ${memory} MiB, ports $ctld_port/$slurmd_port"

# A small world: 3 × 3 tiles of 16 m, two slabs, two levels; eroded land
# (a global pass every worker runs, voxel-scale detail in fixed blocks) and
# a layer on the flow mask, so the tiles carry the landform masks.
scene=$work/world.toml
cat > "$scene" <<'TOML'
seed = 3
[terrain]
root = "world"
[terrain.nodes.world]
type = "subtract"
children = ["land", "tunnels"]
[terrain.nodes.land]
type = "erode_detail"
height = "eroded"
cell_size = 0.5
block = 16
droplet_steps = 8
[terrain.nodes.eroded]
type = "erode"
height = "hills"
min = [-32.0, -32.0]
max = [32.0, 32.0]
cell_size = 2.0
years = 2.0e4
time_step = 2.0e3
uplift = 1.0e-4
erodibility = 1.0e-4
[terrain.nodes.hills]
type = "heightfield"
amplitude = 10.0
wavelength = 25.0
[[layer]]
name = "rivers"
side = "sand"
flow_min = 2.5
flow_softness = 0.5
[terrain.nodes.tunnels]
type = "worms"
cell_size = 16.0
min_y = -8.0
max_y = 2.0
radius = 2.0
[region]
min = [-20.0, -12.0, -20.0]
max = [20.0, 8.0, 20.0]
[sampling]
voxel_size = 0.5
TOML
flags=(--tile-size 16 --lods 2)
start=$(date +%s.%N)
"$strata" bake "$scene" -o "$work/single" "${flags[@]}" --threads 1 -q
single=$(python3 -c "import time; print(f'{time.time() - $start:.2f}')")

# The plan, and the example submit script with the plan's array and memory.
"$strata" bake "$scene" "${flags[@]}" --plan --tiles-per-worker 4 | tee "$work/plan.txt"
grep -q '^  array     0-4$' "$work/plan.txt" || fail "--plan: expected 5 workers for 18 tiles, 4 each"
grep -q '^  landform  eroded: 1,089 cells' "$work/plan.txt" || fail "--plan: the erode node's pass is not reported"
cd "$work"
start=$(date +%s.%N)
read -r bake_job final_job < <(STRATA=$strata "$source/examples/slurm/submit.sh" "$scene" "$work/slurm" 4 2 -- "${flags[@]}")
note "submitted array job $bake_job and finalize job $final_job"
for _ in $(seq 300); do
  final_state=$(scontrol show job "$final_job" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1)
  [[ $final_state == COMPLETED || $final_state == FAILED || $final_state == CANCELLED || $final_state == TIMEOUT ]] && break
  sleep 1
done
elapsed=$(python3 -c "import time; print(f'{time.time() - $start:.2f}')")
[[ $final_state == COMPLETED ]] || fail "finalize job $final_job ended $final_state: $(cat "$work"/strata-*.out 2>/dev/null | tail -5)"
tasks=$(scontrol show job "$bake_job" 2>/dev/null | grep -c 'JobState=COMPLETED' || true)
note "slurm bake: $tasks array tasks completed; ${elapsed} s wall (single process, one thread: ${single} s)"

compare() { # compare DIR_A DIR_B: the bake's files, byte for byte (workers' provenance is a log beside it)
  (cd "$1" && find . -type f ! -name '.strata.lock' ! -name '.*.partial-*' ! -path './provenance/*' | sort) > "$work/a.list"
  (cd "$2" && find . -type f ! -name '.strata.lock' ! -name '.*.partial-*' ! -path './provenance/*' | sort) > "$work/b.list"
  diff -q "$work/a.list" "$work/b.list" >/dev/null || fail "$2 holds other files than $1: $(diff "$work/a.list" "$work/b.list" | head -5)"
  while read -r f; do cmp -s "$1/$f" "$2/$f" || fail "$2/$f differs from $1/$f"; done < "$work/a.list"
}
compare "$work/single" "$work/slurm"
note "the Slurm bake is byte-identical to the single-process bake ($(wc -l < "$work/a.list") files)"
cp "$work/slurm/manifest.json" "$work/manifest.first"
"$strata" bake "$work/slurm" --finalize -q
cmp -s "$work/slurm/manifest.json" "$work/manifest.first" || fail "finalize twice gave other bytes"

# A worker killed half-way leaves no partial tile; its rerun completes the bake.
"$strata" bake "$scene" -o "$work/killed" "${flags[@]}" --worker --tiles-per-worker 18 --tile 0 --threads 1 -q &
worker=$!
# Half-way: once two tiles are recorded (the third is being written).
for _ in $(seq 600); do
  [[ $(find "$work/killed/records" -name '*.json' 2>/dev/null | wc -l) -ge 2 ]] && break
  sleep 0.1
done
kill -KILL "$worker" 2>/dev/null || true
wait "$worker" 2>/dev/null || true
partial=0
# (Hidden .NAME.partial-* files are a killed write's temporaries, not final names.)
for f in $(find "$work/killed/tiles" -name '*.glb' ! -name '.*' 2>/dev/null); do
  "$strata" info "$f" >/dev/null 2>&1 || { partial=$((partial + 1)); echo "partial: $f"; }
done
[[ $partial -eq 0 ]] || fail "$partial tile files under their final names are not complete after SIGKILL"
done_before=$(find "$work/killed/records" -name '*.json' 2>/dev/null | wc -l)
[[ $done_before -lt 18 ]] || fail "the worker finished before it was killed"
"$strata" bake "$scene" -o "$work/killed" "${flags[@]}" --worker --tiles-per-worker 18 --tile 0 -q
"$strata" bake "$work/killed" --finalize -q
compare "$work/single" "$work/killed"
note "killed worker: $done_before of 18 tiles done at SIGKILL; rerun + finalize byte-identical"

# An index out of range exits 2 naming it.
set +e
out=$("$strata" bake "$scene" -o "$work/range" "${flags[@]}" --worker --tiles-per-worker 4 --tile 5 2>&1); code=$?
set -e
[[ $code -eq 2 && $out == *"worker index 5 (--tile) is out of range"* ]] || fail "index out of range: exit $code, '$out'"
[[ ! -e $work/range ]] || fail "an out-of-range worker created its folder"
set +e
out=$(SLURM_ARRAY_TASK_ID=7 "$strata" bake "$scene" -o "$work/range" "${flags[@]}" --worker --tiles-per-worker 4 2>&1); code=$?
set -e
[[ $code -eq 2 && $out == *"worker index 7 (SLURM_ARRAY_TASK_ID)"* ]] || fail "SLURM_ARRAY_TASK_ID out of range: exit $code, '$out'"

# Finalize with a missing tile exits non-zero naming it and the command.
cp -r "$work/single" "$work/missing"
rm "$work/missing/records/7.json" "$work/missing/manifest.json"
set +e
out=$("$strata" bake "$work/missing" --finalize 2>&1); code=$?
set -e
[[ $code -ne 0 && $out == *"tiles are missing or damaged: 7;"* && $out == *"--tiles 7"* ]] ||
  fail "finalize with tile 7 missing: exit $code, '$out'"
[[ ! -e $work/missing/manifest.json ]] || fail "finalize with a missing tile wrote a manifest"

# Kubernetes: the index reaches the worker through JOB_COMPLETION_INDEX.
JOB_COMPLETION_INDEX=2 "$strata" bake "$scene" -o "$work/k8s" "${flags[@]}" --worker --tiles-per-worker 4 -q
records=$(cd "$work/k8s/records" && ls | sort -n | tr '\n' ' ')
[[ $records == "8.json 9.json 10.json 11.json " ]] || fail "JOB_COMPLETION_INDEX=2 baked records '$records', expected tiles 8-11"
python3 - "$source/examples/kubernetes" <<'PY' || fail "the Kubernetes manifests"
import sys, yaml, pathlib
d = pathlib.Path(sys.argv[1])
bake = yaml.safe_load((d / "bake-job.yaml").read_text())
final = yaml.safe_load((d / "finalize-job.yaml").read_text())
claim = yaml.safe_load((d / "volume.yaml").read_text())
spec = bake["spec"]
assert bake["kind"] == "Job" and bake["apiVersion"] == "batch/v1"
assert spec["completionMode"] == "Indexed", "completionMode"
assert isinstance(spec["completions"], int) and spec["completions"] > 0
assert 0 < spec["parallelism"] <= spec["completions"]
c = spec["template"]["spec"]["containers"][0]
assert c["command"][:2] == ["strata", "bake"] and "--worker" in c["command"], c["command"]
assert "--tile" not in c["command"], "the index must come from JOB_COMPLETION_INDEX"
out = c["command"][c["command"].index("-o") + 1]
mounts = {m["mountPath"]: m["name"] for m in c["volumeMounts"]}
assert out in mounts, "the output folder is a mounted volume"
vols = {v["name"]: v for v in spec["template"]["spec"]["volumes"]}
assert vols[mounts[out]]["persistentVolumeClaim"]["claimName"] == claim["metadata"]["name"]
assert "ReadWriteMany" in claim["spec"]["accessModes"]
fc = final["spec"]["template"]["spec"]["containers"][0]
assert fc["command"][:2] == ["strata", "bake"] and "--finalize" in fc["command"]
fout = fc["command"][2]
fm = {m["mountPath"]: m["name"] for m in fc["volumeMounts"]}
fv = {v["name"]: v for v in final["spec"]["template"]["spec"]["volumes"]}
assert fout in fm and fv[fm[fout]]["persistentVolumeClaim"]["claimName"] == claim["metadata"]["name"]
print("slurm_bake_test: Kubernetes manifests: Indexed Job of", spec["completions"], "completions,", spec["parallelism"], "at a time; finalize Job; shared claim", claim["metadata"]["name"])
PY
note "OK"
