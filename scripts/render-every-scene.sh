#!/usr/bin/env bash
# Every method renders every scene: renders every scene of scenes/ with every
# method (local, whitted, raster, radiosity, meshless, path) with the scene's own settings at
# 16 × 12 pixels (the path tracer at 2 samples a pixel), and fails — listing each pair that
# failed and its error — unless every render succeeded or was refused for memory, the documented
# refusal of a render beyond its limits (docs/reliability.md), which is listed apart: a render
# that would hold more than render.memory_limit_mib or a meshless transfer matrix past it, a
# radiosity solve whose form factors need more than radiosity.memory_limit_mib (their messages
# end "or raise render.memory_limit_mib" or "… radiosity.memory_limit_mib"), and meshless site
# sampling past meshless.max_sites ("site sampling: more than N sites", the guard of the transfer
# matrix's n² entries).
#   scripts/render-every-scene.sh CANDELA [OUT_DIR] [OPTION...]
# OUT_DIR (default, or when the first argument after CANDELA is an option: a temporary directory,
# removed) keeps each pair's image, output and exit
# status (scripts/scene-matrix.sh). Every OPTION goes to every render: the ctest
# (tests/CMakeLists.txt, scenes.every_method_renders_every_scene) gives small limits, so that the
# heavy pairs (the 10,584-sphere field by radiosity and meshless, the offices by radiosity, the
# glass globe and the two-mirror scenes by meshless: 40 s to 2 minutes each) are these refusals
# rather than minutes of work, and the others render as they are.
set -uo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 CANDELA [OUT_DIR] [OPTION...]" >&2
  exit 2
fi
candela=$(realpath "$1")
shift
if [[ $# -ge 1 && "$1" != -* ]]; then
  out=$(realpath -m "$1")
  shift
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
options=("$@")
cd "$(dirname "$0")/.." || exit 2
source scripts/scene-matrix.sh
mkdir -p "$out"

rendered=0
failed=()
refused_for_memory=()
render() {  # NAME SCENE ARGS...
  local name="$1" scene="$2" status error
  shift 2
  record_render "$candela" "$out" "$name" "$scene" --set camera.width=16 --set camera.height=12 "$@" \
    ${options[@]+"${options[@]}"}
  status=$(cat "$out/$name.status")
  error=$(grep -m1 -i 'error' "$out/$name.log" || tail -n1 "$out/$name.log")
  if [[ "$status" == 0 ]]; then
    rendered=$((rendered + 1))
  elif [[ "$status" == 2 ]] &&
    grep -Eq 'or raise (render|radiosity)\.memory_limit_mib|site sampling: more than [0-9]+ sites' \
      "$out/$name.log"; then
    refused_for_memory+=("$scene by ${name##*.}: $error")
  else
    failed+=("$scene by ${name##*.} (exit $status): $error")
  fi
}
for_every_scene_and_method render 2

echo "render-every-scene: $rendered pairs rendered, ${#refused_for_memory[@]} refused for memory," \
  "${#failed[@]} failed"
for line in ${refused_for_memory[@]+"${refused_for_memory[@]}"}; do echo "  refused for memory: $line"; done
for line in ${failed[@]+"${failed[@]}"}; do echo "  FAILED: $line"; done
[[ ${#failed[@]} -eq 0 ]]
