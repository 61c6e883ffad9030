#!/bin/sh
# Runs the libFuzzer targets of build-fuzz/fuzz for SECONDS each (default 600) at low priority,
# from the repository root:
#   fuzz/make_seeds.py build/corsa /tmp/fuzz-seeds     # seeds of the folder-reading targets
#   fuzz/run_all.sh /tmp/fuzz-seeds /tmp/fuzz-runs 600
# runs every target, two at a time;
#   fuzz/run_all.sh /tmp/fuzz-seeds /tmp/fuzz-runs 600 xodr_map_fuzz xosc_loader_fuzz
# runs the targets named, one at a time (one job, one worker each; the seeds of xodr_map_fuzz,
# xosc_loader_fuzz and xosc_expression_fuzz come from ../shared and fuzz/corpus, not SEEDS).
# Each target keeps its corpus in RUNS/<target>/, its log in RUNS/<target>.log and what it found
# (crash-, leak-, timeout-, oom- files) in RUNS/<target>-artifacts/.
set -u
seeds=$1
runs=$2
seconds=${3:-600}
shift 2
[ $# -gt 0 ] && shift
shared=$(cd "$(dirname "$0")/../.." && pwd)/shared
mkdir -p "$runs"

one() {  # target dictionary max_len seed folders...
  target=$1 dict=$2 max_len=$3
  shift 3
  mkdir -p "$runs/$target" "$runs/$target-artifacts"
  nice -n 10 "build-fuzz/fuzz/$target" "$runs/$target" "$@" ${dict:+-dict=fuzz/$dict} \
    -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 -max_total_time="$seconds" \
    -print_final_stats=1 -artifact_prefix="$runs/$target-artifacts/" >"$runs/$target.log" 2>&1
  echo "$target rc=$?" >>"$runs/done.txt"
}

target() {  # runs one target by name with its dictionary, length limit and seeds
  case $1 in
    rig_fuzz) one rig_fuzz rig.dict 8192 "$seeds/rig_fuzz" ;;
    suite_manifest_fuzz) one suite_manifest_fuzz suite.dict 16384 "$seeds/suite_manifest_fuzz" ;;
    sweep_folder_fuzz) one sweep_folder_fuzz sweep.dict 4096 "$seeds/sweep_folder_fuzz" ;;
    dataset_index_fuzz) one dataset_index_fuzz dataset.dict 8192 "$seeds/dataset_index_fuzz" ;;
    ngii_layer_fuzz) one ngii_layer_fuzz ngii.dict 100000 "$seeds/ngii_layer_fuzz" ;;
    xodr_map_fuzz)
      mkdir -p "$runs/xodr-seeds"
      cp "$shared"/data/xodr/straight_500m.xodr "$shared"/data/xodr/Ex_Line-Spiral-Arc.xodr \
        "$shared"/data/xodr/Ex_Lane-Width.xodr "$shared"/data/xodr/velodrome.xodr \
        "$shared"/data/xodr/two_plus_one.xodr "$runs/xodr-seeds/"
      one xodr_map_fuzz xodr.dict 16384 "$runs/xodr-seeds"
      ;;
    xosc_loader_fuzz) one xosc_loader_fuzz xosc.dict 16384 "$shared/conformance/asam-osc-1.3" ;;
    xosc_expression_fuzz) one xosc_expression_fuzz "" 4096 fuzz/corpus/expression ;;
    *)
      echo "run_all.sh: unknown target $1" >&2
      return 2
      ;;
  esac
}

if [ $# -gt 0 ]; then
  for name in "$@"; do
    target "$name"
  done
  exit 0
fi

target rig_fuzz &
target suite_manifest_fuzz
wait
target sweep_folder_fuzz &
target dataset_index_fuzz
wait
target ngii_layer_fuzz &
target xodr_map_fuzz
wait
target xosc_loader_fuzz &
target xosc_expression_fuzz
wait
