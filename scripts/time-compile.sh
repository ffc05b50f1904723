#!/bin/bash
# A compiler or linker launcher that appends "user-CPU-s system-CPU-s wall-s output" for each compile or
# link to $ROOTSIM_CPU_LOG (default ./cpu.log): docs/performance.md, "First build".
#   cmake -S . -B build -G Ninja -DCMAKE_CXX_COMPILER_LAUNCHER=$PWD/scripts/time-compile.sh \
#         -DCMAKE_CXX_LINKER_LAUNCHER=$PWD/scripts/time-compile.sh
out=unknown prev=
for a in "$@"; do
  [ "$prev" = "-o" ] && out=$a
  prev=$a
done
exec /usr/bin/time -a -o "${ROOTSIM_CPU_LOG:-$PWD/cpu.log}" -f "%U %S %e $out" "$@"
