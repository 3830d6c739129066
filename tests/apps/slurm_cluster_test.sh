#!/bin/bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# A Slurm cluster of four hosts on this machine, and a bake across it.
# Each host is a network namespace with its own address on a bridge (veth
# pairs; the bridge lives in a namespace of its own, so no traffic reaches
# or leaves this machine's network) and its own host name (a UTS
# namespace): slurmctld on "ctl" (10.77.0.1), slurmd on n1 and n2 (x86_64,
# this build of strata) and n3, whose strata is the aarch64 build run under
# qemu-user (its own mount namespace puts that build where the others have
# theirs, as each node of a real mixed cluster installs its own). One munge
# key. The bake folder is a tmpfs mounted before the hosts start, so every
# host sees the same file system at the same path, as NFS would give.
#
#   slurm_cluster_test.sh CASE STRATA ARM_STRATA ARM_SYSROOT SOURCE_DIR WORK_DIR
#
# CASE (each a ctest case; each bakes a crop of mountains4k.toml with
# erosion, voxel-scale detail, caves and the landform masks as a job array
# over the three nodes, then finalizes, and the result must be the bytes
# of a single process, with no temporary file or lock left behind):
#   bake          no fault; the report says which node baked which tile
#   node-lost     every process of n2 (slurmd, its tasks) killed mid-array:
#                 Slurm marks n2 down and requeues its task elsewhere
#   kill-tile     a worker SIGKILLed mid-tile: no partial tile visible, the
#                 task requeued by hand (scontrol requeue) writes the rest
#   scancel       a running task cancelled (SIGTERM): the worker exits on
#                 its own before Slurm's SIGKILL, the folder lock is free,
#                 a resubmitted task finishes the bake
#   controller    slurmctld stopped and restarted mid-array: the array
#                 goes on from its saved state
#   disk-full     the bake folder fills up: tasks fail naming the file and
#                 the cause, nothing partial is left, and after the disk is
#                 enlarged a rerun of the failed tasks completes the bake
#   measure       (by hand) tiles per minute on 1, 2 and 3 nodes, the
#                 scheduler's overhead per task, the qemu node's cost
# Fails (never skips) when slurm, munge, qemu-user, the aarch64 build or
# network namespaces are missing, naming what.
set -euo pipefail
case_name=$1 strata=$2 arm_strata=$3 sysroot=$4 source=$5 work=$6
fail() { echo "slurm_cluster_test[$case_name]: FAIL: $*" >&2; exit 1; }
note() { echo "slurm_cluster_test[$case_name]: $*"; }
now() { date +%s.%N; }
since() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$(now)"; }

case $case_name in
bake | node-lost | kill-tile | scancel | controller | disk-full | measure) ;;
*) fail "unknown case '$case_name' (bake, node-lost, kill-tile, scancel, controller, disk-full, measure)" ;;
esac
[[ $(id -u) -eq 0 ]] || fail "needs root (network namespaces, mounts, slurmd)"
for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo scancel ip nsenter unshare mount qemu-aarch64 python3 flock; do
  command -v "$tool" >/dev/null ||
    fail "$tool is not installed (scripts/install-deps.sh installs slurm-wlm, munge, qemu-user and iproute2)"
done
[[ -x $strata ]] || fail "no strata at '$strata'"
[[ -x $arm_strata ]] ||
  fail "no aarch64 strata at '$arm_strata': scripts/determinism-builds.sh aarch64 builds it (build-aarch64/apps/strata/strata)"
[[ -f $sysroot/.complete ]] || fail "no arm64 package folder at '$sysroot' (scripts/determinism-builds.sh aarch64 makes it)"
qemu-aarch64 -L "$sysroot" "$arm_strata" --version >/dev/null 2>&1 ||
  fail "the aarch64 strata does not run under qemu-aarch64 -L $sysroot: $(qemu-aarch64 -L "$sysroot" "$arm_strata" --version 2>&1 | tail -2)"

rm -rf "$work"
mkdir -p "$work"/{state,log,run,jobs,shared,bin,arm-bin} "$work"/spool/{n1,n2,n3}
work=$(cd "$work" && pwd)
strata=$(realpath "$strata") arm_strata=$(realpath "$arm_strata") sysroot=$(realpath "$sysroot")

