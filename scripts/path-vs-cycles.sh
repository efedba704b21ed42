#!/usr/bin/env bash
# Candela's path tracer against Blender's Cycles on the same Cornell box (docs/benchmarks.md
# "Path tracing against Cycles"). Needs Blender (Debian's `blender`, 3.4) on
# the machine running it — never a dependency of Candela or its CI — and the reference and lamp
# mask that scripts/path-efficiency.sh leaves in WORK (run it first with the same WORK and SIZE).
#
# scripts/cycles_cornell.py builds scenes/cornell-box.json in Cycles: the same quads, boxes, camera
# and albedos, Lambertian surfaces, the lamp's radiance, box filter, no denoising, no adaptive
# sampling, 64 bounces, THREADS (2) threads. Each renderer renders SPP (64) samples per pixel
# REPEATS (3) times in turn (Candela, Cycles, Candela, ...); the medians of their own render
# seconds (Candela's "render" phase, Cycles' render call: both include their scene set-up and BVH)
# are compared, with each image's MSE against the 8,192-spp Candela reference, whole and with the
# lamp masked, and efficiency 1 / (seconds × MSE). Cycles' error is also measured against its own
# CYCLES_REFERENCE_SPP (2048) reference, and the two references against each other (bias check).
#
#   scripts/path-efficiency.sh && scripts/path-vs-cycles.sh        # about 8 minutes on 2 cores
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
blender="${BLENDER:-blender}"
work="${WORK:-/tmp/candela-path-efficiency}"
size="${SIZE:-256}"
spp="${SPP:-64}"
threads="${THREADS:-2}"
repeats="${REPEATS:-3}"
cycles_reference_spp="${CYCLES_REFERENCE_SPP:-2048}"
reference="$(ls "$work"/reference-"$size"-*.pfm 2> /dev/null | head -1)"
mask="$work/walls-mask.pfm"
if [ -z "$reference" ] || [ ! -f "$mask" ]; then
  echo "path-vs-cycles.sh: no reference in $work: run WORK=$work SIZE=$size scripts/path-efficiency.sh first" >&2
  exit 2
fi
command -v "$blender" > /dev/null || { echo "path-vs-cycles.sh: no $blender (apt-get install blender)" >&2; exit 2; }

cycles() {  # spp, output: prints the render call's seconds
  "$blender" -b --factory-startup -P scripts/cycles_cornell.py -- scenes/cornell-box.json "$size" "$1" "$threads" "$2" \
    2>&1 | sed -n 's/^cycles-seconds //p'
}
candela() {  # output.pfm: prints the render phase's seconds
  "$candela" render scenes/cornell-box.json --method path --set "camera.width=$size" --set "camera.height=$size" \
    --set aa.mode=none --set aa.filter=box --set path.max_depth=64 --threads "$threads" -q --spp "$spp" \
    -o "$1" --stats "$1.json"
  python3 -c "import json; print(json.load(open('$1.json'))['phases_seconds']['render'])"
}
metrics() {  # image, reference, name
  "$candela" compare "$1" "$2" --json "$work/$3-whole.json" > /dev/null
  "$candela" compare "$1" "$2" --mask "$mask" --json "$work/$3-walls.json" > /dev/null
}

cycles_reference="$work/cycles-reference-$size-$cycles_reference_spp.exr"
[ -f "$cycles_reference" ] || cycles "$cycles_reference_spp" "$cycles_reference" > "$cycles_reference.seconds"
candela_seconds=() cycles_seconds=()
for ((i = 0; i < repeats; ++i)); do
  candela_seconds+=("$(candela "$work/candela-$spp.pfm")")
  cycles_seconds+=("$(cycles "$spp" "$work/cycles-$spp.exr")")
done
metrics "$work/candela-$spp.pfm" "$reference" candela
metrics "$work/cycles-$spp.exr" "$reference" cycles
metrics "$work/cycles-$spp.exr" "$cycles_reference" cycles-own
metrics "$cycles_reference" "$reference" references

python3 - "$work" "$spp" "$cycles_reference_spp" "$(lscpu | sed -n 's/^Model name: *//p' | head -1)" "$(nproc)" \
  "$(git rev-parse --short HEAD)" "$("$blender" --version 2> /dev/null | head -1)" \
  "${candela_seconds[*]}" "${cycles_seconds[*]}" <<'PYTHON'
import json, statistics, sys
work, spp, cycles_reference_spp, cpu, cores, commit, blender, candela_runs, cycles_runs = sys.argv[1:]
def rmse(name):
    return (json.load(open(f'{work}/{name}-whole.json'))['rmse'], json.load(open(f'{work}/{name}-walls.json'))['rmse'])
candela_seconds = statistics.median(map(float, candela_runs.split()))
cycles_seconds = statistics.median(map(float, cycles_runs.split()))
print(f'machine: {cpu}, {cores} cores; commit {commit}; {blender}')
print(f'render seconds, each run: Candela {candela_runs}; Cycles {cycles_runs}')
rows = [('Candela (sobol)', candela_seconds, rmse('candela')), ('Cycles', cycles_seconds, rmse('cycles'))]
print(f'{"renderer":16s} {"seconds":>8s} {"RMSE":>9s} {"RMSE walls":>10s}')
for name, seconds, (whole, walls) in rows:
    print(f'{name:16s} {seconds:8.2f} {whole:9.5f} {walls:10.5f}')
(cw, cl), (yw, yl) = rows[0][2], rows[1][2]
print(f'Candela / Cycles: time {candela_seconds / cycles_seconds:.3f}, MSE {cw**2 / yw**2:.3f}, '
      f'MSE walls {cl**2 / yl**2:.3f}, efficiency {(cycles_seconds * yw**2) / (candela_seconds * cw**2):.2f}, '
      f'efficiency walls {(cycles_seconds * yl**2) / (candela_seconds * cl**2):.2f}')
own = rmse('cycles-own')
bias = rmse('references')
print(f'Cycles {spp} spp against its own {cycles_reference_spp}-spp reference: RMSE {own[0]:.5f}, walls {own[1]:.5f}')
print(f'Cycles {cycles_reference_spp}-spp reference against Candela\'s: RMSE {bias[0]:.5f}, walls {bias[1]:.5f}')
PYTHON
