#!/usr/bin/env bash
# The pictures of docs/methods/raster.md (000 §3): scenes/figures/raster-shading.json
# with flat, Gouraud, Phong and dot-product shading, and the same scene ray cast for
# comparison (the exact surfaces). Usage: scripts/raster-figures.sh [candela-binary] [output-directory]
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/raster}"
mkdir -p "$out"
for shading in flat gouraud phong dotproduct; do
  "$candela" render scenes/figures/raster-shading.json -q --set raster.shading=$shading -o "$out/$shading.png"
  echo "wrote $out/$shading.png"
done
"$candela" render scenes/figures/raster-shading.json -q --method local --set local.shadows=false -o "$out/ray-cast.png"
echo "wrote $out/ray-cast.png"
