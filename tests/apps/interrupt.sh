#!/usr/bin/env bash
# A run stopped by a signal removes its staging folder and keeps the earlier results and its
# checkpoints; --restart then finishes it:
#   1. WORK/out holds the results of an earlier run (a marker and previous.txt);
#   2. the scene runs with checkpoints into WORK/out and gets SIGNAL once its first checkpoint
#      is in place;
#   3. its exit status is 128 + the signal's number, WORK holds out (as it was) and
#      out.checkpoints, and nothing else (no hidden staging folder);
#   4. `mfree run --restart WORK/out.checkpoints` ends with exit 0.
#   interrupt.sh MFREE SCENE WORK EVERY SIGNAL [--set KEY=VALUE]...
set -euo pipefail
set -m  # job control: a background job takes SIGINT (without it the shell makes it ignore it)
mfree=$1 scene=$2 work=$3 every=$4 signal=$5
shift 5
rm -rf "$work"
mkdir -p "$work/out"
echo "written by mfree: a run replaces this folder as a whole" >"$work/out/.mfree-output"
echo "the results of an earlier run" >"$work/out/previous.txt"

args=("$@" --set "output.folder=\"$work/out\"" --set "output.checkpoint_every=$every")
"$mfree" run "$scene" "${args[@]}" >"$work/run.log" 2>&1 &
pid=$!
until compgen -G "$work/out.checkpoints/step_*" >/dev/null; do
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "interrupt: the run ended before its first checkpoint (make it longer)" >&2
    cat "$work/run.log" >&2
    exit 1
  fi
  sleep 0.01
done
kill "-$signal" "$pid"
status=0
wait "$pid" || status=$?
expected=$((128 + $(kill -l "$signal")))
cat "$work/run.log"
if [[ $status != "$expected" ]]; then
  echo "interrupt: exit status $status after SIG$signal, expected $expected" >&2
  exit 1
fi
left=$(cd "$work" && find . -mindepth 1 -maxdepth 1 ! -name run.log | sort | tr '\n' ' ')
if [[ $left != "./out ./out.checkpoints " ]]; then
  echo "interrupt: the stopped run left '$left' (expected out and out.checkpoints)" >&2
  exit 1
fi
if [[ $(cd "$work/out" && ls -A | tr '\n' ' ') != ".mfree-output previous.txt " ||
      $(cat "$work/out/previous.txt") != "the results of an earlier run" ]]; then
  echo "interrupt: the stopped run changed the earlier results" >&2
  exit 1
fi
echo "interrupt: exit status $status after SIG$signal; earlier results and checkpoints kept"
"$mfree" run "$scene" "${args[@]}" --restart "$work/out.checkpoints" >"$work/restart.log"
grep "continuing from step" "$work/restart.log"
echo "interrupt: restarted run finished"
