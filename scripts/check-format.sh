#!/usr/bin/env bash
# Fails, naming each file and line, when a C++ file of the repository differs from what
# .clang-format gives (the conventions check themselves). Fix with:
#   clang-format -i $(git ls-files '*.cpp' '*.h')
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
clang-format --dry-run -Werror "${files[@]}"
echo "check-format: ${#files[@]} files match .clang-format"