# Names unique to this run: ctest may run another case's cluster later,
# and a crashed run's namespaces must not collide with this one's.
tag=sc$(($$ % 100000))
ns_bridge=${tag}b ns_ctl=${tag}c
nodes=(n1 n2 n3)
declare -A ns_of=([ctl]=$ns_ctl [n1]=${tag}1 [n2]=${tag}2 [n3]=${tag}3)
declare -A addr_of=([ctl]=10.77.0.1 [n1]=10.77.0.11 [n2]=10.77.0.12 [n3]=10.77.0.13)

cleanup() {
  set +e
  for host in n1 n2 n3 ctl; do
    ip netns pids "${ns_of[$host]}" 2>/dev/null | xargs -r kill -KILL 2>/dev/null
  done
  [[ -f $work/run/munged.pid ]] && kill "$(cat "$work/run/munged.pid")" 2>/dev/null
  sleep 0.2
  mountpoint -q "$work/shared" && umount -l "$work/shared"
  for ns in "${ns_of[@]}" "$ns_bridge"; do ip netns del "$ns" 2>/dev/null; done
}
trap cleanup EXIT

# The network: a bridge in a namespace of its own, a veth pair per host.
ip netns add "$ns_bridge" || fail "cannot create network namespaces (ip netns add): this test needs CAP_NET_ADMIN and CAP_SYS_ADMIN"
ip -n "$ns_bridge" link add br0 type bridge
ip -n "$ns_bridge" link set br0 up
for host in ctl n1 n2 n3; do
  ns=${ns_of[$host]}
  ip netns add "$ns"
  ip link add "v$host" netns "$ns_bridge" type veth peer name eth0 netns "$ns"
  ip -n "$ns_bridge" link set "v$host" master br0 up
  ip -n "$ns" addr add "${addr_of[$host]}/24" dev eth0
  ip -n "$ns" link set eth0 up
  ip -n "$ns" link set lo up
done

# The shared folder: its own file system (disk-full: a small one).
shared_size=256m
[[ $case_name == disk-full ]] && shared_size=${DISK_FULL_SIZE:-1m}
mount -t tmpfs -o "size=$shared_size,mode=0755" strata-shared "$work/shared"

# The same path, another build on each architecture.
printf '#!/bin/sh\nexec %q "$@"\n' "$strata" > "$work/bin/strata"
printf '#!/bin/sh\nexec qemu-aarch64 -L %q %q "$@"\n' "$sysroot" "$arm_strata" > "$work/arm-bin/strata"
chmod +x "$work/bin/strata" "$work/arm-bin/strata"
STRATA_ON_NODES=$work/bin/strata

# munge: one key (every host of a real cluster holds a copy).
dd if=/dev/urandom bs=1024 count=1 of="$work/munge.key" status=none
chmod 400 "$work/munge.key"
munged --key-file "$work/munge.key" --socket "$work/run/munge.socket" --pid-file "$work/run/munged.pid" \
  --log-file "$work/log/munged.log" --seed-file "$work/run/munge.seed" --force ||
  fail "munged did not start: $(tail -3 "$work/log/munged.log" 2>/dev/null)"

memory=3072
cat > "$work/slurm.conf" <<CONF
ClusterName=strata-cluster
SlurmctldHost=ctl(${addr_of[ctl]})
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/run/munge.socket
CredType=cred/munge
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool/%n
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd-%n.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
SchedulerType=sched/backfill
# Batch tasks start at most every batch_sched_delay seconds (Slurm's
# default, 3 s, is most of a small task's cost here; measure: both).
SchedulerParameters=batch_sched_delay=${CLUSTER_BATCH_SCHED_DELAY:-0}
ReturnToService=2
# A lost node is noticed within seconds (a real cluster: minutes) and its
# batch tasks requeued (the bake's workers are idempotent).
SlurmdTimeout=6
MessageTimeout=4
JobRequeue=1
KillWait=10
MinJobAge=600
NodeName=n1 NodeAddr=${addr_of[n1]} CPUs=1 RealMemory=$memory Feature=x86_64 State=UNKNOWN
NodeName=n2 NodeAddr=${addr_of[n2]} CPUs=1 RealMemory=$memory Feature=x86_64 State=UNKNOWN
NodeName=n3 NodeAddr=${addr_of[n3]} CPUs=1 RealMemory=$memory Feature=aarch64 State=UNKNOWN
PartitionName=main Nodes=n[1-3] Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf

