#!/usr/bin/env bash
# Fails when the tree holds a diary line: an issue number of this project, a calendar date, a clock time
# or a work session named in code, tests, docs, scripts or CI, or a measurement note in code. Measurements live in docs/performance.md
# and docs/numerics.md with their commands; history lives in git. References to other projects' issue
# trackers ("upstream issues #190") and dates inside test data files (an RSML's <last-modified>) are not
# diaries.
set -euo pipefail
cd "$(dirname "$0")/.."
pattern='\b[Ii]ssues? [0-9]+\b|\b20[0-9]{2}-[0-9]{2}-[0-9]{2}\b|\b[0-9]{1,2}:[0-9]{2} UTC\b|\bthis session\b|\bsession'"'"'s\b|\blast session\b'
hits=$(git ls-files -z --cached --others --exclude-standard -- src include tests docs python scripts .ci bench fuzz scenes sweeps examples shaders \
         README.md CMakeLists.txt mkdocs.yml ':!tests/data/**' ':!scripts/check_no_diary.sh' \
       | xargs -0 grep -nIE "$pattern" 2>/dev/null | grep -v 'upstream issue' || true)
# measurement notes in code (a timing, a speed-up, a before -> after count): they live in
# docs/performance.md or docs/numerics.md with the command that reproduces them; a comment keeps its
# reasoning and points there
measure='\((measured|measured on [^)]*)[:;] |\b[0-9][0-9.]* ?(µs|us|ms) (for|a|per|on)\b|\b[0-9][0-9.]* ?x (faster|slower|cheaper|less)\b|\b[0-9]+ -> [0-9]+ '
notes=$(git ls-files -z --cached --others --exclude-standard -- src include python/src python/rootsim bench fuzz shaders \
          CMakeLists.txt ':!tests/data/**' \
        | xargs -0 grep -nIE "$measure" 2>/dev/null || true)
if [ -n "$hits" ]; then
  echo "diary lines (issue numbers, dates, clock times or sessions belong in git history, not in the tree):"
  echo "$hits"
fi
if [ -n "$notes" ]; then
  echo "measurement notes in code (move them to docs/performance.md or docs/numerics.md with their command):"
  echo "$notes"
fi
if [ -n "$hits" ] || [ -n "$notes" ]; then exit 1; fi
echo "no diary lines"
