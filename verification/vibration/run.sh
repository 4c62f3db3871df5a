#!/usr/bin/env bash
# Vibration refinement studies (SPEC section 6) with the total-Lagrangian meshfree method:
# A = 0.05 and A = 0.1, node spacings 1/8 to 1/64, central differences and Newmark, errors
# at T/4, T/2, 3T/4 and T, rates, wall times, a time-step check at the finest level, CSV and
# PNG plots in results/vibration*/. Installs and builds mfree when needed.
#   bash verification/vibration/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
for scene in vibration.toml vibration_a01.toml; do
  "$root/build/mfree" converge "$here/$scene"
done
