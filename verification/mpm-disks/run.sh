#!/usr/bin/env bash
# The colliding disks with every MPM method to t = 3.5: energy.csv per method in
# results/mpm-disks/METHOD/, the table of energy lost and largest momentum, and disks.png
# (energy and momentum through time). Installs and builds mfree when needed. About 1 minute.
#   bash verification/mpm-disks/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for method in classic ugimp cpdi bspline bspline_cubic bspline_mls; do
  "$root/build/mfree" run "$here/disks.toml" --set "mpm.method=$method" --set dynamics.frames=0 \
    --set "output.folder=\"results/mpm-disks/$method\"" | grep -E "mfree run|total momentum|energy:"
done
/usr/bin/python3 "$root/verification/plot_mpm_bodies.py" disks results/mpm-disks
