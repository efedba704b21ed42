#!/usr/bin/env bash
# One entry point for a fresh machine: install what is missing, configure, build, then
#   render  render the built-in default scene to candela-default.png
#   test    run the test suite (ctest)
# Environment: BUILD_DIR (default build), CANDELA_SANITIZE=ON for ASan+UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."

action="${1:-render}"
build_dir="${BUILD_DIR:-build}"
jobs="${JOBS:-$(nproc 2>/dev/null || echo 2)}"

bash scripts/install-deps.sh
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCANDELA_WERROR=ON \
  -DCANDELA_SANITIZE="${CANDELA_SANITIZE:-OFF}"
cmake --build "$build_dir" -j "$jobs"

case "$action" in
  render)
    "$build_dir/cli/candela" render -o candela-default.png
    ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    ;;
  *)
    echo "usage: scripts/build.sh [render|test]" >&2
    exit 2
    ;;
esac
