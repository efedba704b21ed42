# shellcheck shell=bash
# Sourced, not run: every scene of scenes/ by every method, each render's output and exit status
# kept — the matrix that scripts/image-regression.sh (images to compare between builds) and
# scripts/render-every-scene.sh (every pair must render) walk. Run from the repository root.

# The methods, in the order they are rendered.
every_method=(local whitted raster radiosity meshless path)

# Every scene file of scenes/, sorted.
every_scene() {
  find scenes \( -name '*.json' -o -name '*.pbrt' -o -name '*.gltf' -o -name '*.glb' \) | sort
}

# The name of a scene's outputs: its path under scenes/ without its extension, '/' made '_'.
scene_stem() {
  local stem
  stem=$(echo "${1#scenes/}" | tr '/' '_')
  stem=${stem%.json}
  stem=${stem%.pbrt}
  stem=${stem%.gltf}
  echo "${stem%.glb}"
}

# record_render CANDELA OUT_DIR NAME SCENE OPTIONS...: `CANDELA render SCENE -o OUT_DIR/NAME.pfm
# --quiet OPTIONS`, its output into OUT_DIR/NAME.log and its exit status into OUT_DIR/NAME.status.
# The caller's array render_prefix (e.g. a timeout command) goes in front, when set.
# shellcheck disable=SC2154  # render_prefix is the caller's, and may be unset
record_render() {
  local candela="$1" out="$2" name="$3" scene="$4"
  shift 4
  ${render_prefix[@]+"${render_prefix[@]}"} "$candela" render "$scene" -o "$out/$name.pfm" --quiet "$@" \
    >"$out/$name.log" 2>&1
  echo "$?" >"$out/$name.status"
}

# for_every_scene_and_method RENDER PATH_SPP: calls `RENDER NAME SCENE --method METHOD` for every
# scene and method (NAME: the scene's stem and the method), the path tracer with --spp PATH_SPP.
for_every_scene_and_method() {
  local render="$1" path_spp="$2" scene stem method
  for scene in $(every_scene); do
    stem=$(scene_stem "$scene")
    for method in "${every_method[@]}"; do
      if [[ "$method" == path ]]; then
        "$render" "$stem.$method" "$scene" --method "$method" --spp "$path_spp"
      else
        "$render" "$stem.$method" "$scene" --method "$method"
      fi
    done
  done
}
