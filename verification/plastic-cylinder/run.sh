#!/usr/bin/env bash
# The plastic thick cylinder: Newton with load steps to 98 % of the limit load (the log shows
# every iteration), the table of elastic-plastic radii against the classical solution and
# cylinder.png in results/plastic-cylinder/; then the same cylinder pushed to 105 % of p_L,
# where Newton must give up just past p_L (the collapse). Installs and builds mfree when needed.
#   bash verification/plastic-cylinder/run.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
cd "$root"
"$root/build/mfree" run "$here/cylinder.toml" | tee results-plastic-cylinder.log | grep -E "^mfree|converged|load steps"
mv results-plastic-cylinder.log results/plastic-cylinder/run.log
/usr/bin/python3 "$here/check.py" results/plastic-cylinder/load_steps.csv results/plastic-cylinder
echo "beyond the limit load: p = 1.05 p_L (Newton must give up just past p_L)"
if "$root/build/mfree" run "$here/cylinder.toml" --set 'constants.p="1.05 * pL"' \
     --set 'output.folder="results/plastic-cylinder-collapse"' --set 'output.fields=[]' \
     > results/plastic-cylinder/collapse.log 2>&1; then
  echo "unexpected: the cylinder carried 1.05 p_L" >&2
  exit 1
fi
last=$(grep "converged: load factor" results/plastic-cylinder/collapse.log | tail -1 | sed -E 's/.*load factor ([0-9.e-]+).*/\1/')
/usr/bin/python3 -c "print(f'last converged pressure: {1.05 * $last:.4f} p_L (log: results/plastic-cylinder/collapse.log)')"
