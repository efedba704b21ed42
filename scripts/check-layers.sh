#!/usr/bin/env bash
# The module layering (README.md, "A tour of the code"): a module may include its own headers and
# those of modules of a LOWER rank; two modules of the same rank may not include each other. The
# modules are the folders of src/, then cli/ (the command line) and python/ (the Python module) at
# the top. Every quoted #include in src/**, cli/** and python/** (.h, .cpp, .inc, .in) is checked,
# unit tests (*_test.cpp) included: they are part of their module. Cross-module tests belong in
# tests/; a unit test may include tests/' support headers (scratch_directory.h, …), nothing else may.
#
# An include is placed by its first folder when that is a module ("math/vector.h"), else relative to
# the including file ("commands.h" in cli/, "../../tests/scratch_directory.h"), else as a support
# header of tests/ or a header the build generates (build_version.h). One it cannot place fails the
# check: a library's headers are included with <…>.
#
# Usage: scripts/check-layers.sh [SOURCE_DIR]   (default: the repository holding this script)
# Exit status: 0 when the layering holds; 1 listing file:line and the two modules for each
# include that breaks it or cannot be placed, and for each folder of src/ that has no rank; 2 on a
# usage error.
set -euo pipefail

source_dir=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
if [[ ! -d "$source_dir/src" ]]; then
  echo "check-layers: no src/ folder in '$source_dir'" >&2
  exit 2
fi
source_dir=$(cd "$source_dir" && pwd)

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
  [cli]=12 [python]=12
)
# Headers the build writes (configure steps), by the module whose folder they stand for.
declare -A generated=([build_version.h]=cli)

# placed: the module of a path relative to the source folder — src/<module>/…, cli/…, python/…,
# tests/… (test support) — or nothing (set in this shell: no subshell per include).
module_of() {
  placed=""
  case "$1" in
    src/*/*) placed=${1#src/}; placed=${placed%%/*} ;;
    cli/*) placed=cli ;;
    python/*) placed=python ;;
    tests/*) placed=tests ;;
  esac
}

status=0
fail() {
  echo "$1"
  status=1
}

for dir in "$source_dir"/src/*/; do
  module=$(basename "$dir")
  [[ -z "${rank[$module]+set}" ]] &&
    fail "src/$module: a module without a rank (add it to scripts/check-layers.sh and README.md)"
done

roots=("$source_dir/src")
for top in cli python; do [[ -d "$source_dir/$top" ]] && roots+=("$source_dir/$top"); done

# file:line:text of every quoted include.
while IFS= read -r hit; do
  file=${hit%%:*}
  rest=${hit#*:}
  line=${rest%%:*}
  text=${rest#*:}
  relative=${file#"$source_dir"/}
  module_of "$relative"
  module=$placed
  [[ -z "$module" || -z "${rank[$module]+set}" ]] && continue  # a module without a rank: listed above
  if ! [[ "$text" =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^\"]+)\" ]]; then
    fail "$relative:$line: $module has an #include the check cannot read: $text"
    continue
  fi
  header=${BASH_REMATCH[1]}
  first=${header%%/*}
  target=""
  if [[ "$header" == */* && -n "${rank[$first]+set}" ]]; then
    target=$first
  elif [[ -f "$(dirname "$file")/$header" ]]; then
    resolved=$(realpath -m "$(dirname "$file")/$header")
    module_of "${resolved#"$source_dir"/}"
    target=$placed
  elif [[ -f "$source_dir/tests/$header" ]]; then
    target=tests
  elif [[ -n "${generated[$header]+set}" ]]; then
    target=${generated[$header]}
  fi
  if [[ -z "$target" ]]; then
    fail "$relative:$line: $module includes \"$header\", which is no module's header, no file beside it and no support header of tests/ (a library's headers are included with <…>)"
    continue
  fi
  [[ "$target" == "$module" ]] && continue
  if [[ "$target" == tests ]]; then
    [[ "$file" == *_test.cpp ]] ||
      fail "$relative:$line: $module includes \"$header\", a support header of tests/, outside a unit test"
    continue
  fi
  if ((rank[$target] >= rank[$module])); then
    relation="higher"
    ((rank[$target] == rank[$module])) && relation="same-rank"
    fail "$relative:$line: $module (rank ${rank[$module]}) includes \"$header\" of $target (rank ${rank[$target]}, $relation)"
  fi
done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "${roots[@]}" \
           --include='*.h' --include='*.cpp' --include='*.inc' --include='*.in' || true)

if ((status != 0)); then
  echo "check-layers: the module layering is broken (README.md, \"A tour of the code\")" >&2
fi
exit $status
