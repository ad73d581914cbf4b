#!/usr/bin/env bash
# A real, single-node Slurm for one test: starts munged, slurmctld and slurmd from Debian's
# packages (slurm-wlm, munge) in a temporary folder, without systemd, then renders a scene with
# `srun -n 3 --mpi=pmix prism render` and with an `sbatch` job script, and checks that both
# images are bit-identical to a single-process render (pixel hashes); then an `sbatch` job
# serves its live session (`prism view --serve`) and an offscreen `prism connect` moves the
# camera and saves an EXR that must equal `prism render` of that view. Every daemon it started
# is stopped by its pid when it ends, whether it passed or not; on failure it prints the logs.
#   slurm_render.sh PRISM PIXEL_HASH SCENE [PRISM RENDER OPTIONS...]
# Needs root: munged must run as the munge user and slurmd as root (it starts job steps as the
# submitting user). As another user the test is skipped (exit 77) with the reason.
set -uo pipefail

readonly kSkip=77
if (($# < 3)); then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
prism=$(realpath "$1")
pixel_hash=$(realpath "$2")
scene=$(realpath "$3")
shift 3
render_options=("$@")

fail() {
  echo "SLURM TEST FAILED: $*" >&2
  exit 1
}

if [[ $(id -u) -ne 0 ]]; then
  echo "SKIPPED: a private Slurm needs root (munged runs as the munge user, slurmd as root);" \
    "run the suite as root, e.g. in CI" >&2
  exit "$kSkip"
fi
for tool in munged setpriv slurmctld slurmd srun sbatch sinfo scancel squeue; do
  command -v "$tool" >/dev/null ||
    fail "'$tool' is missing: run scripts/setup.sh (it installs slurm-wlm and munge)"
done
id munge >/dev/null 2>&1 || fail "no 'munge' user: the munge package is not installed properly"

work=$(mktemp -d /tmp/prism-slurm.XXXXXX)
chmod 755 "$work"  # munged (the munge user) must reach its folder inside
daemon_pids=()
passed=0

# Stops the daemons this script started, newest first: TERM, then KILL after 10 s.
stop_daemons() {
  local pid i
  for ((i = ${#daemon_pids[@]} - 1; i >= 0; i--)); do
    pid=${daemon_pids[i]}
    kill -TERM "$pid" 2>/dev/null || continue
    for _ in $(seq 100); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    if kill -0 "$pid" 2>/dev/null; then
      echo "daemon $pid ignored SIGTERM for 10 s: killing it" >&2
      kill -KILL "$pid" 2>/dev/null
    fi
    wait "$pid" 2>/dev/null
  done
}

print_logs() {
  local log
  for log in "$work"/log/*.log "$work"/*.out; do
    [[ -f $log ]] || continue
    echo "----- $log (last 40 lines)" >&2
    tail -n 40 "$log" >&2
  done
}

cleanup() {
  # Jobs first, so slurmd's step daemons end with them; then the daemons themselves.
  if ((${#daemon_pids[@]} >= 2)); then
    timeout 10 scancel --full --quiet --user=root 2>/dev/null
  fi
  stop_daemons
  ((passed)) || print_logs
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Polls CONDITION (a command) every 0.2 s for at most SECONDS; fails with WHAT.
wait_for() {
  local seconds=$1 what=$2
  shift 2
  local deadline=$((SECONDS + seconds))
  until "$@" >/dev/null 2>&1; do
    ((SECONDS < deadline)) || fail "$what did not happen within $seconds s"
    sleep 0.2
  done
}

# TCP ports nobody listens on (from /proc/net/tcp*, no tools needed), picked at random in
# 20000-59999 so two runs side by side and a system Slurm on 6817/6818 do not collide.
listening_ports() {
  local _slot address _remote state _rest
  cat /proc/net/tcp /proc/net/tcp6 2>/dev/null |
    while read -r _slot address _remote state _rest; do
      [[ $state == 0A ]] && echo $((16#${address##*:}))  # 0A: LISTEN; the port is hex
    done
}
free_port() {
  local port used
  used=" $(listening_ports | tr '\n' ' ') "
  for _ in $(seq 50); do
    port=$((20000 + RANDOM % 40000))
    [[ $used == *" $port "* || " ${chosen_ports:-} " == *" $port "* ]] || {
      chosen_ports="${chosen_ports:-} $port"
      echo "$port"
      return
    }
  done
  fail "no free TCP port found"
}

mkdir -p "$work"/{munge,log,state,spool}
chmod 755 "$work/munge"
chown munge:munge "$work/munge"

# --- munge: a fresh key, read only by the munge user, and the daemon in the foreground.
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chown munge:munge "$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
# setpriv execs munged itself, so $! is munged's pid.
setpriv --reuid=munge --regid=munge --clear-groups munged --foreground \
  --key-file="$work/munge/munge.key" --socket="$socket" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/log/munged.log" --seed-file="$work/munge/munged.seed" \
  >"$work/log/munged.console.log" 2>&1 &
daemon_pids+=($!)
wait_for 15 "munged creating $socket" test -S "$socket"

# --- slurm.conf: one node with this machine's CPUs, no cgroups, no accounting.
node=$(hostname -s)
cpus=$(nproc)
ctld_port=$(free_port)
slurmd_port=$(free_port)
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=prismtest
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=prism Nodes=$node Default=YES MaxTime=10 State=UP OverSubscribe=YES
EOF

# -D: in the foreground, so $! is the daemon; -i: no state from an earlier run.
slurmctld -D -i -f "$SLURM_CONF" >"$work/log/slurmctld.console.log" 2>&1 &
daemon_pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >"$work/log/slurmd.console.log" 2>&1 &
daemon_pids+=($!)
node_idle() { [[ $(sinfo -h -N -n "$node" -o %T 2>/dev/null) == idle* ]]; }
wait_for 60 "node $node becoming idle in Slurm (sinfo)" node_idle
# Open MPI from Debian starts directly under srun through PMIx.
srun --mpi=list 2>&1 | grep -qw pmix ||
  fail "Slurm has no pmix MPI plugin (srun --mpi=list: $(srun --mpi=list 2>&1 | tr '\n' ' '))"
echo "slurm: controller on port $ctld_port, node $node with $cpus CPUs, in $work"

hash_of() {
  [[ -f $1 ]] || fail "$1 was not written"
  "$pixel_hash" "$1" | cut -d' ' -f1-2
}

# --- the single-process reference.
timeout 120 "$prism" render "$scene" "${render_options[@]}" -q -o "$work/reference.exr" ||
  fail "the single-process reference render failed"
reference=$(hash_of "$work/reference.exr")
echo "reference   $reference"

# --- srun: three ranks on the node, more than its CPUs if need be (--overcommit).
timeout 120 srun --mpi=pmix -n 3 --overcommit --time=5 "$prism" render "$scene" \
  "${render_options[@]}" -o "$work/srun.exr" >"$work/srun.out" 2>&1 ||
  fail "srun exited with $? (output: $(cat "$work/srun.out"))"
grep -q "^ranks     3" "$work/srun.out" || fail "srun's render did not run on 3 ranks:
$(cat "$work/srun.out")"
got=$(hash_of "$work/srun.exr")
echo "srun -n 3   $got"
[[ $got == "$reference" ]] || fail "srun's image differs from the single-process render"

# --- sbatch: the hybrid job script of docs/distributed.md, scaled to this node: ranks ×
# threads per rank, the threads given to Prism from SLURM_CPUS_PER_TASK. --wait returns when
# the job has ended, with its exit code.
cat >"$work/job.sh" <<EOF
#!/bin/bash
#SBATCH --job-name=prism-test
#SBATCH --ntasks=3
#SBATCH --cpus-per-task=1
#SBATCH --overcommit
#SBATCH --time=5
#SBATCH --output=$work/job.out
srun --mpi=pmix "$prism" render "$scene" ${render_options[*]} \\
  --threads "\$SLURM_CPUS_PER_TASK" -o "$work/sbatch.exr"
EOF
timeout 180 sbatch --wait --chdir="$work" "$work/job.sh" >"$work/sbatch.out" 2>&1 ||
  fail "the sbatch job failed or timed out (exit $?):
$(cat "$work/sbatch.out" "$work/job.out" 2>/dev/null)"
grep -q "^ranks     3" "$work/job.out" || fail "the batch job did not render on 3 ranks:
$(cat "$work/job.out")"
grep -q "rank 2: 1 threads" "$work/job.out" || fail "the batch job's ranks did not take \
--threads from SLURM_CPUS_PER_TASK:
$(cat "$work/job.out")"
got=$(hash_of "$work/sbatch.exr")
echo "sbatch      $got"
[[ $got == "$reference" ]] || fail "the batch job's image differs from the single-process render"

# --- a served job: the job script of docs/distributed.md that serves its live session instead
# of showing it. An offscreen viewer on "the desk" (this machine) connects with the connection
# file, moves the camera, saves an EXR of one pass and leaves; the job ends with it
# (--exit-with-client). The EXR must be bit-identical to `prism render` of the view it moved to.
cat >"$work/serve.sh" <<EOF
#!/bin/bash
#SBATCH --job-name=prism-serve
#SBATCH --ntasks=2
#SBATCH --cpus-per-task=1
#SBATCH --overcommit
#SBATCH --time=5
#SBATCH --output=$work/serve.out
srun --mpi=pmix "$prism" view "$scene" ${render_options[*]} --threads "\$SLURM_CPUS_PER_TASK" \\
  --serve 127.0.0.1:0 --connection-file "$work/job.connection" --exit-with-client
EOF
serve_job=$(sbatch --parsable --chdir="$work" "$work/serve.sh" 2>"$work/serve.sbatch.err") ||
  fail "sbatch refused the serving job: $(cat "$work/serve.sbatch.err")"
connection_written() { [[ -f $work/job.connection ]]; }
wait_for 120 "the serving job's connection file" connection_written
[[ $(stat -c %a "$work/job.connection") == 600 ]] ||
  fail "the connection file is not private (mode $(stat -c %a "$work/job.connection"))"
QT_QPA_PLATFORM=offscreen timeout 120 "$prism" connect "$work/job.connection" --keys wd \
  --exit-after-passes 1 --save "$work/desk.exr" >"$work/desk.out" 2>&1 ||
  fail "the viewer failed (exit $?): $(cat "$work/desk.out" "$work/serve.out" 2>/dev/null)"
job_gone() { [[ -z $(squeue -h -j "$serve_job" 2>/dev/null) ]]; }
wait_for 60 "the serving job ending after its viewer left" job_gone
grep -q "served     until the viewer left (--exit-with-client)" "$work/serve.out" ||
  fail "the serving job did not end with its viewer: $(cat "$work/serve.out")"
view_options=$(sed -n 's/^view       \(--camera-position [^ ]* --look-at [^ ]*\).*/\1/p' \
  "$work/desk.out")
[[ -n $view_options ]] || fail "the viewer did not print its view: $(cat "$work/desk.out")"
# shellcheck disable=SC2086  # the view options are two option-value pairs
timeout 120 "$prism" render "$scene" "${render_options[@]}" $view_options -q \
  -o "$work/desk-reference.exr" || fail "the render of the viewer's view failed"
got=$(hash_of "$work/desk.exr")
echo "served      $got"
[[ $got == "$(hash_of "$work/desk-reference.exr")" ]] ||
  fail "the viewer's EXR differs from prism render of the same view"
[[ $got != "$reference" ]] || fail "the viewer's keys did not move the camera"

passed=1
echo "PASSED: srun and sbatch images are bit-identical to the single-process render, and a"
echo "served job's viewer saved prism render's pixels of the view it moved to"
