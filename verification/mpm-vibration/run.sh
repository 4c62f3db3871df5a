#!/usr/bin/env bash
# MPM vibration studies (SPEC section 6): every method (Classic, uGIMP, cpGIMP, lCPDI, qCPDI,
# CPDI2, quadratic and cubic B-splines, point-evaluated and averaged over the particle domains,
# MLS-reconstructed quadratic B-splines) on 8 to 64
# cells with 9 and 4 particles per cell at A = 0.05 and A = 0.1, errors at T/4, T/2, 3T/4 and T, rates, wall
# times; then the ten-period run at A = 0.1 with energy through time; then the update schemes
# and mappings (mapping.toml), MLS with a quadratic basis (mls.toml) and the B-splines averaged
# over the particle domains (bspline_cpgimp.toml) at both amplitudes. CSV and PNG plots in
# results/mpm-vibration/*/. Installs and builds mfree when needed.
#   bash verification/mpm-vibration/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for scene in vibration.toml vibration_a01.toml long_run.toml mapping.toml mls.toml bspline_cpgimp.toml; do
  "$root/build/mfree" converge "$here/$scene"
done
for scene in mapping mls bspline_cpgimp; do
  "$root/build/mfree" converge "$here/$scene.toml" --set exact.amplitude=0.1 --set "output.folder=results/mpm-vibration/$scene-a01"
done