# A host: its namespace, its host name, and (n3) its own strata build.
start_controller() {
  nsenter --net="/run/netns/$ns_ctl" unshare --uts -- bash -c 'hostname ctl; exec slurmctld -D "$@"' _ "$@" \
    >>"$work/log/slurmctld.out" 2>&1 &
  disown
}
start_node() {
  local host=$1 bind=:
  [[ $host == n3 ]] && bind="mount --bind $work/arm-bin $work/bin"
  nsenter --net="/run/netns/${ns_of[$host]}" unshare --uts --mount --propagation private -- \
    bash -c "hostname $host && $bind && exec slurmd -D" >>"$work/log/slurmd-$host.out" 2>&1 &
  disown
}
# nsenter, not `ip netns exec`: that remounts /sys, hiding the cgroup
# hierarchy slurmd needs.
on_ctl() { nsenter --net="/run/netns/$ns_ctl" "$@"; }
start_controller -c
for host in "${nodes[@]}"; do start_node "$host"; done
for _ in $(seq 60); do
  idle=$(on_ctl sinfo -h -N -o '%N %T' 2>/dev/null | grep -c ' idle' || true)
  [[ $idle -eq 3 ]] && break
  sleep 1
done
[[ $idle -eq 3 ]] || fail "the nodes did not come up: $(on_ctl sinfo -N 2>&1 | tail -4; tail -3 "$work"/log/slurm*.log 2>/dev/null)"
# CLUSTER_HOLD=SECONDS keeps the cluster up that long before the case
# (to look around: nsenter --net=/run/netns/NAME squeue, with SLURM_CONF).
if [[ -n ${CLUSTER_HOLD:-} ]]; then
  note "holding the cluster for $CLUSTER_HOLD s: SLURM_CONF=$SLURM_CONF nsenter --net=/run/netns/$ns_ctl squeue"
  sleep "$CLUSTER_HOLD"
fi
note "cluster up: ctl ${addr_of[ctl]}; n1 ${addr_of[n1]}, n2 ${addr_of[n2]} (x86_64); n3 ${addr_of[n3]} (aarch64 under qemu-user)"

# The world: a 64 m crop of mountains4k at 1 m voxels (eroded land,
# rills and talus, rock relief, a worm tunnel 3-15 m under the ground,
# the landform masks in its layers), 4 × 4 × 4 tiles of 16 m, two levels.
scene=$work/jobs/mountains4k-crop.toml
python3 "$source/tests/apps/crop_scene.py" "$source/examples/worlds/mountains4k.toml" "$scene" -1408 512 64 120 184
flags=(--tile-size 16 --lods 2)
per_worker=4
tiles=64
workers=$((tiles / per_worker))
start=$(now)
"$strata" bake "$scene" -o "$work/single" "${flags[@]}" --threads 2 -q
note "single process (this machine, 2 threads): $(since "$start") s"
bake=$work/shared/bake

