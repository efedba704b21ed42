#!/usr/bin/env bash
# The README's gallery (the Cornell box by all six methods, with their times and errors),
# docs/validation.md's error-against-time chart and the screenshot of the HTML report — all from one
# `candela report` run, so that the pictures, the times and the chart are the same run's.
#   scripts/gallery-figures.sh            # 256×256, reference 4096 spp, path 1024 spp (~6 min, 2 cores)
#   SIZE=64 REFERENCE_SPP=256 SPP=64 MASK= scripts/gallery-figures.sh   # a quick look
# The chart leaves the lamp out (MASK, default docs/images/validation/cornell/no-lamp-mask.png, 256×256):
# its edges, a hundred times the walls, would otherwise dominate every method's error.
# Needs the build (build/cli/candela, or CANDELA=...) and, for the screenshot, chromium (installed by
# scripts/install-deps.sh for the report test). Prints the README's table.
set -euo pipefail
cd "$(dirname "$0")/.."
candela=${CANDELA:-build/cli/candela}
size=${SIZE:-256}
reference_spp=${REFERENCE_SPP:-4096}
spp=${SPP:-1024}
MASK=${MASK-docs/images/validation/cornell/no-lamp-mask.png}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$candela" report scenes/cornell-box.json --methods local,whitted,raster,radiosity,meshless,path \
  --set camera.width="$size" --set camera.height="$size" --reference-spp "$reference_spp" --spp "$spp" \
  --equal-time -o "$work/report" -q ${MASK:+--error-mask "$MASK"}

gallery=docs/images/gallery
validation=docs/images/validation
mkdir -p "$gallery" "$validation"
for image in reference local whitted raster radiosity meshless path; do
  cp "$work/report/$image.png" "$gallery/cornell-$image.png"
done
cp "$work/report/convergence.svg" "$validation/cornell-convergence.svg"
cp "$work/report/convergence.csv" "$validation/cornell-convergence.csv"
cp "$work/report/report.json" "$gallery/cornell-report.json"

if command -v chromium > /dev/null; then
  timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=5000 \
    --user-data-dir="$work/chromium-profile" --window-size=1100,1500 \
    --screenshot="$gallery/report-screenshot.png" "file://$work/report/index.html" 2> "$work/chromium.log" ||
    { cat "$work/chromium.log"; exit 1; }
else
  echo "gallery-figures: no chromium, no screenshot" >&2
fi

# The README's table: time and errors per method, from report.json.
/usr/bin/python3 - "$gallery/cornell-report.json" <<'PYTHON'
import json, sys
report = json.load(open(sys.argv[1]))
machine = report["machine"]
print(f"{report['width']}×{report['height']}, {machine['cpu']}, {machine['threads']} threads")
print("| method | time (s) | RMSE | relMSE |")
print("| --- | --- | --- | --- |")
for entry in report["methods"]:
    errors = entry["errors"]
    print(f"| {entry['label']} | {entry['seconds']:.3g} | {errors['rmse']:.3g} | {errors['relative_mse']:.3g} |")
PYTHON
