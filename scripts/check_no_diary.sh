#!/usr/bin/env bash
# Fails when the tree holds a diary line: an issue number of this project, a calendar date, a clock time
# or a work session named in code, tests, docs, scripts or CI. Measurements live in docs/performance.md
# and docs/numerics.md with their commands; history lives in git. References to other projects' issue
# trackers ("upstream issues #190") and dates inside test data files (an RSML's <last-modified>) are not
# diaries.
set -euo pipefail
cd "$(dirname "$0")/.."
pattern='\b[Ii]ssues? [0-9]+\b|\b20[0-9]{2}-[0-9]{2}-[0-9]{2}\b|\b[0-9]{1,2}:[0-9]{2} UTC\b|\bthis session\b|\bsession'"'"'s\b|\blast session\b'
hits=$(git ls-files -z --cached --others --exclude-standard -- src include tests docs python scripts .ci bench fuzz scenes sweeps examples shaders \
         README.md CMakeLists.txt mkdocs.yml ':!tests/data/**' ':!scripts/check_no_diary.sh' \
       | xargs -0 grep -nIE "$pattern" 2>/dev/null | grep -v 'upstream issue' || true)
if [ -n "$hits" ]; then
  echo "diary lines (issue numbers, dates, clock times or sessions belong in git history, not in the tree):"
  echo "$hits"
  exit 1
fi
echo "no diary lines"
