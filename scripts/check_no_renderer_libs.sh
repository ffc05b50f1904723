#!/usr/bin/env bash
# fails when the executable $1 loads a GL, OSMesa or libav* library (ldd): the analysis library and what
# links it must run where the renderer's libraries are not installed (docs/architecture.md)
set -euo pipefail
exe=${1:?usage: check_no_renderer_libs.sh EXECUTABLE}
libs=$(ldd "$exe")
bad=$(grep -E 'libOSMesa|libGL|libEGL|libav(codec|format|util)|libswscale' <<<"$libs" || true)
if [[ -n $bad ]]; then
  echo "$exe loads renderer libraries:" >&2
  echo "$bad" >&2
  exit 1
fi
# a sanity check that ldd listed the libraries at all (a static or unreadable file lists none)
grep -q 'libc\.so' <<<"$libs" || { echo "$exe: ldd listed no libc, cannot tell" >&2; exit 1; }
echo "$exe: no GL, OSMesa or libav library ($(grep -c '=>' <<<"$libs") libraries)"
