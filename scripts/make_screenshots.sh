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
echo "wrote $out/modeler_*.png"