job_state() { on_ctl scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }
# The states of the array's tasks, one "INDEX STATE NODE" line each.
task_states() {
  on_ctl squeue -h -r -j "$1" -t all -o '%K %T %N' 2>/dev/null | sort -n
}
wait_array_done() { # wait_array_done JOB SECONDS: until no task is pending or running
  local job=$1 limit=$2 left
  for _ in $(seq $((limit * 4))); do
    left=$(on_ctl squeue -h -r -j "$job" -t PENDING,RUNNING,CONFIGURING,COMPLETING,REQUEUED 2>/dev/null | wc -l)
    [[ $left -eq 0 ]] && return 0
    sleep 0.25
  done
  fail "array $job still has $left tasks after $limit s: $(task_states "$job" | tr '\n' ';')"
}
wait_job() { # wait_job JOB SECONDS: prints its final state
  local state
  for _ in $(seq $(($2 * 4))); do
    state=$(job_state "$1")
    case $state in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) break ;; esac
    sleep 0.25
  done
  echo "$state"
}
submit() { # the README's way: examples/slurm/submit.sh; prints "ARRAY FINAL"
  (cd "$work/jobs" && on_ctl env STRATA="$STRATA_ON_NODES" "$source/examples/slurm/submit.sh" \
    "$scene" "$bake" "$per_worker" 8 -- "${flags[@]}")
}
submit_tasks() { # submit_tasks ARRAY_SPEC [SBATCH FLAGS]: bake tasks (again), waits, prints the job
  local job
  job=$(cd "$work/jobs" && on_ctl env STRATA="$STRATA_ON_NODES" sbatch --parsable --array="$1" --mem=1024M \
    "${@:2}" "$source/examples/slurm/bake.sbatch" "$scene" "$bake" "$per_worker" "${flags[@]}")
  # sbatch --wait polls at growing intervals (seconds late): poll here.
  wait_array_done "$job" 600 >&2
  echo "$job"
}
strata_pid() { # the strata worker running in HOST's namespace (qemu's on n3)
  local pid
  for pid in $(ip netns pids "${ns_of[$1]}" 2>/dev/null); do
    if { tr '\0' ' ' < "/proc/$pid/cmdline"; } 2>/dev/null | grep -qE 'strata bake .*--worker'; then
      echo "$pid"; return 0
    fi
  done
}
# A requeued batch task waits about two minutes (Slurm sets its begin
# time); an operator (here the test) may start it at once.
release_requeued() { # release_requeued JOB: fails if none is held
  local held
  for _ in $(seq 60); do
    held=$(on_ctl squeue -h -r -j "$1" -t PENDING -o '%i %r' | awk '$2 == "BeginTime" {print $1}')
    [[ -n $held ]] && break
    sleep 0.5
  done
  [[ -n $held ]] || return 1
  for task in $held; do on_ctl scontrol update JobId="$task" StartTime=now; done
}
# Signals the worker busy on HOST once tiles are recorded and the worker is
# past its start-up (it catches SIGTERM: /proc/PID/status SigCgt), with
# SIGKILL to the process or TERM through scancel (Slurm's way: SIGTERM,
# SIGKILL after KillWait). Retries when the task ends first. Prints
# "INDEX PID".
signal_worker() { # signal_worker HOST KILL|TERM
  local pid index again caught
  for _ in $(seq 3000); do
    pid=$(strata_pid "$1")
    caught=$(sed -n 's/^SigCgt:\s*//p' "/proc/$pid/status" 2>/dev/null || true)
    if [[ -n $pid && -n $caught && $(records) -ge 2 ]] && (((0x$caught >> 14) & 1)); then
      index=$(on_ctl squeue -h -r -j "$array_job" -t RUNNING -w "$1" -o '%K' | head -1)
      again=$(strata_pid "$1")
      # The same worker before and after: it is the task squeue saw.
      if [[ -n $index && $again == "$pid" ]]; then
        if [[ $2 == KILL ]]; then
          kill -KILL "$pid" 2>/dev/null && { echo "$index $pid"; return 0; }
        else
          on_ctl scancel "${array_job}_$index" 2>/dev/null && kill -0 "$pid" 2>/dev/null &&
            { echo "$index $pid"; return 0; }
        fi
      fi
    fi
    sleep 0.02
  done
  fail "no worker on $1 could be signalled ($2)"
}
# No partial file under a final name: every .glb present is as long as
# its header says (a write cut short is shorter).
whole_tiles() { # whole_tiles WHEN
  local cut
  cut=$(python3 - "$bake/tiles" <<'PY'
import pathlib, struct, sys
for f in sorted(pathlib.Path(sys.argv[1]).rglob("*.glb")):
    if f.name.startswith("."):
        continue  # a write's temporary (.NAME.partial-*), not a final name
    b = f.read_bytes()
    if len(b) < 12 or b[:4] != b"glTF" or struct.unpack_from("<I", b, 8)[0] != len(b):
        print(f)
PY
)
  [[ -z $cut ]] || fail "partial tiles under their final names $1: $cut"
}
records() { { find "$bake/records" -name '*.json' 2>/dev/null || true; } | wc -l; }

