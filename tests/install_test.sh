#!/usr/bin/env bash
# `cmake --install` into a scratch prefix: PREFIX/bin/candela runs and says its
# version; with a Python interpreter given, the module `candela` imports from
# PREFIX/lib/python3/dist-packages (where Debian's python3 looks under /usr and /usr/local).
# Usage: tests/install_test.sh BUILD_DIR [PYTHON]
set -euo pipefail
build=${1:?usage: install_test.sh BUILD_DIR [PYTHON]}
python=${2:-}
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > "$prefix/install.log"
version=$("$prefix/bin/candela" --version)
case "$version" in
  "candela 0.1.0 (commit "*) ;;
  *) echo "FAIL: $prefix/bin/candela --version said: $version"; exit 1 ;;
esac
if [ -n "$python" ]; then
  # From the prefix, not the build tree (ctest runs in build/python, beside the built module).
  (cd "$prefix" && PYTHONPATH="$prefix/lib/python3/dist-packages" "$python" - "$prefix" <<'PYTHON'
import sys
import candela
assert candela.__file__.startswith(sys.argv[1] + "/lib/python3/dist-packages/"), candela.__file__
assert callable(candela.render) and callable(candela.load_file)
print("installed module:", candela.__file__)
PYTHON
  )
fi
echo "install: $version"
