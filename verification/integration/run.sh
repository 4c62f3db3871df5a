#!/usr/bin/env bash
# Integration-accuracy study (README's main command): installs and builds mfree when
# needed, runs the study of study.toml, prints the error table with observed rates, and
# plots error against spacing and against run time.
#   bash verification/integration/run.sh [OUTPUT_FOLDER]     (default: results/integration)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-$root/results/integration}
bash "$root/.ci/setup"
"$root/build/mfree" integration "$here/${SCENE:-study.toml}" --out "$out"
/usr/bin/python3 "$here/plot.py" "$out/integration.csv" "$out"
echo "results in $out: integration.csv, error_vs_spacing.png, error_vs_time.png"
