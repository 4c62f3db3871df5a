#!/usr/bin/env bash
# The strip footing on Drucker–Prager soil: Newton with load steps to 98 % of Prandtl's collapse
# load (results/plastic-footing/, load_steps.csv, VTK), then past it (to 1.1 q_u), where Newton
# must give up near q_u: the discrete collapse load. Installs and builds mfree when needed. ~45 s.
#   bash verification/plastic-footing/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
"$root/build/mfree" run "$here/footing.toml" | grep -E "^mfree|converged|load steps"
echo "beyond the collapse load: q = 1.1 q_u (Newton must give up near q_u)"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if "$root/build/mfree" run "$here/footing.toml" --set 'constants.q="1.1 * qu"' \
     --set 'output.folder="results/plastic-footing-collapse"' --set 'output.fields=[]' \
     --set 'newton.load_factors=[0.5, 0.8, 0.85, 0.88, 0.9, 0.92, 0.94, 0.96, 0.98, 1.0]' > "$log" 2>&1; then
  echo "unexpected: the soil carried 1.1 q_u" >&2
  exit 1
fi
last=$(grep "converged: load factor" "$log" | tail -1 | sed -E 's/.*load factor ([0-9.e-]+).*/\1/')
/usr/bin/python3 -c "print(f'last converged pressure: {1.1 * $last:.4f} q_u')"
