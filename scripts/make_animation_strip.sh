#!/usr/bin/env bash
# Regenerates the picture strip of docs/animation.md (docs/img/animation/*.png): the Fox's walk
# from ../shared/data as a space-time lattice (17 frames, 2 cubic levels), frames 0, 4, 8, 12 and
# 16 as sampled, after lifting a level-0 control point on the middle of the back (point 102) up by 40 (the Fox is about 160 long) at frame 8 (it spreads over
# frames 2..14), and after the same lift at level 1 (frames 6..10 only); prints the JSON numbers.
# Usage: scripts/make_animation_strip.sh [BUILD_DIR]  (default: build)
# Needs a build with the renderer (SUBLIFT_WITH_GUI=ON) and headless EGL (Mesa is enough).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
cli="$build/app/sublift-cli"
[[ -x "$cli" ]] || { echo "no sublift-cli at $cli (pass the build directory)" >&2; exit 1; }
fox="$root/../shared/data/gltf/Fox/Fox.glb"
[[ -f "$fox" ]] || { echo "no Fox at $fox (../shared/data)" >&2; exit 1; }
out="$root/docs/img/animation"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
echo "0 8 102 0 40 0" > "$tmp/level0.txt"
echo "1 8 102 0 40 0" > "$tmp/level1.txt"
common=(animation "$fox" --animation 1 --frames 17 --levels 2)
"$cli" "${common[@]}" -o "$tmp/walk_##.obj" --json > "$tmp/walk.json"
"$cli" "${common[@]}" --edits "$tmp/level0.txt" -o "$tmp/edit0_##.obj" >/dev/null 2>&1
"$cli" "${common[@]}" --edits "$tmp/level1.txt" -o "$tmp/edit1_##.obj" >/dev/null 2>&1
for f in 00 04 08 12 16; do
  for row in walk edit0 edit1; do
    "$cli" render "$tmp/${row}_$f.obj" -o "$out/${row}_$f.png" --size 320x240 >/dev/null
  done
done
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print({k: j[k] for k in ("frames", "base_steps", "base_vertices", "finest_surface_vertices", "lattice_vertices", "finest_lattice_vertices", "fit", "wavelets", "ms")})' "$tmp/walk.json"
