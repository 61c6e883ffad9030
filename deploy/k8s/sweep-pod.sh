#!/bin/sh
# What a pod of a Corsa sweep runs (POSIX sh; the image installs it as
# /usr/local/share/corsa/sweep-pod.sh). Two steps, each a Kubernetes Job (deploy/k8s):
#
#   sweep-pod.sh shard   one pod per shard of an Indexed Job: shard JOB_COMPLETION_INDEX of
#                        CORSA_SHARD_COUNT into $CORSA_SWEEP_DIR/out/shard-<index>; a retried pod
#                        resumes its shard (--resume keeps the variants it finished)
#   sweep-pod.sh merge   once every shard has completed: the shards into $CORSA_SWEEP_DIR/out/merged
#
# Environment:
#   CORSA_SWEEP_DIR     this sweep's folder on the shared volume: in/ (staged inputs), out/
#   CORSA_DIST          the distribution (or scenario) file, relative to in/
#   CORSA_SHARD_COUNT   the Job's completions (a pod does not see its Job's completion count)
#   JOB_COMPLETION_INDEX  set by Kubernetes in an Indexed Job
#   CORSA_JOBS          threads per pod (default: the CPUs the pod may use)
#   CORSA_SWEEP_ARGS    more `corsa sweep` options, split at spaces (e.g. --param Gap=20:60:5)
#   CORSA               the corsa binary (default: corsa on PATH)
#
# Exit status: 0 when the shard (or merge) is complete, including variants that failed (they are
# recorded in summary.csv: the engine is deterministic, so a retry would fail them again); 2 for
# bad input, which every retry and every other shard would meet too: the Job's podFailurePolicy
# fails the whole Job on it; anything else (3: internal error, 137: killed) is retried per index.

corsa=${CORSA:-corsa}
say() { echo "sweep-pod: $*" >&2; }
need() {
  eval "value=\${$1:-}"
  if [ -z "$value" ]; then
    say "error: $1 is not set ($2)"
    exit 2
  fi
}

need CORSA_SWEEP_DIR "the sweep's folder on the shared volume"
dir=$CORSA_SWEEP_DIR

case ${1:-} in
  shard)
    need JOB_COMPLETION_INDEX "set by Kubernetes in an Indexed Job"
    need CORSA_SHARD_COUNT "the Job's completions"
    need CORSA_DIST "the distribution file, relative to $dir/in"
    index=$JOB_COMPLETION_INDEX
    out=$dir/out/shard-$index
    jobs=${CORSA_JOBS:-$(nproc 2>/dev/null || echo 1)}
    # A pod stopped before its shard was recorded has no finished variant: start it afresh.
    resume=""
    if [ -f "$out/sweep.json" ]; then
      if [ -f "$out/shard.json" ]; then resume=--resume; else resume=--force; fi
    fi
    # shellcheck disable=SC2086 # CORSA_SWEEP_ARGS and $resume are split on purpose
    "$corsa" sweep "$dir/in/$CORSA_DIST" --shard auto --shard-count "$CORSA_SHARD_COUNT" \
      -j "$jobs" -o "$out" $resume ${CORSA_SWEEP_ARGS:-}
    status=$?
    ;;
  merge)
    # Every shard folder the Job wrote, in index order (the merge checks that they are one sweep
    # and hold every variant exactly once).
    set -- "$dir"/out/shard-*
    if [ ! -d "$1" ]; then
      say "error: no shard folder in $dir/out: has the sweep Job run?"
      exit 2
    fi
    "$corsa" sweep merge --force "$dir/out/merged" "$@"
    status=$?
    ;;
  *)
    say "usage: sweep-pod.sh shard|merge"
    exit 2
    ;;
esac

case $status in
  0 | 1) exit 0 ;;
  2) exit 2 ;;
  *)
    say "corsa failed with exit status $status"
    exit "$status"
    ;;
esac
