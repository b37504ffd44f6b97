#!/usr/bin/env bash
# Regenerates the compression figure docs/img/compression/*.png (docs/triangle_wavelets.md): a
# head (Blender's Suzanne from ../shared/data) resampled onto the octahedron split 6 times,
# analysed with the butterfly wavelets of paper 004, and rebuilt from 1 %, 5 % and 20 % of its
# wavelet coefficients with `sublift-cli compress`; prints the errors as a Markdown table.
# Usage: scripts/make_compression_figure.sh [BUILD_DIR] [SCHEME]  (defaults: build, butterfly)
# Needs a build with the renderer (SUBLIFT_WITH_GUI=ON) and headless EGL (Mesa is enough).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
scheme="${2:-butterfly}"
cli="$build/app/sublift-cli"
[[ -x "$cli" ]] || { echo "no sublift-cli at $cli (pass the build directory)" >&2; exit 1; }
head="$root/../shared/data/control_meshes/other/suzanne.obj"
[[ -f "$head" ]] || { echo "no head model at $head (../shared/data)" >&2; exit 1; }
out="$root/docs/img/compression"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

"$cli" resample-sphere "$head" --levels 6 -o "$tmp/head.obj" --base-out "$tmp/base.obj" --force >/dev/null  # a few rays cross twice
"$cli" analyze "$tmp/head.obj" --base "$tmp/base.obj" --scheme "$scheme" --levels 6 -o "$tmp/head.sublift" >/dev/null 2>&1
"$cli" render "$tmp/head.obj" -o "$out/head_full.png" --size 400x400 >/dev/null
echo "| kept | wavelets kept | L2 error | L-infinity error |"
echo "| --- | --- | --- | --- |"
for pct in 1 5 20; do
  keep=$(printf '0.%02d' "$pct")
  json=$("$cli" compress "$tmp/head.sublift" --keep "$keep" -o "$tmp/head_$pct.obj" --json)
  "$cli" render "$tmp/head_$pct.obj" -o "$out/head_$pct.png" --size 400x400 >/dev/null
  python3 -c 'import json,sys; j=json.loads(sys.argv[2]); print("| %s %% | %d of %d | %.5f | %.5f |" % (sys.argv[1], j["kept"], j["total"], j["l2_error"], j["linf_error"]))' "$pct" "$json"
done
echo "| 100 % | all | 0 | 0 |"
