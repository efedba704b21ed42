#!/usr/bin/env bash
# The path tracer's throughput (docs/benchmarks.md "Path tracing"): the Cornell box of
# scenes/cornell-box.json with the 100,000-triangle dragon of ../shared/models standing in it,
# 256 × 256, 64 spp, with each accelerator; prints seconds, rays and Mrays/s, checks that
# every exact accelerator gives the same image bytes, and measures bvh-fast's image against bvh's.
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
work="${WORK:-/tmp/candela-path-bench}"
models="$(cd .. && pwd)/shared/models"
mkdir -p "$work"
python3 - scenes/cornell-box.json "$work/dragon-box.json" "$models/dragon_100k.obj" <<'PYTHON'
import sys
text = open(sys.argv[1]).read()
last = text.rindex(']')
dragon = (',\n    {"name": "dragon", "type": "mesh", "file": "%s", "material": "light-grey",'
          ' "transform": [{"scale": 0.33}, {"rotate": {"angle": -30, "axis": [0, 1, 0]}}, {"translate": [4.6, 0, 6.6]}]}\n  '
          % sys.argv[3])
open(sys.argv[2], 'w').write(text[:last].rstrip() + dragon + text[last:])
PYTHON
for accelerator in list bvh bvh-fast embree; do
  [ "$accelerator" = list ] && [ "${WITH_LIST:-0}" != 1 ] && continue  # 100,000 triangles: hours
  "$candela" render "$work/dragon-box.json" --method path --spp "${SPP:-64}" --accel "$accelerator" -q \
    -o "$work/$accelerator.exr" --stats "$work/$accelerator.json"
  python3 - "$work/$accelerator.json" "$accelerator" <<'PYTHON'
import json, sys
stats = json.load(open(sys.argv[1]))
seconds = stats["phases_seconds"]["render"]
rays = stats["rays"]
print(f"{sys.argv[2]:8s} build {stats['phases_seconds']['build']:.2f} s  render {seconds:.2f} s  "
      f"{rays['total']:,} rays ({rays['primary']:,} primary, {rays['shadow']:,} shadow, "
      f"{rays['reflected']:,} bounces)  {rays['total'] / seconds / 1e6:.2f} Mrays/s")
PYTHON
done
cmp "$work/bvh.exr" "$work/embree.exr" && echo "bvh and embree: the same image bytes"
# bvh-fast is outside the exact contract (docs/accelerators.md): how far its image is from bvh's.
"$candela" compare "$work/bvh-fast.exr" "$work/bvh.exr" --diff "$work/bvh-fast-difference.png"
