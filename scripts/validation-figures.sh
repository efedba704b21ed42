#!/usr/bin/env bash
# The cross-method validation of docs/validation.md (SPEC §13, issue 9 item 6): the diffuse Cornell
# box (scenes/cornell-box.json, 256 × 256) by classic radiosity (hemicube and ray-cast form
# factors), meshless radiosity (each basis), Whitted and the path tracer, every image measured
# against a high-sample path-traced reference; plus the path tracer at equal time to each method.
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
echo "validation: reports in $work, pictures and report.json files in $docs"