await_final() { # await_final WHEN: submit.sh's finalize job completes; its log holds the report
  local state
  state=$(wait_job "$final_job" 300)
  [[ $state == COMPLETED ]] ||
    fail "finalize job $final_job ended ${state:-unknown} $1: $(tail -5 "$work/jobs/strata-finalize-$final_job.out" 2>/dev/null)"
  finalize_out=$work/jobs/strata-finalize-$final_job.out
}
finalize() { # a finalize job (afterok cannot be met after a failed task: submitted anew)
  local job state
  job=$(cd "$work/jobs" && on_ctl env STRATA="$STRATA_ON_NODES" sbatch --parsable \
    "$source/examples/slurm/finalize.sbatch" "$bake")
  state=$(wait_job "$job" 300)
  [[ $state == COMPLETED ]] || fail "finalize job $job ended ${state:-unknown}: $(tail -5 "$work/jobs/strata-finalize-$job.out" 2>/dev/null)"
  finalize_out=$work/jobs/strata-finalize-$job.out
}

compare() { # the bake against the single process, byte for byte; no litter, no held lock
  (cd "$work/single" && find . -type f ! -name '.strata.lock' | sort) > "$work/a.list"
  (cd "$bake" && find . -type f ! -name '.strata.lock' ! -path './provenance/*' | sort) > "$work/b.list"
  diff -q "$work/a.list" "$work/b.list" >/dev/null ||
    fail "the cluster's bake holds other files than the single process's: $(diff "$work/a.list" "$work/b.list" | head -5 | tr '\n' ' ')"
  while read -r f; do cmp -s "$work/single/$f" "$bake/$f" || fail "$f differs from the single process's"; done < "$work/a.list"
  litter=$(find "$bake" -name '.*partial-*' | head -3)
  [[ -z $litter ]] || fail "temporary files left after finalize: $litter"
  [[ ! -e $bake/.strata.lock ]] || flock -n "$bake/.strata.lock" true || fail "the bake folder's lock is still held"
  note "byte-identical to the single process ($(wc -l < "$work/a.list") files); no temporary file or lock left"
}

report() { # which node baked which tile, from finalize's report; every tile once
  grep 'baked by' "$finalize_out" | sed 's/^ */  /'
  # Only a full disk may keep a tile whose provenance it could not write.
  if [[ $case_name != disk-full ]] && grep -q 'baked by  unknown' "$finalize_out"; then
    fail "tiles without provenance: $(grep 'baked by  unknown' "$finalize_out")"
  fi
  local total
  total=$(sed -n 's/.*baked by  [^ ]* ([^)]*): \([0-9]*\) tiles.*/\1/p' "$finalize_out" | awk '{n += $1} END {print n + 0}')
  [[ $total -eq $tiles ]] || fail "the report accounts for ${total:-0} of $tiles tiles"
}

# The array through the README's submit script; afterwards every task
# must have COMPLETED (after requeues) and the finalize job with it.
submit_and_wait() {
  read -r array_job final_job < <(submit)
  note "submitted array $array_job ($workers tasks of $per_worker tiles) and finalize $final_job"
}
expect_completed() {
  local bad
  bad=$(task_states "$array_job" | awk '$2 != "COMPLETED"')
  [[ -z $bad ]] || fail "array tasks not completed: $(tr '\n' ';' <<<"$bad")"
}

case $case_name in
bake)
  start=$(now)
  submit_and_wait
  await_final "without a fault"
  note "the array and finalize took $(since "$start") s"
  expect_completed
  report
  for host in n1 n2 n3; do grep -q "baked by  $host (" "$finalize_out" || fail "$host baked no tile"; done
  grep -q 'baked by  n3 (aarch64)' "$finalize_out" || fail "n3's tiles were not baked by the aarch64 build"
  grep -q 'baked by  n1 (x86_64)' "$finalize_out" || fail "n1's tiles were not baked by the x86_64 build"
  compare
  ;;
