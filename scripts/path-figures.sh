#!/usr/bin/env bash
# The pictures of docs/methods/path.md: scenes/cornell-box.json at 256 × 256
#   cornell-box-path.png        the path-traced reference, REFERENCE_SPP (2048) Sobol' passes
#   cornell-box-radiosity.png   classic radiosity (the scene's own settings, Gouraud display)
#   sampler-NAME-16spp.png      each path.sampler at 16 spp, to set beside the reference
# Every path image: one point per pixel and pass, box filter (aa.mode none, the default).
# Usage: scripts/path-figures.sh [candela-binary] [output-directory]   (about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/path}"
scene=scenes/cornell-box.json
reference_spp="${REFERENCE_SPP:-2048}"
mkdir -p "$out"
box=(--set aa.mode=none --set aa.filter=box)
"$candela" render "$scene" --method path --spp "$reference_spp" "${box[@]}" -q -o "$out/cornell-box-path.png"
"$candela" render "$scene" --method radiosity --set 'radiosity.display="gouraud"' -q \
  -o "$out/cornell-box-radiosity.png"
for sampler in independent stratified sobol; do
  "$candela" render "$scene" --method path --spp 16 "${box[@]}" --set "path.sampler=$sampler" -q \
    -o "$out/sampler-$sampler-16spp.png"
done
