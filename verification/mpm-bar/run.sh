#!/usr/bin/env bash
# The vibrating bar with every MPM method at 16, 32 and 64 cells along the bar, three periods:
# energy.csv (with the momentum, hence v_cm) every step in results/mpm-bar/METHOD_CELLS/, the
# table of periods and v_cm errors, and bar.png. Installs and builds mfree when needed.
#   bash verification/mpm-bar/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for method in classic ugimp cpdi bspline bspline_cubic bspline_mls; do
  for along in 16 32 64; do
    cells=$((along * 5 / 4))  # the grid box is 5/4 of the bar's length
    "$root/build/mfree" run "$here/bar.toml" --set "mpm.method=$method" --set "mpm.cells=$cells" \
      --set "output.folder=\"results/mpm-bar/${method}_$(printf %02d "$along")\"" | grep -E "mfree run|energy:"
  done
done
/usr/bin/python3 "$root/verification/plot_mpm_bodies.py" bar results/mpm-bar
