#!/usr/bin/env bash
# Candela's path tracer against Blender's Cycles on the glTF scenes of scenes/gltf/ (docs/import.md):
# each file as Blender's exporter wrote it (scripts/blender_gltf_scenes.py), rendered by Candela
# from the file and by Cycles after Blender's glTF importer has read it (scripts/cycles_gltf.py).
# Needs Blender (Debian's `blender`, 3.4) on the machine running it — never a dependency of
# Candela or its CI.
#
# Units: Blender's exporter writes its watts × 683 lm/W (cd, lx) and its importer divides them
# out again; Candela converts cd and lx at 179 lm/W and its pixels are π × radiance. So Candela's
# image × 179 / (683 π) is in Cycles' units: film.exposure = log2(179 / (683 π)) = −3.5835 stops.
# The textured scene's sky is not in glTF: scenes/gltf/textured-sky.json includes the file and adds
# a uniform sky of Candela colour SKY × 683 π / 179, Cycles a world of strength SKY.
#
# Each renderer renders SPP (256) samples per pixel at WIDTH × HEIGHT (320 × 240) with THREADS (2)
# threads; `candela compare` gives the mean luminances and the relative MSE of Candela's image
# against Cycles'. Side-by-side PNGs go to OUT (docs/import), the table to stdout.
#   scripts/gltf-vs-cycles.sh        # about 4 minutes on 2 cores
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
blender="${BLENDER:-blender}"
work="${WORK:-/tmp/candela-gltf-vs-cycles}"
out="${OUT:-docs/import}"
width="${WIDTH:-320}"
height="${HEIGHT:-240}"
spp="${SPP:-256}"
threads="${THREADS:-2}"
sky="0.3"
command -v "$blender" > /dev/null || { echo "gltf-vs-cycles.sh: no $blender (apt-get install blender)" >&2; exit 2; }
mkdir -p "$work" "$out"
exposure=-3.5835

printf '| scene | Candela s | Cycles s | mean luminance Candela | mean luminance Cycles | ratio | relMSE |\n'
printf '| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n'
for name in interior textured still-life; do
  gltf="scenes/gltf/$name/$name.gltf"
  scene="$gltf"
  scene_sky=0
  if [ "$name" = textured ]; then
    scene=scenes/gltf/textured-sky.json
    scene_sky="$sky"
  fi
  "$candela" render "$scene" --method path --spp "$spp" --threads "$threads" -q \
    --set "camera.width=$width" --set "camera.height=$height" --set aa.mode=none --set aa.filter=box \
    --set path.max_depth=64 --set "film.exposure=$exposure" -o "$work/$name-candela.pfm" --stats "$work/$name.json"
  candela_seconds=$(python3 -c "import json; print(json.load(open('$work/$name.json'))['phases_seconds']['render'])")
  cycles_seconds=$("$blender" -b --factory-startup -P scripts/cycles_gltf.py -- "$gltf" "$width" "$height" "$spp" \
    "$threads" "$scene_sky" "$work/$name-cycles.exr" 2>&1 | sed -n 's/^cycles-seconds //p')
  "$candela" compare "$work/$name-candela.pfm" "$work/$name-cycles.exr" --json "$work/$name-compare.json" > /dev/null
  "$candela" convert "$work/$name-candela.pfm" "$out/$name-candela.png" > /dev/null 2>&1
  "$candela" convert "$work/$name-cycles.exr" "$out/$name-cycles.png" > /dev/null 2>&1
  python3 - "$work/$name-compare.json" "$name" "$candela_seconds" "$cycles_seconds" <<'PYTHON'
import json, sys
metrics = json.load(open(sys.argv[1]))
a, b = metrics["mean_luminance"], metrics["mean_luminance_reference"]
print(f"| {sys.argv[2]} | {float(sys.argv[3]):.2f} | {float(sys.argv[4]):.2f} | {a:.4f} | {b:.4f} | {a / b:.4f} | "
      f"{metrics['relative_mse']:.4f} |")
PYTHON
done
echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores; commit $(git rev-parse --short HEAD); $("$blender" --version 2> /dev/null | head -1)"
