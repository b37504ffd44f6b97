#!/usr/bin/env bash
# Regenerates the basis-function gallery docs/img/bases/*.png (shown in docs/bases.md) with
# `sublift-cli basis --png`. Usage: scripts/make_bases_gallery.sh [BUILD_DIR]  (default: build)
# Needs a build with the renderer (SUBLIFT_WITH_GUI=ON) and headless EGL (Mesa is enough).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
cli="$build/app/sublift-cli"
[[ -x "$cli" ]] || { echo "no sublift-cli at $cli (pass the build directory)" >&2; exit 1; }
out="$root/docs/img/bases"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
a="$root/assets"

# name  input  arguments...
shot() {
  local name="$1" in="$2"
  shift 2
  local ext=ply
  echo "$name: basis $(basename "$in") $*"
  "$cli" basis "$in" "$@" -o "$tmp/$name.$ext" --png "$out/$name.png" 2>/dev/null >/dev/null
}

# Regular patch: the open 4x4 quad grid (assets/quad_grid_boundary.obj, in the xz plane), level 1
# (8x8 quads); vertex 12 is its centre. Level-2 e-vertices are 81..224, f-vertices 225..288;
# 120 is the edge midpoint at (0.25, 0), 252 the face centre at (0.25, 0.25).
grid="$a/quad_grid_boundary.obj"
shot linear_scaling_regular "$grid" --scheme linear --level 1 --vertex 12
shot cubic_scaling_regular  "$grid" --scheme cubic  --level 1 --vertex 12
shot cubic_edge_wavelet     "$grid" --scheme cubic  --level 1 --wavelet 120
shot cubic_face_wavelet     "$grid" --scheme cubic  --level 1 --wavelet 252
shot cubic_dual_scaling     "$grid" --scheme cubic  --level 1 --vertex 12 --dual --levels 2
# Extraordinary vertices of valence 3 and 5 at the centre of flat stars of kite quads, level 2
# (the support, two level-2 rings, stays two rings clear of the boundary), so the height field
# shows the function over a plane rather than the curvature of a corner.
shot cubic_scaling_valence3 "$a/star3_flat.obj" --scheme cubic --level 2 --vertex 0
shot cubic_scaling_valence5 "$a/star5_flat.obj" --scheme cubic --level 2 --vertex 0
# The centre of a flat grid whose middle row is a tagged crease (vertex 24 on the crease).
shot cubic_scaling_crease   "$a/crease_grid_flat.obj" --scheme cubic --level 1 --vertex 24
# A volume scaling function: the centre vertex 62 of the 4x4x4 hex block, level 1.
shot cubic_scaling_volume   "$a/hex_block_4.lattice" --scheme cubic --level 1 --vertex 62
# Wang & Ma's interpolatory sqrt(2) scheme on the same grid: level 2 has the 1-to-4 level-1
# topology (vertex 12 the centre again), level 1 is the diagonal grid between. Level-3 face point
# 108 sits on the level-2 face at (0.25, 0.25); its wavelet is lifted by local orthogonalisation.
shot sqrt2_scaling_regular "$grid" --scheme sqrt2 --level 2 --vertex 12
shot sqrt2_scaling_odd     "$grid" --scheme sqrt2 --level 1 --vertex 12
shot sqrt2_face_wavelet    "$grid" --scheme sqrt2 --level 2 --wavelet 108
shot sqrt2_scaling_crease  "$a/crease_grid_flat.obj" --scheme sqrt2 --level 2 --vertex 24
echo "wrote $(ls "$out"/*.png | wc -l) pictures to $out"
