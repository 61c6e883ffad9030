#!/usr/bin/env bash
# A corsa for tests/cluster/slurm_sweep_test.sh that holds one array task mid-shard, so that the
# test cancels a task that is certainly still running whatever the machine's load: in the array
# task $CORSA_HOLD_TASK, `corsa sweep` runs $CORSA_REAL in the background and, as soon as its
# shard folder ($CORSA_HOLD_OUT/shard-K) holds a finished variant, stops it (SIGSTOP) and creates
# $CORSA_HOLD_FILE; it stays stopped until the job is cancelled (Slurm sends SIGCONT and SIGTERM,
# then SIGKILL after KillWait). The sweep runs at the lowest priority so that this script, which
# looks every 10 ms, sees the first variant long before the other 39 are done (each takes some
# 50 ms of CPU). If the shard still ended first, no hold file is made and the script exits 3, which
# the test reports. Every other call (other tasks, `sweep merge`) is $CORSA_REAL itself.
set -euo pipefail
real=${CORSA_REAL:?}
if [[ ${1:-} != sweep || ${2:-} == merge || ${SLURM_ARRAY_TASK_ID:-} != "${CORSA_HOLD_TASK:?}" ]]; then
  exec "$real" "$@"
fi
shard="${CORSA_HOLD_OUT:?}/shard-$SLURM_ARRAY_TASK_ID"
nice -n 19 "$real" "$@" &
sweep=$!
until compgen -G "$shard/variants/*/result.csv" >/dev/null; do
  if ! kill -0 "$sweep" 2>/dev/null; then
    wait "$sweep" || true
    echo "held_corsa: the shard ended before it could be held" >&2
    exit 3
  fi
  sleep 0.01
done
kill -STOP "$sweep"
if [[ -f "$shard/summary.csv" ]]; then
  echo "held_corsa: the shard ended before it could be held" >&2
  exit 3
fi
touch "${CORSA_HOLD_FILE:?}"
wait "$sweep"
