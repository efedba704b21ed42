#!/usr/bin/env bash
# The module layering of src/ (README.md, "A tour of the code"): a module may include its own
# headers and those of modules of a LOWER rank; two modules of the same rank may not include
# each other. Every `#include "module/..."` in src/<module>/** is checked, unit tests
# (*_test.cpp) included: they are part of their module. Cross-module tests belong in tests/.
#
# Usage: scripts/check-layers.sh [SOURCE_DIR]   (default: the repository holding this script)
# Exit status: 0 when the layering holds; 1 listing file:line and the two modules for each
# include that breaks it, and for each folder of src/ that has no rank; 2 on a usage error.
set -euo pipefail

source_dir=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
if [[ ! -d "$source_dir/src" ]]; then
  echo "check-layers: no src/ folder in '$source_dir'" >&2
  exit 2
fi

# Rank of each module, bottom to top. Keep in step with README.md.
declare -A rank=(
  [math]=0
  [util]=1
  [sampling]=2
  [geometry]=3 [camera]=3
  [io]=4
  [distributed]=5
  [shading]=6 [accel]=6
  [scene]=7
  [raster]=8
  [radiosity]=9 [meshless]=9
  [integrators]=10
  [bench]=11 [validate]=11
)

status=0
for dir in "$source_dir"/src/*/; do
  module=$(basename "$dir")
  if [[ -z "${rank[$module]+set}" ]]; then
    echo "src/$module: a module without a rank (add it to scripts/check-layers.sh and README.md)"
    status=1
    continue
  fi
  # file:line:text of every quoted include that names a folder.
  while IFS= read -r hit; do
    file=${hit%%:*}
    rest=${hit#*:}
    line=${rest%%:*}
    text=${rest#*:}
    target=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"([^/"]+)\/.*/\1/' <<<"$text")
    [[ "$target" == "$module" ]] && continue
    [[ -z "${rank[$target]+set}" ]] && continue  # not a module of src/ (a library's folder)
    if ((rank[$target] >= rank[$module])); then
      relative=${file#"$source_dir"/}
      header=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)".*/\1/' <<<"$text")
      relation="higher"
      ((rank[$target] == rank[$module])) && relation="same-rank"
      echo "$relative:$line: $module (rank ${rank[$module]}) includes \"$header\" of $target" \
           "(rank ${rank[$target]}, $relation)"
      status=1
    fi
  done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^/"]+/' "$dir" \
             --include='*.h' --include='*.cpp' --include='*.in' || true)
done

if ((status != 0)); then
  echo "check-layers: the module layering is broken (README.md, \"A tour of the code\")" >&2
fi
exit $status
