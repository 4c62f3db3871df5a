#!/usr/bin/env bash
# The beam with point particles (B-splines, MLS) and with particle domains (lCPDI), at
# E = 1e5 Pa (the scene) and 1e6 Pa (a copy of it with that modulus): the tip displacement
# at t = 1 s, and beam.png, the particles at t = 1 s for E = 1e5 Pa. About 10 s on 2 threads.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
out="$root/results/mpm-clamped-beam"
mkdir -p "$out"
sed 's/^youngs_modulus = 1.0e5$/youngs_modulus = 1.0e6/' "$here/beam.toml" > "$out/beam_1e6.toml"
for scene in "$here/beam.toml" "$out/beam_1e6.toml"; do
  label=$([[ $scene == */beam.toml ]] && echo "E = 1e5 Pa" || echo "E = 1e6 Pa")
  tag=$([[ $scene == */beam.toml ]] && echo 1e5 || echo 1e6)
  for method in bspline bspline_mls cpdi; do
    tip=$("$root/build/mfree" run "$scene" --set mpm.method="$method" --set dynamics.frames=0 \
      --set "output.folder=\"$out/${method}_$tag\"" 2>/dev/null | grep "probe (")
    echo "$label, $method:$tip"
  done
done
/usr/bin/python3 "$here/plot.py" "$out"