node-lost)
  submit_and_wait
  # Mid-array: tiles recorded, and a worker running on n2.
  for _ in $(seq 600); do
    [[ $(records) -ge 2 && -n $(strata_pid n2) ]] && break
    sleep 0.1
  done
  [[ -n $(strata_pid n2) ]] || fail "no worker ran on n2"
  # The node dies: its slurmd, slurmstepd and the worker, all at once.
  ip netns pids "${ns_of[n2]}" | xargs -r kill -KILL
  note "n2 lost mid-task ($(records) of $tiles tiles recorded)"
  # Slurm notices within SlurmdTimeout and requeues the task.
  release_requeued "$array_job" || fail "Slurm requeued no task of the lost node: $(task_states "$array_job" | tr '\n' ';')"
  wait_array_done "$array_job" 600
  expect_completed
  # The task n2 was running: requeued by Slurm (Restarts), ended elsewhere.
  requeued=$(on_ctl scontrol -o show job "$array_job" |
    sed -n 's/.*ArrayTaskId=\([0-9]*\) .*Restarts=\([1-9][0-9]*\) .*NodeList=\([^ ]*\) .*/\1 \3/p')
  [[ -n $requeued ]] || fail "no task was requeued after n2 was lost"
  while read -r index node; do
    [[ $node != n2 ]] || fail "task $index was requeued but finished on the lost node"
    note "task $index requeued by Slurm, finished on $node"
  done <<<"$requeued"
  note "n2 is $(on_ctl sinfo -h -n n2 -o '%T')"
  await_final "after the requeue"
  report
  compare
  ;;
kill-tile)
  submit_and_wait
  read -r index pid < <(signal_worker n1 KILL)
  note "SIGKILLed the worker of task $index on n1 ($(records) of $tiles tiles recorded)"
  wait_array_done "$array_job" 600
  state=$(task_states "$array_job" | awk -v i="$index" '$1 == i {print $2}')
  [[ $state == FAILED ]] || fail "the killed task $index ended $state, not FAILED"
  whole_tiles "after SIGKILL"
  on_ctl scontrol requeue "${array_job}_$index"
  release_requeued "$array_job" || true
  wait_array_done "$array_job" 600
  expect_completed
  note "task $index requeued by hand (scontrol requeue), completed"
  finalize
  report
  compare
  ;;
scancel)
  submit_and_wait
  read -r index pid < <(signal_worker n1 TERM)
  cancelled=$(now)
  while kill -0 "$pid" 2>/dev/null; do sleep 0.05; done
  took=$(since "$cancelled")
  python3 -c "import sys; sys.exit(float(sys.argv[1]) >= 9.0)" "$took" ||
    fail "the worker took $took s to stop after SIGTERM (Slurm's SIGKILL comes at 10 s)"
  wait_array_done "$array_job" 600
  state=$(task_states "$array_job" | awk -v i="$index" '$1 == i {print $2}')
  [[ $state == CANCELLED ]] || fail "the cancelled task $index ended $state"
  out=$work/jobs/strata-bake-${array_job}_$index.out
  # It stops at its next check and says so, or it was already exiting
  # (its tiles all recorded: SIGTERM then ends it at once).
  said=$(grep -m1 'interrupted' "$out" || true)
  if [[ -z $said ]]; then
    for ((t = index * per_worker; t < (index + 1) * per_worker; ++t)); do
      [[ -f $bake/records/$t.json ]] || fail "the cancelled worker neither reported an interruption nor finished tile $t: $(tail -3 "$out")"
    done
    said="its tiles were all recorded (it was exiting)"
  fi
  whole_tiles "after SIGTERM"
  note "task $index cancelled: the worker stopped in $took s: $said"
  # No worker holds the folder lock (finalize takes it).
  [[ ! -e $bake/.strata.lock ]] || flock -n "$bake/.strata.lock" true || fail "the folder lock is held after scancel"
  job=$(submit_tasks "$index")
  [[ $(job_state "${job}_$index") == COMPLETED ]] || fail "the resubmitted task $index ended $(job_state "${job}_$index")"
  note "task $index submitted again (job $job): completed"
  finalize
  report
  compare
  ;;
