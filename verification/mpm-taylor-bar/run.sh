#!/usr/bin/env bash
# The Taylor-bar impact on 80, 160 and 320 cells (results/mpm-taylor-bar/cells_N/), then the
# energy table and taylor_bar.png (plot.py). Installs and builds mfree when needed. ~3 min on 2 cores.
#   bash verification/mpm-taylor-bar/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for cells in 80 160 320; do
  "$root/build/mfree" run "$here/bar.toml" --set "mpm.cells=$cells" \
    --set "output.folder=\"results/mpm-taylor-bar/cells_$cells\"" | grep -E "mfree run|drifts|particle-steps"
done
/usr/bin/python3 "$here/plot.py" results/mpm-taylor-bar
