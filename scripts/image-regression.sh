#!/usr/bin/env bash
# Renders every scene of scenes/ with every method (and the radiosity and meshless variants) at a
# small size into OUT_DIR, one .pfm each, so that two builds can be compared byte for byte:
#   scripts/image-regression.sh CANDELA OUT_DIR        # e.g. before and after a redesign
#   cmp -s before/x.pfm after/x.pfm
# A render that fails or takes over 120 s is recorded as such (OUT_DIR/NAME.status) and compared
# like an image. Not part of CI (minutes on 2 cores).
set -uo pipefail
candela="$1"
out="$2"
cd "$(dirname "$0")/.."
source scripts/scene-matrix.sh
mkdir -p "$out"
size=(--set camera.width=40 --set camera.height=30)
render_prefix=(timeout -k 5 120)
render() {  # NAME SCENE ARGS...
  local name="$1" scene="$2"
  shift 2
  record_render "$candela" "$out" "$name" "$scene" --threads 2 "${size[@]}" "$@"
}
for_every_scene_and_method render 4
scene=scenes/cornell-box.json
for solver in gauss-seidel gaussian; do
  render "variant.radiosity-$solver" $scene --method radiosity --set radiosity.solver=$solver
done
for display in flat ray-traced elements; do
  render "variant.radiosity-$display" $scene --method radiosity --set radiosity.display=$display
done
render variant.radiosity-ray-cast $scene --method radiosity --set radiosity.form_factors=ray-cast
render variant.radiosity-no-ambient $scene --method radiosity --set radiosity.ambient=false
render variant.radiosity-subdivision $scene --method radiosity --set radiosity.subdivision_threshold=0.2
render variant.radiosity-gs-subdivision $scene --method radiosity --set radiosity.solver=gauss-seidel \
  --set radiosity.subdivision_threshold=0.2
render variant.radiosity-contacts $scene --method radiosity --set radiosity.split_at_contacts=true
for basis in radial shepard; do
  render "variant.meshless-$basis" $scene --method meshless --set meshless.basis=$basis
done
for display in direct indirect hybrid; do
  render "variant.meshless-$display" $scene --method meshless --set meshless.display=$display
done
render variant.meshless-cubic $scene --method meshless --set meshless.basis=radial --set meshless.kernel=cubic
render variant.meshless-thesis $scene --method meshless --set meshless.effective_area=thesis
for accel in grid octree bvh embree; do
  render "variant.whitted-$accel" scenes/two-mirrors.json --accel $accel
done
render variant.raster-flat scenes/figures/raster-shading.json --method raster --set raster.shading=flat
render variant.raster-gouraud scenes/figures/raster-shading.json --method raster --set raster.shading=gouraud
render variant.raster-dotproduct scenes/figures/raster-shading.json --method raster --set raster.shading=dotproduct
render variant.aa-adaptive scenes/two-mirrors.json --set aa.mode=adaptive
render variant.cameras-all scenes/cornell-box.json --camera all
render variant.radiosity-export $scene --method radiosity --export-solution "$out/variant.radiosity-export.csv"
render variant.radiosity-export-ply $scene --method radiosity --export-solution "$out/variant.radiosity-export.ply"
render variant.meshless-sites $scene --method meshless --show-sites "$out/variant.meshless-sites.sites.pfm"