controller)
  submit_and_wait
  for _ in $(seq 600); do [[ $(records) -ge 12 ]] && break; sleep 0.1; done
  on_ctl scontrol shutdown slurmctld >/dev/null 2>&1 || true
  for _ in $(seq 100); do pgrep -x slurmctld >/dev/null || break; sleep 0.1; done
  pgrep -x slurmctld >/dev/null && fail "slurmctld did not stop"
  note "slurmctld stopped mid-array ($(records) of $tiles tiles recorded); restarting it from its saved state"
  sleep 2
  start_controller
  wait_array_done "$array_job" 600
  expect_completed
  await_final "after the restart"
  report
  compare
  ;;
disk-full)
  submit_and_wait
  wait_array_done "$array_job" 600
  failed=$(task_states "$array_job" | awk '$2 == "FAILED" {print $1}' | paste -sd,)
  [[ -n $failed ]] || fail "no task failed on a $shared_size folder (make DISK_FULL_SIZE smaller)"
  first=${failed%%,*}
  out=$work/jobs/strata-bake-${array_job}_$first.out
  grep -q 'No space left on device' "$out" || fail "task $first did not name the cause: $(tail -3 "$out")"
  # A task names the tile it was writing, or the file (a task whose first
  # write, the bake's scene.toml, finds the disk already full).
  grep -qE "tile [0-9]+ \(|cannot write '[^']+'" "$out" || fail "task $first did not name the tile or file: $(tail -3 "$out")"
  note "the folder filled: tasks $failed failed ($(head -c 300 "$out"))"
  whole_tiles "on a full disk"
  litter=$(find "$bake" -name '.*partial-*' | head -3)
  [[ -z $litter ]] || fail "temporary files left on the full disk: $litter"
  mount -o remount,size=256m "$work/shared"
  job=$(submit_tasks "$failed")
  note "the folder enlarged; tasks $failed submitted again (job $job)"
  bad=$(task_states "$job" | awk '$2 != "COMPLETED"')
  [[ -z $bad ]] || fail "the rerun's tasks did not complete: $(tr '\n' ';' <<<"$bad")"
  finalize
  report
  compare
  ;;
measure)
  # Tiles per minute with 1, 2 and 3 nodes (this machine has 2 cores: this
  # measures the scheduler and the qemu node, not a speed-up), the
  # scheduler's overhead per task, and seconds per tile on each node.
  for use in n1 n1,n2 n1,n2,n3; do
    rm -rf "$bake"
    exclude=$(comm -23 <(printf '%s\n' n1 n2 n3) <(tr , '\n' <<<"$use" | sort) | paste -sd,)
    start=$(now)
    submit_tasks "0-$((workers - 1))" ${exclude:+--exclude=$exclude} >/dev/null
    took=$(since "$start")
    note "nodes $use: $tiles tiles in $took s = $(python3 -c "print(f'{60 * $tiles / $took:.0f}')") tiles/min"
  done
  finalize
  report
  python3 - "$bake/provenance" <<'PY'
import json, pathlib, statistics, sys
by = {}
for f in pathlib.Path(sys.argv[1]).glob("*.json"):
    p = json.loads(f.read_text())
    by.setdefault(f"{p['host']} ({p['arch']})", []).append(p["seconds"])
for host, s in sorted(by.items()):
    print(f"slurm_cluster_test[measure]: {host}: {len(s)} tiles, {sum(s):.2f} s in all, "
          f"mean {statistics.mean(s):.3f} s, median {statistics.median(s):.3f} s a tile")
PY
  start=$(now)
  job=$(cd "$work/jobs" && on_ctl sbatch --parsable --array=0-29 --mem=64M --wrap true)
  wait_array_done "$job" 600
  took=$(since "$start")
  note "scheduler overhead: 30 empty tasks on 3 nodes (one at a time each) in $took s:" \
    "$(python3 -c "print(f'{$took / 10:.2f}')") s a task"
  ;;
esac
note "OK"
