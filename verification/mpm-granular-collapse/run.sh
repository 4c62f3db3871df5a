#!/usr/bin/env bash
# The granular column collapse at aspect ratios a = 0.5, 1 and 2: particles as a .pvd series,
# particles.csv and energy.csv in results/mpm-granular-collapse/aA/, then the table of runouts
# against the experimental laws and runout.png (runout.py). Installs and builds mfree when
# needed. About 5 minutes on one thread.
#   bash verification/mpm-granular-collapse/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
out=results/mpm-granular-collapse
rm -rf "$out"
for a in 0.5 1 2; do
  height=$(/usr/bin/python3 -c "print(0.2 * $a)")
  # [[body]] is an array of tables: --set replaces it whole, with the column's height a L0
  "$root/build/mfree" run "$here/column.toml" \
    --set "body=[{name = \"column\", shape = \"rectangle\", box = [[0.0, 0.0], [0.2, $height]], material = \"sand\"}]" \
    --set "output.folder=\"$out/a$a\"" | grep -E "mfree run|particles, grid|energy:|wrote [0-9]+ frames|  total "
done
/usr/bin/python3 "$here/runout.py" "$out"
