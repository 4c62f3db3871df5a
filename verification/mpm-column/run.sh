#!/usr/bin/env bash
# The damped column under gravity with the MPM methods: particles.csv of the settled state in
# results/mpm-column/METHOD/, the table of sigma_yy errors and column.png (sigma_yy against
# height). Installs and builds mfree when needed.
#   bash verification/mpm-column/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for method in classic ugimp cpdi bspline bspline_cubic bspline_mls; do
  "$root/build/mfree" run "$here/column.toml" --set "mpm.method=$method" \
    --set "output.folder=\"results/mpm-column/$method\"" | grep -E "mfree run|wrote .*particles.csv"
done
/usr/bin/python3 "$root/verification/plot_mpm_bodies.py" column results/mpm-column
