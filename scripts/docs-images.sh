#!/bin/sh
# Regenerates the pictures of docs/rendering.md and the README (docs/img/*.png, a few tens of kB each)
# from short runs of the shipped scenes. Usage: scripts/docs-images.sh [BUILD_DIR] (default build)
set -eu
build=${1:-build}
rootsim="$build/rootsim"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs/img
# the waving root of Fig. 2B for 45 h, and the Fig. 2A tilt series for 30 h
"$rootsim" run scenes/fig2b_waving.toml --set growth.steps=900 --out "$work/wave" --quiet
for a in 20 40 60 80; do
  "$rootsim" run "scenes/fig2a_alpha$a.toml" --set growth.steps=600 --out "$work/a$a" --quiet
done
# frame N of a render into docs/img/NAME.png
frame() {
  name=$1 n=$2
  shift 2
  "$rootsim" render "$@" --quiet --png-dir "$work/$name"
  cp "$work/$name/frame_$(printf %05d "$n").png" "docs/img/$name.png"
}
frame fit 90 "$work/wave" --size 640x360
frame follow 90 "$work/wave" --size 640x360 --camera follow --field-mm 2
frame inset 90 "$work/wave" --size 640x360 --inset --field-mm 2
frame colour 90 "$work/wave" --size 640x360 --camera follow --field-mm 2 --color-by twist
frame plot 60 "$work/wave" --size 800x450 --color-by curvature --plot theta_tip,Eb,Tw
frame shadows 45 "$work/a80" --size 480x270 --camera follow --field-mm 1.5 --shadows
"$rootsim" montage "$work/a20" "$work/a40" "$work/a60" "$work/a80" --size 800x450 --quiet --png-dir "$work/montage"
cp "$work/montage/frame_00060.png" docs/img/montage.png
ls -l docs/img
