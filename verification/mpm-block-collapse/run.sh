#!/usr/bin/env bash
# The collapsing block with the MPM methods to t = 1 s: energy.csv in
# results/mpm-block-collapse/METHOD/, the table of energy drift and block.png (the balance
# through time). Installs and builds mfree when needed.
#   bash verification/mpm-block-collapse/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for method in classic ugimp cpdi bspline bspline_cubic bspline_mls; do
  "$root/build/mfree" run "$here/block.toml" --set "mpm.method=$method" --set dynamics.frames=0 \
    --set "output.folder=\"results/mpm-block-collapse/$method\"" | grep -E "mfree run|energy:"
done
/usr/bin/python3 "$root/verification/plot_mpm_bodies.py" block results/mpm-block-collapse
