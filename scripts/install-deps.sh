#!/usr/bin/env bash
# Installs rootsim's build and run dependencies from Debian's packages (needs root). Idempotent: only
# missing packages are installed.
set -euo pipefail
pkgs=(cmake ninja-build g++ pkg-config
      libeigen3-dev libcli11-dev doctest-dev libtomlplusplus-dev libbenchmark-dev
      libsuitesparse-dev                # KLU: the sparse Newton step with self-contact
      libtinyxml2-dev                   # the RSML reader (src/io/rsml.cpp: XML with line numbers)
      libnlopt-dev                      # `rootsim fit` (src/analysis/fit_trace.cpp): BOBYQA on the response surface
      libssl-dev                        # OpenSSL's libcrypto: SHA-256 of what rootsim wrote (markers, signatures)
      nlohmann-json3-dev                # every JSON file rootsim writes (src/io/json.cpp), a GLB's JSON read back (write_rule.cpp)
      libosmesa6-dev libglm-dev libstb-dev libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
      libcairo2-dev fonts-dejavu-core python3 zlib1g-dev
      libpng-dev                        # every PNG rootsim writes (png_encode.hpp: pHYs, the signature tEXt) and reads
      python3-dev pybind11-dev python3-pybind11 python3-numpy   # the Python package (python/)
      python3-pytest python3-matplotlib                         # its tests; examples/*.py
      clang libclang-rt-dev             # sanitizer + libFuzzer build (.ci/run, scripts/fuzz.sh)
      slurm-wlm munge                   # tests/slurm/run.sh: a sweep through a single-node SLURM
      chromium                          # ctest figures_report_html: report.html in a headless browser
      paraview python3-paraview xvfb xauth  # ctest paraview_script: pvpython opens export --paraview's script
                                        # python3-paraview's pvpython also runs tests/vtk_read.py (VTK's own
                                        # reader reads the .vtp files); it conflicts with python3-vtk9, so not that
      mkdocs                            # the docs site (ctest docs_site_builds)
      nodejs                            # ctest gltf_validator: the Khronos glTF-Validator (npm, below)
      blender                           # ctest gltf_blender: Blender imports and renders the .glb
      poppler-utils)                    # tests/test_figure.cpp: pdftotext, pdfimages read the PDF panels
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm: Debian's package, unless the installed Node brings its own (NodeSource's nodejs does)
command -v npm >/dev/null || missing+=(npm)
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "all dependencies present"
fi
# the Khronos glTF-Validator (ctest gltf_validator, tests/gltf/validate.js): an npm package, pinned
if ! (cd / && node -e "require(require('path').join('$(npm root -g)', 'gltf-validator'))") 2>/dev/null; then
  echo "installing: npm gltf-validator@2.0.0-dev.3.10"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO npm install -g gltf-validator@2.0.0-dev.3.10
fi
