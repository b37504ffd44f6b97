#!/bin/sh
# Renders the README's modeler screenshots into docs/img/ with `sublift --script --headless`.
# Usage: scripts/make_screenshots.sh [BUILD_DIR]   (default: build)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
exe=$build/app/sublift
out=$here/docs/img
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
cd "$work"

# A torus: fine bumps at level 2, then a coarse edit at level 0 in world and in local frames.
cat > surface.txt <<SCRIPT
open $here/assets/torus_quad.obj
subdivide 1
level 2
soft 0.12
select 2 10 18 26 34 42 50 58 66 74 82 90
move 0 0.12 0
select
soft 0
screenshot $out/modeler_fine_edit.png
level 0
soft 0.9
select 2
move 0 0.9 0
select
screenshot $out/modeler_coarse_edit_world.png
undo
frames local
select 2
move 0 0.9 0
select
screenshot $out/modeler_coarse_edit_local.png
colour 0
screenshot $out/modeler_colour_level0.png
SCRIPT
"$exe" --script surface.txt --headless --size 1100x700

# A lattice: x-ray and a clipping plane reach an inner control point.
cat > lattice.txt <<SCRIPT
open $here/assets/hex_block_4.lattice
display xray on
clip Z 0.5
select 62
soft 0.6
move 0.25 0.25 0
screenshot $out/modeler_lattice.png
SCRIPT
"$exe" --script lattice.txt --headless --size 1100x700
# Free-form deformation: the Fox glTF sample (../shared/data) in a 3x3x3 box lattice, the head
# end of the lattice raised at level 0 and a dent pressed into the back at level 1.
fox="$here/../shared/data/gltf/Fox/Fox.glb"
if [ -f "$fox" ]; then
  cat > ffd.txt <<SCRIPT
model $fox
ffd box 3 3 3 0.05
view right
screenshot $out/ffd_fox_before.png
select 48 49 50 51 52 53 54 55 56 57 58 59 60 61 62 63
move 0 35 0
level 1
select 332
move 0 -14 0
select
level 0
view right
screenshot $out/ffd_fox_after.png
SCRIPT
  "$exe" --script ffd.txt --headless --size 1100x700
else
  echo "skipped the FFD screenshots: $fox not found (../shared/data is absent)"
fi
# Fitting scans (docs/fit.md): the scan, the base over it, the fitted levels with the level-0
# cage, and a coarse edit that carries the scan's detail. NAME FILE SOFT_RADIUS DY.
fit_pictures() {
  scan="$here/../shared/data/scans/$2"
  if [ ! -f "$scan" ]; then
    echo "skipped the fit pictures of $1: $scan not found (../shared/data is absent)"
    return
  fi
  cat > "fit_$1.txt" <<SCRIPT
open $scan
display net off
screenshot $out/fit_$1_input.png
fit-preview
screenshot $out/fit_$1_base.png
fit
display net on
screenshot $out/fit_$1_fitted.png
soft $3
select 0
move 0 $4 0
select
display net off
screenshot $out/fit_$1_edit.png
SCRIPT
  "$exe" --script "fit_$1.txt" --headless --size 1100x700
}
fit_pictures rocker rocker-arm.obj 0.35 0.12
fit_pictures fandisk fandisk.off 0.8 0.3
fit_pictures bunny stanford-bunny.obj 0.06 0.02
echo "wrote $out/modeler_*.png, $out/ffd_*.png and $out/fit_*.png"
