#!/usr/bin/env bash
# The office-with-a-window figures of docs/lighting-design.md: scenes/office-daylight.json
# rendered by path and radiosity, and its work plane (0.8 m up, 0.25 m in from the walls, 50 × 70
# points) probed by radiosity with the downlights on (lux) and off (the daylight factor), with the
# false-colour images and the JSON summaries (the CSVs to /tmp), and the radiosity render's
# luminance in false colour, into docs/images/probe/.
# Usage: scripts/office-daylight-figures.sh [candela-binary]   (about 10 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=docs/images/probe
mkdir -p "$out"
scene=scenes/office-daylight.json
plane=(--grid 0.25,0.8,0.25,0,0,2.5,3.5,0,0 --grid-size 50,70 --contours 8 --samples 1024)
"$candela" render "$scene" --method path -o "$out/office-daylight-path.png" --stats "$out/office-daylight-path.json" -q
"$candela" render "$scene" --method radiosity -o "$out/office-daylight-radiosity.png" \
  --stats "$out/office-daylight-radiosity.json" -q
"$candela" probe "$scene" --method radiosity "${plane[@]}" -o /tmp/office-daylight-plane.csv \
  --image "$out/office-daylight-plane.png" --json "$out/office-daylight-plane.json"
"$candela" probe "$scene" --method radiosity --set 'lights=[]' "${plane[@]}" --daylight-factor \
  -o /tmp/office-daylight-df.csv --image "$out/office-daylight-df.png" --json "$out/office-daylight-df.json"
# The radiosity render's luminance in false colour (cd/m², logarithmic, 3 decades, 6 contour steps):
# film.exposure is −2 in the scene, undone by --exposure.
"$candela" render "$scene" --method radiosity -o /tmp/office-daylight-radiosity.exr -q
"$candela" falsecolor /tmp/office-daylight-radiosity.exr --exposure -2 --log --contours 6 \
  -o "$out/office-daylight-luminance.png" --json "$out/office-daylight-luminance.json"
