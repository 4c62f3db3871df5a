#!/usr/bin/env bash
# A run killed after a checkpoint and restarted from it ends with the results of a run that
# was never interrupted, bit for bit:
#   1. the scene runs whole into WORK/whole;
#   2. it runs again with checkpoints into WORK/cut, and is killed (SIGKILL) once the first
#      checkpoint is in place: no WORK/cut folder may be left;
#   3. `mfree run --restart WORK/cut.checkpoints` continues it;
#   4. every file of WORK/whole but summary.json (run times) equals WORK/cut's byte for byte,
#      and the checkpoints are gone.
#   restart.sh MFREE SCENE WORK EVERY [--set KEY=VALUE]...
set -euo pipefail
mfree=$1 scene=$2 work=$3 every=$4
shift 4
rm -rf "$work"
mkdir -p "$work"
"$mfree" run "$scene" "$@" --set "output.folder=\"$work/whole\"" >"$work/whole.log"

cut=("$@" --set "output.folder=\"$work/cut\"" --set "output.checkpoint_every=$every")
"$mfree" run "$scene" "${cut[@]}" >"$work/cut.log" 2>&1 &
pid=$!
until compgen -G "$work/cut.checkpoints/step_*" >/dev/null; do
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "restart: the run ended before its first checkpoint (make it longer)" >&2
    cat "$work/cut.log" >&2
    exit 1
  fi
  sleep 0.01
done
kill -KILL "$pid"
wait "$pid" 2>/dev/null || true
if [[ -e $work/cut ]]; then
  echo "restart: the killed run left an output folder" >&2
  exit 1
fi
echo "killed after $(cd "$work/cut.checkpoints" && ls -d step_* | tr '\n' ' ')"

"$mfree" run "$scene" "${cut[@]}" --restart "$work/cut.checkpoints" >"$work/restart.log"
grep "continuing from step" "$work/restart.log"
if [[ -e $work/cut.checkpoints ]]; then
  echo "restart: the finished run left its checkpoints" >&2
  exit 1
fi
files=0
while IFS= read -r -d '' f; do
  name=${f#"$work/whole/"}
  [[ $name == summary.json ]] && continue
  if ! cmp "$f" "$work/cut/$name"; then
    echo "restart: $name differs from the uninterrupted run's" >&2
    exit 1
  fi
  files=$((files + 1))
done < <(find "$work/whole" -type f -print0)
if [[ $(cd "$work/whole" && find . -type f | sort) != $(cd "$work/cut" && find . -type f | sort) ]]; then
  echo "restart: the two runs wrote different files" >&2
  exit 1
fi
echo "restart: $files files identical to the uninterrupted run's"
