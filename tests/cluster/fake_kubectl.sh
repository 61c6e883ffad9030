#!/usr/bin/env bash
# A stand-in for kubectl that runs what deploy/k8s/run-sweep.sh asks of a cluster on this machine,
# so that the driver, the rendered manifests and the pod script are tested together without one:
#   - the volume's /data is $FAKE_CLUSTER/data; the image's pod script is deploy/k8s/sweep-pod.sh
#     and its corsa is $CORSA;
#   - `apply -f -` of an Indexed Job runs every index's pod one after the other with the Job's env
#     and JOB_COMPLETION_INDEX, retrying a pod up to backoffLimitPerIndex times; an exit code the
#     podFailurePolicy lists under FailJob fails the Job at once (condition Failed), as does an
#     index out of retries; otherwise the Job is Complete. A plain Job (the merge) runs its pod once.
#   - `exec [-i] POD -- sh -c CMD` runs CMD here with /data mapped; `get job -o jsonpath` prints the
#     Job's condition; `logs` prints the pods' output.
# Every call is appended to $FAKE_CLUSTER/calls.
set -euo pipefail
cluster=${FAKE_CLUSTER:?}
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
echo "kubectl $*" >>"$cluster/calls"
mkdir -p "$cluster/data" "$cluster/jobs"

# The value of the first `key: value` line of a manifest, without quotes.
field() { sed -n "s/^ *$1: \"\\{0,1\\}\\([^\"]*\\)\"\\{0,1\\}\$/\\1/p" "$2" | head -1; }
# The container's env as NAME=value lines.
env_of() {
  awk '/- name: / { name = $3 } /value: / && name != "" { v = $0; sub(/^ *value: /, "", v);
       gsub(/^"|"$/, "", v); print name "=" v; name = "" }' "$1" | sed "s|=/data/|=$cluster/data/|"
}

run_pod() {  # MANIFEST MODE INDEX -> exit status of the pod
  local manifest=$1 mode=$2 index=$3 environment=()
  mapfile -t environment < <(env_of "$manifest")
  env "${environment[@]}" ${index:+JOB_COMPLETION_INDEX=$index} \
    /bin/sh "$source_dir/deploy/k8s/sweep-pod.sh" "$mode" >>"$cluster/jobs/$(field name "$manifest").log" 2>&1
}

run_job() {  # MANIFEST -> writes the Job's condition
  local manifest=$1 name mode completions retries fail_codes status
  name=$(field name "$manifest")
  mode=$(sed -n 's/.*sweep-pod.sh", "\([a-z]*\)"].*/\1/p' "$manifest")
  if grep -q "completionMode: Indexed" "$manifest"; then
    completions=$(field completions "$manifest")
    retries=$(field backoffLimitPerIndex "$manifest")
  else
    completions=1 retries=0
  fi
  fail_codes=$(sed -n 's/^ *values: \[\(.*\)\]$/\1/p' "$manifest" | head -1)
  for ((index = 0; index < completions; ++index)); do
    for ((attempt = 0; ; ++attempt)); do
      status=0
      if grep -q "completionMode: Indexed" "$manifest"; then
        run_pod "$manifest" "$mode" "$index" || status=$?
      else
        run_pod "$manifest" "$mode" "" || status=$?
      fi
      ((status == 0)) && break
      if [[ ",$fail_codes," == *",$status,"* ]] || ((attempt >= retries)); then
        echo Failed >"$cluster/jobs/$name.condition"
        return
      fi
    done
  done
  echo Complete >"$cluster/jobs/$name.condition"
}

case $1 in
  get)
    if [[ $2 == pvc ]]; then [[ -f $cluster/pvc ]]; exit; fi
    cat "$cluster/jobs/$3.condition"
    ;;
  apply)
    manifest=$(mktemp "$cluster/manifest.XXXXXX")
    cat >"$manifest"
    case $(field kind "$manifest") in
      PersistentVolumeClaim) touch "$cluster/pvc" ;;
      Job) run_job "$manifest" ;;
      Pod) ;;
    esac
    ;;
  wait | delete) ;;
  exec)
    shift
    [[ $1 == -i ]] && shift
    shift 2  # POD --
    [[ $1 == sh && $2 == -c ]] || { [[ $1 == tar ]] && set -- sh -c "$*"; }
    exec sh -c "${3//\/data\//$cluster/data/}"
    ;;
  logs)
    job=${*: -1}
    job=${job#job/}
    job=${job#job-name=}
    for arg in "$@"; do [[ $arg == job-name=* ]] && job=${arg#job-name=}; done
    cat "$cluster/jobs/$job.log" 2>/dev/null || true
    ;;
  *)
    echo "fake kubectl: unsupported: $*" >&2
    exit 1
    ;;
esac
