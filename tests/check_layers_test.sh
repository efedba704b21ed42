#!/usr/bin/env bash
# The layer check itself (scripts/check-layers.sh): it passes on a tree that keeps the layering (src/,
# cli/, python/, relative includes, .inc files, test support headers in unit tests only)
# and fails, naming file:line and both modules, on each kind of violation.
# Usage: tests/check_layers_test.sh PATH/TO/check-layers.sh
set -euo pipefail

check=${1:?usage: check_layers_test.sh PATH/TO/check-layers.sh}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

# A tree with a few modules that keep the layering: lower ranks only, own headers, library folders.
make_tree() {
  rm -rf "$scratch/tree"
  mkdir -p "$scratch/tree/src/math" "$scratch/tree/src/io" "$scratch/tree/src/scene"
  printf '#pragma once\n' >"$scratch/tree/src/math/vector.h"
  printf '#include "io/reader.h"\n\n#include <nlohmann/json.hpp>\n#include "math/vector.h"\n' \
    >"$scratch/tree/src/io/reader.cpp"
  printf '#pragma once\n#include "math/vector.h"\n#include <tinygltf/tiny_gltf.h>\n' >"$scratch/tree/src/io/reader.h"
  printf '#include "scene/scene.h"\n#include "io/reader.h"\n  #  include "math/vector.h"\n' \
    >"$scratch/tree/src/scene/scene.cpp"
}

# expect STATUS DESCRIPTION [TEXT...]: the check's exit status, and each TEXT in its output.
expect() {
  local want=$1 description=$2
  shift 2
  local output got=0
  output=$(bash "$check" "$scratch/tree" 2>&1) || got=$?
  if [[ "$got" != "$want" ]]; then
    echo "FAIL: $description: exit status $got, expected $want; output:"
    echo "$output"
    failures=$((failures + 1))
    return
  fi
  for text in "$@"; do
    if ! grep -qF -- "$text" <<<"$output"; then
      echo "FAIL: $description: no '$text' in the output:"
      echo "$output"
      failures=$((failures + 1))
    fi
  done
  echo "ok: $description"
}

make_tree
expect 0 "a tree that keeps the layering passes"

make_tree
printf '#include "math/vector.h"\n#include "scene/scene.h"\n' >"$scratch/tree/src/io/writer.cpp"
expect 1 "a module including a higher one fails" \
  'src/io/writer.cpp:2: io (rank 4) includes "scene/scene.h" of scene (rank 7, higher)'

make_tree
printf '#include "io/reader.h"\n' >"$scratch/tree/src/math/vector_test.cpp"
expect 1 "a unit test including a higher module fails" 'src/math/vector_test.cpp:1: math (rank 0)'

make_tree
mkdir -p "$scratch/tree/src/camera" "$scratch/tree/src/geometry"
printf '#pragma once\n' >"$scratch/tree/src/geometry/shape.h"
printf '\n#include "geometry/shape.h"\n' >"$scratch/tree/src/camera/camera.h"
expect 1 "two modules of the same rank fail" \
  'src/camera/camera.h:2: camera (rank 3) includes "geometry/shape.h" of geometry (rank 3, same-rank)'

make_tree
mkdir -p "$scratch/tree/src/newmodule"
expect 1 "a module without a rank fails" "src/newmodule: a module without a rank"

make_tree
mkdir -p "$scratch/tree/src/scene"
printf '#include "radiosity/radiosity_settings.h"\n' >"$scratch/tree/src/scene/scene.h"
expect 1 "the scene including a method's settings fails" \
  'src/scene/scene.h:1: scene (rank 7) includes "radiosity/radiosity_settings.h" of radiosity (rank 9, higher)'

# cli/ and python/ are the top modules: they may include any of src/, not each other, and src/ may
# include neither.
make_tree
mkdir -p "$scratch/tree/cli" "$scratch/tree/python"
printf '#pragma once\n' >"$scratch/tree/cli/commands.h"
printf '#include "commands.h"\n#include "scene/scene.h"\n' >"$scratch/tree/cli/main.cpp"
printf '#include "scene/scene.h"\n' >"$scratch/tree/python/module.cpp"
expect 0 "cli/ and python/ including src/ and their own headers pass"
printf '#include "../cli/commands.h"\n' >>"$scratch/tree/python/module.cpp"
expect 1 "python/ including cli/ fails" \
  'python/module.cpp:2: python (rank 12) includes "../cli/commands.h" of cli (rank 12, same-rank)'

make_tree
mkdir -p "$scratch/tree/cli"
printf '#pragma once\n' >"$scratch/tree/cli/commands.h"
printf '#include "../../cli/commands.h"\n' >"$scratch/tree/src/io/writer.cpp"
expect 1 "a relative include of a higher module fails" \
  'src/io/writer.cpp:1: io (rank 4) includes "../../cli/commands.h" of cli (rank 12, higher)'

make_tree
printf '#include "scene/scene.h"\n' >"$scratch/tree/src/io/traversal.inc"
expect 1 "an .inc file is checked" 'src/io/traversal.inc:1: io (rank 4) includes "scene/scene.h"'

make_tree
printf '#include "tinygltf/tiny_gltf.h"\n' >>"$scratch/tree/src/io/reader.cpp"
printf '#include "nowhere.h"\n' >>"$scratch/tree/src/scene/scene.cpp"
expect 1 "an include that cannot be placed fails" \
  'src/io/reader.cpp:5: io includes "tinygltf/tiny_gltf.h", which is no module' \
  'src/scene/scene.cpp:4: scene includes "nowhere.h", which is no module'

make_tree
mkdir -p "$scratch/tree/tests"
printf '#pragma once\n' >"$scratch/tree/tests/scratch_directory.h"
printf '#include "scratch_directory.h"\n#include "../../tests/scratch_directory.h"\n' >"$scratch/tree/src/io/reader_test.cpp"
expect 0 "a unit test including a support header of tests/ passes"
printf '#include "scratch_directory.h"\n' >"$scratch/tree/src/io/writer.cpp"
expect 1 "a module's own code including a support header of tests/ fails" \
  'src/io/writer.cpp:1: io includes "scratch_directory.h", a support header of tests/, outside a unit test'

make_tree
printf '#include "math/vector.h\n' >"$scratch/tree/src/io/writer.cpp"
expect 1 "an include the check cannot read fails" \
  'src/io/writer.cpp:1: io has an #include the check cannot read'

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
