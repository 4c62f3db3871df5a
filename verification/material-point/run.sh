#!/usr/bin/env bash
# The two material-point tests of small-strain J2 plasticity (README.md): uniaxial strain
# through yield, unloading and reverse yield; tension, then shear at constant axial strain.
# Each run prints its table and writes path.csv and summary.json to
# results/material-point/uniaxial/ and results/material-point/tension-shear/; plot.py draws
# uniaxial.png (sigma_yy against eps_yy) and tension_shear.png (sigma_xy, sigma_yy against t)
# into the same folders. Installs and builds mfree when needed.
#   bash verification/material-point/run.sh        (under a second once mfree is built)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
"$root/build/mfree" run "$here/uniaxial.toml"
"$root/build/mfree" run "$here/tension_shear.toml"
/usr/bin/python3 "$here/plot.py" results/material-point/uniaxial results/material-point/tension-shear
