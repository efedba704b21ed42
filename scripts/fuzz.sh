#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) with clang + ASan/UBSan and runs each for a fixed
# budget. Not part of the default CI: run it by hand or on a schedule.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 60 s, every target)
#
# The seed corpus fuzz/corpus/<target>/ is only read; new inputs go to a scratch folder
# (build-fuzz/corpus-scratch/<target>/, outside git). A crash, sanitizer report, hang
# (-timeout=10) or out-of-memory (-rss_limit_mb=2048) leaves its input under
# build-fuzz/artifacts/<target>/ and makes the script exit 1.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
build="${CANDELA_FUZZ_BUILD_DIR:-$root/build-fuzz}"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scene_loader_fuzzer obj_fuzzer image_fuzzer ply_fuzzer gltf_fuzzer gltf_scene_fuzzer ies_fuzzer eulumdat_fuzzer pbrt_fuzzer)
fi
# Only the harnesses that exist in this checkout.
present=()
for target in "${targets[@]}"; do
  if [ -f "$root/fuzz/$target.cpp" ]; then present+=("$target"); fi
done
targets=("${present[@]}")

generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DCANDELA_FUZZ=ON -DCANDELA_BUILD_TESTS=OFF -DCANDELA_EMBREE=OFF
cmake --build "$build" --target "${targets[@]}" -j "${CANDELA_FUZZ_JOBS:-2}"

failed=()
for target in "${targets[@]}"; do
  artifacts="$build/artifacts/$target"
  scratch="$build/corpus-scratch/$target"
  mkdir -p "$artifacts" "$scratch"
  dictionary=()
  if [ -f "$root/fuzz/$target.dict" ]; then dictionary=(-dict="$root/fuzz/$target.dict"); fi
  echo "fuzz.sh: $target for ${seconds}s"
  # The scratch corpus comes first: libFuzzer writes new inputs to the first folder only.
  if ! "$build/fuzz/$target" "$scratch" "$root/fuzz/corpus/$target" "${dictionary[@]}" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$artifacts/" -print_final_stats=1 2>&1 | tee "$build/$target.log" | tail -n 20; then
    failed+=("$target")
  elif ls "$artifacts" | grep -q .; then
    failed+=("$target")
  fi
done

if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]} (inputs under $build/artifacts/)" >&2
  exit 1
fi
echo "fuzz.sh: no findings in ${targets[*]}"
