#!/bin/sh
# Lamé's sphere, mfree against deal.II side by side (README.md). Installs Debian's deal.II when it
# is missing (root, apt-get), builds the peer in build-dealii/ and runs compare.py.
#   sh verification/benchmarks/dealii/run.sh [OUT] [--quick]     (from the repository root)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
out=${1:-$root/results/dealii-comparison}
shift $(( $# > 0 ? 1 : 0 ))
if [ ! -f /usr/share/cmake/deal.II/deal.IIConfig.cmake ]; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q libdeal.ii-dev
fi
[ -x "$root/build/mfree" ] || { echo "run.sh: build mfree first (README.md): $root/build/mfree is missing" >&2; exit 1; }
cmake -S "$here" -B "$root/build-dealii" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$root/build-dealii" -j2 > /dev/null
/usr/bin/python3 "$here/compare.py" "$root/build/mfree" "$root/build-dealii/lame_sphere_dealii" "$out" "$@"
