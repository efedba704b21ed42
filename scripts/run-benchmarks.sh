#!/usr/bin/env bash
# Runs `candela bench` on every model of ../shared/models and on the 10,584-sphere scene,
# writing one JSON file each into docs/bench/ and the tables into docs/bench/*.txt.
# Usage: scripts/run-benchmarks.sh [candela-binary] [models-directory]
# Long: about 20 minutes on a 2-core machine. Figures go into docs/benchmarks.md
# (scripts/benchmarks-to-markdown.py).
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
models="${2:-../shared/models}"
out=docs/bench
mkdir -p "$out"
accels=(bvh bvh-fast grid octree embree)
common=(--threads 1 2 --repeat 3 --min-time 1 -q)

run() {  # name, arguments...
  local name="$1"; shift
  echo "bench: $name" >&2
  "$candela" bench "$@" "${common[@]}" --json "$out/$name.json" > "$out/$name.txt"
}

run cornell_box "$models/cornell_box.obj" --accel list "${accels[@]}" \
  --eye 278 273 -800 --lookat 278 273 0 --fov 39.3 --light 278 540 279.5
for model in bunny_npm stanford_bunny dragon_100k igea; do
  run "$model" "$models/$model.obj" --accel "${accels[@]}"
done
run sphere_1M --sphere 1000000 --accel "${accels[@]}"
# 000 §5.7.2: 10,584 objects, the list against the accelerators (fewer rays: the list is slow).
run sphere_field_10584 scenes/sphere-field-10584.json --accel list bvh grid octree embree-exact \
  --width 128 --height 128 --rays 16384
# The scanline rasterizer on every model (one thread, its own framing; see benchmarks.md).
echo "bench: raster" >&2
"$candela" bench --raster "$models"/*.obj --json "$out/raster.json" > "$out/raster.txt"
# Radiosity at scale, the Cornell box meshed to 11,771 elements (3,346 patches), solved
# progressively to 0.1% unshot with 1 and 2 threads (see benchmarks.md, "Radiosity").
echo "bench: radiosity" >&2
"$candela" bench --solve radiosity scenes/cornell-box.json --set radiosity.patch_size=1 \
  --set radiosity.element_size=0.6 --threads 1 2 -q --json "$out/radiosity.json" > "$out/radiosity.txt"
# The meshless method on the Cornell box at three spacings (about 4,600, 10,200 and
# 21,000 sites; see benchmarks.md, "Meshless"): time and memory as the sites grow.
for spacing in 0.27 0.18 0.12; do
  echo "bench: meshless, spacing $spacing" >&2
  "$candela" bench --solve meshless scenes/cornell-box.json --set meshless.spacing=$spacing --set meshless.grid=128 \
    --set meshless.rounds=6 --threads 2 -q --json "$out/meshless-$spacing.json" > "$out/meshless-$spacing.txt"
done
