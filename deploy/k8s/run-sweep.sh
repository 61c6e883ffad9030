#!/usr/bin/env bash
# Runs a Corsa sweep on Kubernetes from this machine, with kubectl:
#   1. makes the claim corsa-sweep-data (deploy/k8s/pvc.yaml) if missing, and a pod mounting it;
#   2. stages INPUT_DIR into /data/NAME/in (NAME unique per sweep: corsa-sweep-<time>-<random>);
#   3. runs the Indexed Job (sweep-job.yaml, one pod per shard) and waits until it is Complete or
#      Failed (a failed Job prints its failed pods' last log lines and stops here, exit 1);
#   4. runs the merge Job (sweep-merge-job.yaml) and waits the same way;
#   5. copies /data/NAME/out/merged into RESULT_DIR, and deletes the staging pod.
# The Jobs and the data on the volume stay for inspection; `kubectl delete job -l corsa/sweep=NAME`
# removes the Jobs and their pods.
#
#   deploy/k8s/run-sweep.sh [options] INPUT_DIR DIST.xosc RESULT_DIR [-- corsa sweep options]
#
#   INPUT_DIR   a folder holding the distribution and everything it refers to (scenario, catalogs,
#               maps) by relative paths inside the folder
#   DIST.xosc   the distribution (or scenario) file, relative to INPUT_DIR
#   RESULT_DIR  where the merged sweep goes (absent or empty)
#   --shards N  pods, one shard each (default 8)       --jobs N   threads and CPUs per pod (4)
#   --image I   the image from deploy/k8s/Dockerfile (corsa:latest)
#   --name N    the sweep's name instead of a generated one   --claim C   (corsa-sweep-data)
#   --timeout S  seconds to wait for each Job (86400)
# Options after `--` go to every `corsa sweep` (split at spaces: no spaces inside one).
# Environment: KUBECTL (default kubectl; its current context and namespace are used).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
kubectl=${KUBECTL:-kubectl}

usage() {
  sed -n '/^#   deploy/,/^# Environment/p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
shards=8 jobs=4 image=corsa:latest name="" claim=corsa-sweep-data timeout=86400
positional=()
while (($#)); do
  case $1 in
    --shards) shards=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --image) image=$2; shift 2 ;;
    --name) name=$2; shift 2 ;;
    --claim) claim=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --) shift; break ;;
    -h | --help) usage ;;
    -*) echo "run-sweep.sh: unknown option $1" >&2; usage ;;
    *) positional+=("$1"); shift ;;
  esac
done
((${#positional[@]} == 3)) || usage
input=${positional[0]} dist=${positional[1]} result=${positional[2]}
sweep_args="$*"

fail() { echo "run-sweep.sh: error: $*" >&2; exit 2; }
[[ $shards =~ ^[1-9][0-9]*$ ]] || fail "--shards expects a positive whole number"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || fail "--jobs expects a positive whole number"
[[ -d $input ]] || fail "$input is not a folder"
[[ -f $input/$dist ]] || fail "$input/$dist does not exist (DIST.xosc is relative to INPUT_DIR)"
if [[ -e $result && -n $(ls -A "$result") ]]; then fail "$result exists and is not empty"; fi
if [[ -z $name ]]; then
  name="corsa-sweep-$(date -u +%Y%m%d-%H%M%S)-$(od -An -N2 -tx2 /dev/urandom | tr -d ' ')"
fi
# A Job's name is a DNS label, and its pods' host names add -<index>.
[[ $name =~ ^[a-z0-9]([-a-z0-9]*[a-z0-9])?$ && ${#name} -le 50 ]] ||
  fail "--name must be lower-case letters, digits and '-', at most 50 characters"
for value in "$dist" "$sweep_args" "$image"; do
  [[ $value != *[\"\\@]* ]] || fail "'$value': quotes, backslashes and @ cannot go into the manifests"
done

# A manifest template with this sweep's values.
render() {
  sed -e "s|@NAME@|$name|g" -e "s|@SHARDS@|$shards|g" -e "s|@JOBS@|$jobs|g" \
    -e "s|@IMAGE@|$image|g" -e "s|@CLAIM@|$claim|g" -e "s|@DIST@|$dist|g" \
    -e "s|@ARGS@|$sweep_args|g" "$here/$1"
}

# Waits until Job $1 has the condition Complete (returns 0) or Failed (prints why, returns 1).
wait_job() {
  local job=$1 deadline=$((SECONDS + timeout)) conditions
  while true; do
    conditions=$("$kubectl" get job "$job" \
      -o jsonpath='{range .status.conditions[?(@.status=="True")]}{.type}{"\n"}{end}')
    if grep -qx Failed <<<"$conditions"; then
      echo "run-sweep.sh: job $job failed:" >&2
      "$kubectl" get job "$job" -o jsonpath='{range .status.conditions[*]}{.type}: {.reason} {.message}{"\n"}{end}' >&2 || true
      "$kubectl" logs -l "job-name=$job" --prefix --tail=5 >&2 || true
      return 1
    fi
    grep -qx Complete <<<"$conditions" && return 0
    ((SECONDS < deadline)) || { echo "run-sweep.sh: timed out waiting for job $job" >&2; return 1; }
    sleep 5
  done
}

echo "run-sweep.sh: sweep $name: $shards shards of $dist"
if ! "$kubectl" get pvc "$claim" >/dev/null 2>&1; then
  sed "s|name: corsa-sweep-data|name: $claim|" "$here/pvc.yaml" | "$kubectl" apply -f -
fi
render sweep-io-pod.yaml | "$kubectl" apply -f -
trap '"$kubectl" delete pod "$name-io" --wait=false >/dev/null 2>&1 || true' EXIT
"$kubectl" wait --for=condition=Ready "pod/$name-io" --timeout=600s >/dev/null

tar -C "$input" -cf - . |
  "$kubectl" exec -i "$name-io" -- sh -c "mkdir -p '/data/$name/in' && tar -C '/data/$name/in' -xf -"

render sweep-job.yaml | "$kubectl" apply -f -
wait_job "$name" || exit 1
render sweep-merge-job.yaml | "$kubectl" apply -f -
wait_job "$name-merge" || exit 1
"$kubectl" logs "job/$name-merge" || true

mkdir -p "$result"
"$kubectl" exec "$name-io" -- tar -C "/data/$name/out/merged" -cf - . | tar -C "$result" -xf -
echo "run-sweep.sh: sweep $name merged into $result"
