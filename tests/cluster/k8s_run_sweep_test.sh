#!/usr/bin/env bash
# deploy/k8s/run-sweep.sh with a kubectl stand-in (tests/cluster/fake_kubectl.sh) that runs the
# rendered Jobs' pods here, under /bin/sh with JOB_COMPLETION_INDEX, on a folder standing for the
# volume:
#   1. a 3-shard sweep staged, run, merged and collected equals the unsharded sweep (trajectories
#      byte for byte, summary.csv but for wall times, sweep.json but for the input paths);
#   2. two sweeps get different names and folders on the volume;
#   3. bad input (exit 2 in a pod) fails the Job, the wait sees Failed, prints the pod's error and
#      exits 1 without running the merge.
#
#   tests/cluster/k8s_run_sweep_test.sh CORSA_BINARY
set -euo pipefail
CORSA=$(realpath "$1")
export CORSA
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d /tmp/corsa-k8s-test.XXXXXX)
trap '[[ -n ${KEEP:-} ]] || rm -rf "$dir"' EXIT
export KUBECTL="$source_dir/tests/cluster/fake_kubectl.sh"
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then echo "ok: $what"; else
    echo "FAILED: $what" >&2
    failures=$((failures + 1))
  fi
}

# A self-contained input folder: the distribution, its scenario with the map beside it, catalogs.
in=$dir/inputs
mkdir -p "$in/maps"
fixtures=$source_dir/tests/sweep/fixtures
cp "$fixtures/grid.xosc" "$in/"
cp -r "$fixtures/catalogs" "$in/"
cp "$source_dir/scenarios/maps/motorway_2km.xodr" "$in/maps/"
sed 's|../../../scenarios/maps/|maps/|' "$fixtures/follow.xosc" >"$in/follow.xosc"

run_sweep() {  # CLUSTER_FOLDER RESULT_FOLDER [corsa sweep options]
  local cluster=$1 result=$2
  shift 2
  mkdir -p "$cluster"
  FAKE_CLUSTER=$cluster timeout 120 "$source_dir/deploy/k8s/run-sweep.sh" --shards 3 --jobs 1 \
    "$in" grid.xosc "$result" -- "$@"
}

# 1. A sweep end to end.
run_sweep "$dir/cluster" "$dir/result" --record-every 10 >"$dir/run.log" 2>&1 ||
  { cat "$dir/run.log" >&2; echo "FAILED: run-sweep.sh exited non-zero" >&2; exit 1; }
"$CORSA" sweep "$in/grid.xosc" --record-every 10 -o "$dir/whole" --quiet
name=$(sed -n 's/^run-sweep.sh: sweep \([^:]*\): 3 shards of grid.xosc$/\1/p' "$dir/run.log")
check "the sweep got a generated name" grep -Eq '^corsa-sweep-[0-9]{8}-[0-9]{6}-[0-9a-f]{4}$' <<<"$name"
check "the inputs were staged on the volume" test -f "$dir/cluster/data/$name/in/maps/motorway_2km.xodr"
for k in 0 1 2; do
  check "pod $k wrote shard $k/3" grep -q "\"shard\": \"$k/3\"" "$dir/cluster/data/$name/out/shard-$k/shard.json"
done
check "the merge Job ran after the sweep Job" \
  grep -q "merged 3 shards into $dir/cluster/data/$name/out/merged: 12 variants" "$dir/run.log"
files() { (cd "$1" && find . -type f | sort); }
check "the result holds the files of the unsharded sweep" diff <(files "$dir/whole") <(files "$dir/result")
same_trajectories() {
  local file
  while read -r file; do
    cmp -s "$dir/whole/$file" "$dir/result/$file" || { echo "differs: $file" >&2; return 1; }
  done < <(cd "$dir/whole" && find . -name trajectory.csv)
}
check "every trajectory.csv is the same byte for byte" same_trajectories
without_wall_time() { sed -E 's/,[0-9.e+-]*$//' "$1"; }
check "summary.csv is the same but for wall times" \
  diff <(without_wall_time "$dir/whole/summary.csv") <(without_wall_time "$dir/result/summary.csv")
without_paths() { grep -Ev '^  "(source|scenario)": ' "$1"; }
check "sweep.json is the same but for the input paths" \
  diff <(without_paths "$dir/whole/sweep.json") <(without_paths "$dir/result/sweep.json")

# 2. Another sweep on the same volume gets its own name.
sleep 1
run_sweep "$dir/cluster" "$dir/result2" --no-trajectories >"$dir/run2.log" 2>&1 ||
  { cat "$dir/run2.log" >&2; echo "FAILED: the second run-sweep.sh exited non-zero" >&2; exit 1; }
name2=$(sed -n 's/^run-sweep.sh: sweep \([^:]*\): .*/\1/p' "$dir/run2.log")
check "a second sweep has another name" test -n "$name2" -a "$name2" != "$name"
check "the first sweep's outputs are untouched" test -f "$dir/cluster/data/$name/out/merged/summary.csv"

# 3. Bad input: the pods exit 2, the Job fails, the wait returns, no merge.
status=0
run_sweep "$dir/bad" "$dir/result3" --param Nonexistent=1,2 >"$dir/run3.log" 2>&1 || status=$?
check "a failed Job makes run-sweep.sh exit 1" test "$status" -eq 1
check "it names the failed Job" grep -q "run-sweep.sh: job corsa-sweep-.* failed" "$dir/run3.log"
check "it shows the pod's error" grep -q "Nonexistent" "$dir/run3.log"
pod_lines() { cat "$dir"/bad/jobs/*.log | wc -l; }
check "exit 2 failed the Job at its first pod, with no retry" test "$(pod_lines)" -eq 1
check "no merge Job was applied" test "$(grep -c '^kubectl apply' "$dir/bad/calls")" -eq 3
check "nothing was collected" test ! -e "$dir/result3"

if ((failures > 0)); then
  echo "FAILED: $failures check(s) failed" >&2
  exit 1
fi
echo "k8s run-sweep test: all checks passed"
