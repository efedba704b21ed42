#!/usr/bin/env bash
# The texture and environment assets of scenes/textures/ (docs/materials.md):
#   tiles.png           stone floor tiles with grout (256×256, repeats seamlessly)
#   random-squares.png  000 Figure 21: randomly colored squares, for the sphere mapping
#   uv-grid.png         a grid whose hue follows u and brightness v, for showing mappings
#   sky.exr             an equirectangular sky (gradient, sun, ground), linear half floats
#   sky-{px,nx,py,ny,pz,nz}.png  a cube map rendered by candela from sky-source.json: six 90°
#                       views from one point, in the cube map's default "inside" layout
#                       (src/shading/environment.h)
# and checks the cube map: the environment alone, seen through an oblique camera, must look
# like the source scene seen through the same camera.
# Usage: scripts/make-textures.sh [candela-binary]    (python3, standard library only)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=scenes/textures
size=256
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

python3 scripts/make_textures.py images "$out"
echo "wrote $out/tiles.png $out/random-squares.png $out/uv-grid.png $out/sky.exr"

# face, target, up: the "inside" layout's cameras (up +y for the side faces, −z looking up, +z
# looking down); each render is a face as it is.
eye="0, 1.6, 0"
while read -r face target up; do
  "$candela" render "$out/sky-source.json" --quiet --set "camera.width=$size" --set "camera.height=$size" \
    --set "camera.eye=[$eye]" --set "camera.target=$target" --set "camera.up=$up" -o "$work/$face.pfm"
  python3 scripts/make_textures.py png "$work/$face.pfm" "$out/sky-$face.png"
  echo "wrote $out/sky-$face.png"
done <<'FACES'
px [1,1.6,0] [0,1,0]
nx [-1,1.6,0] [0,1,0]
py [0,2.6,0] [0,0,-1]
ny [0,0.6,0] [0,0,1]
pz [0,1.6,1] [0,1,0]
nz [0,1.6,-1] [0,1,0]
FACES

# The check: an oblique view straight from the source scene and from the cube map alone.
check_camera='{"eye": [0, 1.6, 0], "target": [-0.8, 1.9, -1], "up": [0, 1, 0], "fov": 100, "width": 96, "height": 64}'
"$candela" render "$out/sky-source.json" --quiet --set "camera=$check_camera" --set aa.mode=none -o "$work/direct.pfm"
cat > "$work/cube.json" <<EOF
{"format": "candela/1", "camera": $check_camera,
 "environment": {"type": "cube", "faces": {"+x": "$PWD/$out/sky-px.png", "-x": "$PWD/$out/sky-nx.png",
   "+y": "$PWD/$out/sky-py.png", "-y": "$PWD/$out/sky-ny.png", "+z": "$PWD/$out/sky-pz.png", "-z": "$PWD/$out/sky-nz.png"}, "layout": "inside"},
 "shapes": []}
EOF
"$candela" render "$work/cube.json" --quiet -o "$work/cube.pfm"
echo -n "cube map against its source scene: "
python3 scripts/make_textures.py compare "$work/direct.pfm" "$work/cube.pfm"
