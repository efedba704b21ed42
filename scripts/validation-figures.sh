#!/usr/bin/env bash
# The cross-method validation of docs/validation.md (SPEC §13): the diffuse Cornell
# box (scenes/cornell-box.json, 256 × 256) by classic radiosity (hemicube and ray-cast form
# factors), meshless radiosity (each basis), Whitted and the path tracer, every image measured
# against a high-sample path-traced reference; plus the path tracer at equal time to each method;
# then the same room lit by a point light only (scenes/cornell-box-point.json).
#
#   scripts/validation-figures.sh            # after scripts/build.sh; ≈ 15 min on 2 cores
#   REFERENCE_SPP=2048 scripts/validation-figures.sh   # a quicker, noisier reference
#
# The reference is rendered once into $WORK (checkpointed: an interrupted run goes on where it
# stopped) with seed 0; every report renders with render.seed = 1, so that the path tracer's own
# entries do not share samples with the reference. Copies the pictures and the report.json files
# into docs/images/validation/cornell/.
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
work="${WORK:-/tmp/candela-validation}"
spp="${REFERENCE_SPP:-8192}"
scene=scenes/cornell-box.json
docs=docs/images/validation/cornell
mkdir -p "$work" "$docs"

reference="$work/reference.exr"
if [ ! -f "$reference" ] || [ "${RENDER_REFERENCE:-0}" = 1 ]; then
  resume=()
  if [ -f "$work/reference.ckpt" ]; then resume=(--resume "$work/reference.ckpt"); fi
  "$candela" render "$scene" --method path --spp "$spp" "${resume[@]}" --checkpoint "$work/reference.ckpt" \
    --checkpoint-every 60 -q -o "$reference" --stats "$work/reference-stats.json"
fi

report() {  # name, then candela report options
  local name="$1"
  shift
  "$candela" report "$scene" --reference "$reference" --set render.seed=1 -q -o "$work/$name" "$@"
  cp "$work/$name/report.json" "$docs/$name.json"
  for image in "$work/$name"/*.png; do
    base="$(basename "$image" .png)"
    [ "$base" = reference ] && continue
    cp "$image" "$docs/$name-$base.png"
  done
}

# Classic radiosity, the scene's own settings (hemicube), then ray-cast form factors; Whitted; the
# path tracer at 64 spp; each with the path tracer at equal time.
report radiosity-hemicube --methods radiosity,whitted,path --spp 64 --equal-time
report radiosity-ray-cast --methods radiosity --equal-time --set radiosity.form_factors=ray-cast
for basis in normalized shepard radial; do
  report "meshless-$basis" --methods meshless --equal-time --set meshless.basis="$basis" --set meshless.spacing=0.35
done
cp "$work/radiosity-hemicube/reference.png" "$docs/reference.png"

# The same errors without the lamp: its 12-valued pixels dominate every sum, and only the path
# tracer draws its sharp edge. The mask is the scene rendered by the local model with every
# surface emitting 1 and the lamp, enlarged by 0.15 on each side, emitting 0.
python3 - "$scene" "$work/mask-scene.json" <<'PYTHON'
import sys
text = open(sys.argv[1]).read()
lamp = '{"name": "light", "type": "quad", "corner": [4, 8, 4], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "material": "lamp"}'
assert lamp in text
text = text.replace(lamp, lamp.replace('[4, 8, 4]', '[3.85, 7.99, 3.85]').replace('[2, 0, 0]', '[2.3, 0, 0]')
                    .replace('[0, 0, 2]', '[0, 0, 2.3]'))
for name in ['red', 'blue', 'light-grey', 'grey', 'black', 'yellow']:
    text = text.replace('"%s": {"kd"' % name, '"%s": {"emission": 1, "kd"' % name)
text = text.replace('"lamp": {"kd": 0, "emission": [12, 12, 11]}', '"lamp": {"kd": 0, "emission": 0}')
open(sys.argv[2], 'w').write(text)
PYTHON
"$candela" render "$work/mask-scene.json" --method local --set ambient=0 -q -o "$work/no-lamp-mask.png"
cp "$work/no-lamp-mask.png" "$docs/no-lamp-mask.png"
for report_dir in "$work"/radiosity-* "$work"/meshless-*; do
  name="$(basename "$report_dir")"
  for image in "$report_dir"/*.exr; do
    base="$(basename "$image" .exr)"
    [ "$base" = reference ] && continue
    "$candela" compare "$image" "$reference" --mask "$work/no-lamp-mask.png" --json "$docs/$name-$base-no-lamp.json" > /dev/null
  done
done
# The same room lit by a point light only (scenes/cornell-box-point.json), against its own
# reference of as many samples.
point_scene=scenes/cornell-box-point.json
point_docs=docs/images/validation/cornell-point
point_reference="$work/point-reference.exr"
mkdir -p "$point_docs"
if [ ! -f "$point_reference" ] || [ "${RENDER_REFERENCE:-0}" = 1 ]; then
  resume=()
  if [ -f "$work/point-reference.ckpt" ]; then resume=(--resume "$work/point-reference.ckpt"); fi
  "$candela" render "$point_scene" --method path --spp "$spp" "${resume[@]}" \
    --checkpoint "$work/point-reference.ckpt" --checkpoint-every 60 -q -o "$point_reference" \
    --stats "$work/point-reference-stats.json"
fi
"$candela" report "$point_scene" --reference "$point_reference" --set render.seed=1 -q -o "$work/point" \
  --methods radiosity,whitted,meshless,path --spp 64
cp "$work/point/report.json" "$point_docs/report.json"
cp "$work/point"/*.png "$point_docs/"

echo "validation: reports in $work, pictures and report.json files in $docs and $point_docs"
