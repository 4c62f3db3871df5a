#!/usr/bin/env bash
# Cantilever convergence study (README's main command): installs and builds mfree when
# needed, runs `mfree converge` on cantilever.toml (lattice and perturbed clouds, linear and
# quadratic RK, our projected quadrature against Gauss cells and nodal integration, 5
# levels), prints the error table with rates and the tip deflection, and plots.
#   bash verification/cantilever/run.sh [SCENE]      (default: cantilever.toml)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
"$root/build/mfree" converge "$here/${1:-cantilever.toml}"
