#!/usr/bin/env bash
# scripts/slurm/sweep.sbatch end to end on a real single-node Slurm (tests/cluster/slurm_local.sh):
#   1. a 4-task array with CORSA_MERGE=1; task 2 is held after its first variant and cancelled
#      (scancel), so the merge job it depends on must be cancelled too (--kill-on-invalid-dep), not
#      left pending;
#   2. the documented recovery: task 2 resubmitted alone (sbatch --array=2) resumes shard 2 of 4
#      (the count from the shards' shard.json) and submits the merge again;
#   3. the merge equals the unsharded sweep: same files, trajectories and sweep.json byte for byte,
#      summaries equal but for their wall-clock times;
#   4. refusals with the commands that work: a first submission that does not start at 0, and an
#      array with a step;
#   5. every task logs one summary line.
# Every wait has a timeout; the daemons are stopped on any exit.
#
#   tests/cluster/slurm_sweep_test.sh CORSA_BINARY
set -euo pipefail
corsa=$(realpath "$1")
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
# shellcheck source=slurm_local.sh
source "$source_dir/tests/cluster/slurm_local.sh"

dir=$(mktemp -d /tmp/corsa-slurm-test.XXXXXX)
chmod 711 "$dir"
trap 'slurm_stop; rm -rf "$dir"' EXIT
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then echo "ok: $what"; else
    echo "FAILED: $what" >&2
    failures=$((failures + 1))
  fi
}
die() {
  echo "FAILED: $*" >&2
  for log in "$dir"/run/*.log; do [[ -f $log ]] && { echo "--- $log" >&2; cat "$log" >&2; }; done
  exit 1
}
# wait_until SECONDS DESCRIPTION COMMAND...
wait_until() {
  local seconds=$1 what=$2 start=$SECONDS
  shift 2
  until "$@"; do
    ((SECONDS - start < seconds)) || die "timed out after ${seconds} s waiting for $what"
    sleep 0.1
  done
}
job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }
no_jobs_left() { [[ -z $(squeue -h -o %i) ]]; }

slurm_start "$dir/slurm"
mkdir "$dir/run"
cd "$dir/run"
export CORSA="$corsa"
# 4 shards of 40 variants, each variant some 50 ms: long enough to cancel one task mid-run.
# shellcheck disable=SC2054 # the commas are inside the --param values
sweep_args=(--param Ego_Speed=20:39.5:0.5 --param Gap=30,50,70,90 --dt 0.0002 --record-every 2000)
dist="$source_dir/tests/sweep/fixtures/follow.xosc"
script="$source_dir/scripts/slurm/sweep.sbatch"

# 1. The array; task 2 cancelled once it has finished a variant but not its shard. Its corsa is
# held (stopped) after the first variant (tests/cluster/held_corsa.sh), so that the cancel lands
# mid-shard however loaded the machine is: a shard left running ends in about 2 s.
held="$dir/task-2-held"
array=$(CORSA_MERGE=1 CORSA="$source_dir/tests/cluster/held_corsa.sh" CORSA_REAL="$corsa" \
  CORSA_HOLD_TASK=2 CORSA_HOLD_OUT="$dir/out" CORSA_HOLD_FILE="$held" \
  sbatch --parsable --array=0-3 "$script" "$dist" "$dir/out" "${sweep_args[@]}")
task2_held_or_ended() { [[ -f $held || $(job_state "${array}_2") =~ ^(COMPLETED|FAILED)$ ]]; }
wait_until 60 "task 2 to finish its first variant" task2_held_or_ended
[[ -f $held ]] || die "task 2 was not held mid-shard (state $(job_state "${array}_2"))"
shard2_started() { compgen -G "$dir/out/shard-2/variants/*/result.csv" >/dev/null; }
check "task 2 finished a variant before it was cancelled" shard2_started
scancel "${array}_2"
wait_until 30 "task 2 to end" bash -c "[[ \$(scontrol show job ${array}_2 | grep -c 'JobState=CANCELLED') == 1 ]]"
check "task 2 was cancelled before its shard was done" test ! -f "$dir/out/shard-2/summary.csv"
wait_until 90 "the array and the merge job to end" no_jobs_left
merge1=$(squeue -h -t all -n corsa-sweep-merge -o %i | head -1)
[[ -n $merge1 ]] || die "task 0 submitted no merge job"
check "the merge job was cancelled with the failed array (not pending for ever)" \
  test "$(job_state "$merge1")" == CANCELLED
check "no merge was written after the failed task" test ! -e "$dir/out/merged"
for k in 0 1 3; do
  check "task $k finished shard $k/4" grep -q "\"shard\": \"$k/4\"" "$dir/out/shard-$k/shard.json"
  check "task $k finished its shard" test -f "$dir/out/shard-$k/summary.csv"
done

# 2. Recovery: resubmit task 2 alone; it resumes shard 2/4 and submits the merge again.
redo=$(CORSA_MERGE=1 sbatch --parsable --array=2 "$script" "$dist" "$dir/out" "${sweep_args[@]}")
wait_until 90 "the resubmitted task and its merge to end" no_jobs_left
check "the resubmitted task succeeded" test "$(job_state "${redo}_2")" == COMPLETED
check "the resubmitted task ran shard 2/4" grep -q '"shard": "2/4"' "$dir/out/shard-2/shard.json"
check "the resubmitted task resumed the finished variants" \
  grep -Eq "swept 40 variants \(shard 2/4 of 160\).*[0-9]+ ran, [0-9]+ resumed, 0 failed" \
  "corsa-sweep-${redo}_2.log"
merge2=$(squeue -h -t all -n corsa-sweep-merge -o %i | sort -n | tail -1)
check "the second merge job ran" test "$(job_state "$merge2")" == COMPLETED
check "the merge job logged its summary" \
  grep -q "merged 4 shards into $dir/out/merged: 160 variants, 0 failed" "corsa-sweep-merge-$merge2.log"

# 3. The merge equals the unsharded sweep.
"$corsa" sweep "$dist" "${sweep_args[@]}" -j 2 -o "$dir/whole" --quiet
files() { (cd "$1" && find . -type f | sort); }
without_wall_time() { sed -E 's/,[0-9.e+-]*$//' "$1"; }
check "the merge holds the files of the unsharded sweep" \
  diff <(files "$dir/whole") <(files "$dir/out/merged")
check "sweep.json is the same" cmp "$dir/whole/sweep.json" "$dir/out/merged/sweep.json"
check "summary.csv is the same but for wall times" \
  diff <(without_wall_time "$dir/whole/summary.csv") <(without_wall_time "$dir/out/merged/summary.csv")
same_trajectories() {
  local file
  while read -r file; do
    cmp -s "$dir/whole/$file" "$dir/out/merged/$file" || { echo "differs: $file" >&2; return 1; }
  done < <(cd "$dir/whole" && find . -name trajectory.csv)
}
check "every trajectory.csv is the same byte for byte" same_trajectories

# 4. Refusals, each a failed task whose log names the commands that work.
late=$(sbatch --parsable --array=2 "$script" "$dist" "$dir/fresh" "${sweep_args[@]}")
stepped=$(sbatch --parsable --array=0-6:2 "$script" "$dist" "$dir/stepped" "${sweep_args[@]}")
wait_until 60 "the refused tasks to end" no_jobs_left
check "a first submission of task 2 alone is refused" test "$(job_state "${late}_2")" == FAILED
check "its log says to submit the whole array or requeue" \
  grep -q "first submission must be the whole array from 0 (sbatch --array=0-N ...).*scontrol requeue" \
  "corsa-sweep-${late}_2.log"
check "the refused task wrote no shard" test ! -e "$dir/fresh/shard-2"
check "an array with a step is refused" test "$(job_state "${stepped}_4")" == FAILED
check "its log says which array to submit" \
  grep -q "submit --array=0-3 for 4 shards" "corsa-sweep-${stepped}_4.log"

# 5. One line per task log, its own: Slurm's step daemon adds a line of its own to a task it
# cancels ("slurmstepd: error: *** JOB N ... CANCELLED ..."), not counted. The cancelled task's
# corsa (held at the lowest priority) writes its "interrupted" line if it ends its variant within
# KillWait, else Slurm's SIGKILL leaves it no line: at most that one line there.
own_lines() { grep -vc '^slurmstepd' "$1" || true; }
for log in corsa-sweep-*.log; do
  if [[ $log == "corsa-sweep-${array}_2.log" ]]; then
    check "$log has at most one line, its interruption" \
      test "$(own_lines "$log")" -eq "$(grep -c 'interrupted by SIGTERM' "$log" || true)"
    check "$log has at most one line" test "$(own_lines "$log")" -le 1
  else
    check "$log has one line" test "$(own_lines "$log")" -eq 1
  fi
done

if ((failures > 0)); then
  die "$failures check(s) failed"
fi
echo "slurm sweep test: all checks passed"
