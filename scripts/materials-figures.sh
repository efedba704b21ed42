#!/usr/bin/env bash
# The pictures of docs/materials.md (materials, textures, environment and bump mapping,
# transparency): every scene of scenes/figures/ into docs/images/materials/NAME.png, and
# scenes/materials-gallery.json into docs/images/materials-gallery.png. Prints each render time.
# The textures they use are made by scripts/make-textures.sh.
# Usage: scripts/materials-figures.sh [candela-binary] [output-directory]
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/materials}"
mkdir -p "$out"
render() {  # scene output
  local start=$EPOCHREALTIME
  "$candela" render "$1" --quiet -o "$2"
  awk -v file="$2" -v start="$start" -v end="$EPOCHREALTIME" 'BEGIN { printf "wrote %s (%.1f s)\n", file, end - start }'
}
for scene in scenes/figures/*.json; do
  [ "$(basename "$scene")" = raster-shading.json ] && continue  # scripts/raster-figures.sh draws it
  render "$scene" "$out/$(basename "$scene" .json).png"
done
render scenes/materials-gallery.json "$(dirname "$out")/materials-gallery.png"
