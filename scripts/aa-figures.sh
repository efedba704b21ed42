#!/usr/bin/env bash
# 000 Figures 52 and 53: a crop of the two-mirror scene at 1, 4 and 9 samples a pixel, uniform
# against jittered; plus adaptive (max level 3) beside its sample map and uniform 8×8; all with the
# box filter (each pixel the mean of its own samples, as in the seed).
# Usage: scripts/aa-figures.sh [candela-binary] [output-directory]
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/aa}"
crop=150,170,250,250
mkdir -p "$out"
for n in 1 2 3; do
  for mode in uniform jittered; do
    "$candela" render -q --set aa.filter=box --set aa.mode=$mode --set aa.n=$n --crop $crop -o "$out/$mode-$((n * n)).png"
  done
done
"$candela" render -q --set aa.filter=box --set aa.mode=adaptive --set aa.max_level=3 --crop $crop -o "$out/adaptive.png" \
  --aa-map "$out/adaptive-map.png" --stats "$out/adaptive-stats.json"
"$candela" render -q --set aa.filter=box --set aa.mode=uniform --set aa.n=8 --crop $crop -o "$out/uniform-64.png" \
  --stats "$out/uniform-64-stats.json"
