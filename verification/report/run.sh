#!/usr/bin/env bash
# Verification report: installs and builds mfree when needed (.ci/setup), reruns every
# verification study and writes REPORT.md with tables and PNG figures.
#   bash verification/report/run.sh                 full: verification/REPORT.md (~34 min on 2 cores)
#   bash verification/report/run.sh --quick --out build/report-quick    coarse levels, a few minutes
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
bash "$root/.ci/setup"
/usr/bin/python3 "$here/report.py" "$@"
