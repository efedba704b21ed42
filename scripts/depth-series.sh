#!/usr/bin/env bash
# 000 Figure 51: the two-mirror scene with the ray tree cut at depth 0, 1, 2 and 3.
# Usage: scripts/depth-series.sh [candela-binary] [output-directory]
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images}"
mkdir -p "$out"
for depth in 0 1 2 3; do
  "$candela" render scenes/two-mirrors.json --quiet --set whitted.max_depth="$depth" \
    -o "$out/two-mirrors-depth-$depth.png"
  echo "wrote $out/two-mirrors-depth-$depth.png"
done
