#!/usr/bin/env bash
# Installs the Debian packages Candela needs, only those missing (idempotent). Run as root
# (or with sudo available). SPEC §16 lists why each is here.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  nlohmann-json3-dev libcli11-dev libtbb-dev libstb-dev libopenexr-dev libtinyobjloader-dev
  libeigen3-dev libfmt-dev libgtest-dev libbenchmark-dev libembree-dev libnanoflann-dev
  libopenmpi-dev openmpi-bin  # MPI: distributed rendering and radiosity (src/distributed, docs/distributed.md)
  libtinygltf-dev  # glTF 2.0 mesh import (src/io/gltf_import.cpp)
  fonts-dejavu-core  # the plots' and false-colour legends' text (src/io/text.h, through stb_truetype)
  clang-format  # .ci/run checks every C++ file against .clang-format (scripts/check-format.sh)
  # The Python module (python/) for Debian's /usr/bin/python3, and its tests (pytest):
  pybind11-dev python3-dev python3-numpy python3-pytest
  chromium  # needed by the report test (tests/report_cli_test.cpp opens the HTML report headless); Debian 12 package
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
run_as_root=()
if [ "$(id -u)" -ne 0 ]; then run_as_root=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${run_as_root[@]}" apt-get update -qq
"${run_as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
