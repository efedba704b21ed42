#!/usr/bin/env bash
# Noise per second of the path tracer's samplers (docs/benchmarks.md "Path tracing:
# samplers"): the Cornell box of scenes/cornell-box.json at SIZE² (256), box filter, no adaptive
# sampling, with each path.sampler at SPP (64) samples per pixel and at the time the independent
# sampler took for them, against a REFERENCE_SPP (8192) Sobol' reference. Prints seconds, passes,
# RMSE and relMSE of the whole image and with the lamp masked (the lamp and the pixels beside it,
# `candela compare --mask`), MSE relative to the independent sampler's, and efficiency
# 1 / (seconds × MSE) relative to it. Render seconds are the medians of REPEATS (3) runs.
#
# BASELINE=path/to/candela (a build of an earlier commit, e.g. 28e7633, the path tracer before its
# samplers) adds its path tracer, in the same rotation, as "baseline-SPP", and Sobol' at the
# baseline's time as "sobol-baseline-time": the targets in docs/benchmarks.md are against that one.
#
#   scripts/path-efficiency.sh                 # about 20 minutes on 2 cores (the reference: most)
#   REFERENCE_SPP=2048 SIZE=128 scripts/path-efficiency.sh
#   BASELINE=/tmp/issue-time/build/cli/candela scripts/path-efficiency.sh
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
work="${WORK:-/tmp/candela-path-efficiency}"
size="${SIZE:-256}"
spp="${SPP:-64}"
reference_spp="${REFERENCE_SPP:-8192}"
threads="${THREADS:-2}"
repeats="${REPEATS:-3}"
baseline="${BASELINE:-}"
mkdir -p "$work"
common=(scenes/cornell-box.json --method path --set "camera.width=$size" --set "camera.height=$size"
        --set aa.mode=none --set aa.filter=box --set path.max_depth=64 --threads "$threads" -q)

reference="$work/reference-$size-$reference_spp.pfm"
if [ ! -f "$reference" ]; then
  "$candela" render "${common[@]}" --spp "$reference_spp" --set path.sampler=sobol --set render.seed=987654321 \
    -o "$reference"
fi
# The lamp and the pixels beside it (luminance above 6 within one pixel), left out of the masked
# metrics: its edges are half lamp, half ceiling.
python3 - "$reference" "$work/walls-mask.pfm" <<'PYTHON'
import struct, sys
data = open(sys.argv[1], 'rb').read()
parts = data.split(b'\n', 3)
width, height = map(int, parts[1].split())
scale = float(parts[2])
endian = '<' if scale < 0 else '>'
values = struct.unpack(endian + 'f' * (3 * width * height), parts[3][:12 * width * height])
bright = [0.2126 * values[3 * i] + 0.7152 * values[3 * i + 1] + 0.0722 * values[3 * i + 2] > 6
          for i in range(width * height)]
mask = []
for y in range(height):
    for x in range(width):
        near = any(bright[yy * width + xx] for yy in range(max(0, y - 1), min(height, y + 2))
                   for xx in range(max(0, x - 1), min(width, x + 2)))
        mask += [0.0 if near else 1.0] * 3
with open(sys.argv[2], 'wb') as out:
    out.write(b'PF\n%d %d\n-1.0\n' % (width, height))
    out.write(struct.pack('<' + 'f' * len(mask), *mask))
PYTHON

# Each render REPEATS (3) times, the samplers in turn (A B C A B C ...): the images are the same
# bytes each time, and the medians of the render seconds stand for the times (on a shared 2-core
# machine one render's time varies by ±10 %).
render() {  # name, then render arguments; appends the render phase's seconds to name.seconds
  local name="$1" binary="$candela"
  shift
  if [[ "$name" == baseline-* ]]; then binary="$baseline"; fi
  "$binary" render "${common[@]}" "$@" -o "$work/$name.pfm" --stats "$work/$name.json"
  python3 -c "import json; print(json.load(open('$work/$name.json'))['phases_seconds']['render'])" \
    >> "$work/$name.seconds"
}
compare() {  # name
  "$candela" compare "$work/$1.pfm" "$reference" --json "$work/$1-whole.json" > /dev/null
  "$candela" compare "$work/$1.pfm" "$reference" --mask "$work/walls-mask.pfm" --json "$work/$1-walls.json" > /dev/null
}
median() {  # name
  python3 -c "import statistics; print(statistics.median(map(float, open('$work/$1.seconds'))))"
}
rm -f "$work"/*.seconds
for ((i = 0; i < repeats; ++i)); do
  for sampler in independent stratified sobol; do render "$sampler-$spp" --spp "$spp" --set "path.sampler=$sampler"; done
  if [ -n "$baseline" ]; then render "baseline-$spp" --spp "$spp"; fi
done
# Equal time: the passes that fit in the independent sampler's median time at each sampler's
# median seconds per pass (a pass count, not --time, so that the images do not depend on timing).
budget=$(median "independent-$spp")
for ((i = 0; i < repeats; ++i)); do
  for sampler in stratified sobol; do
    passes=$(python3 -c "print(max(1, round($spp * $budget / $(median "$sampler-$spp"))))")
    render "$sampler-equal-time" --spp "$passes" --set "path.sampler=$sampler"
  done
done
names=(independent-$spp stratified-$spp sobol-$spp stratified-equal-time sobol-equal-time)
if [ -n "$baseline" ]; then
  budget=$(median "baseline-$spp")
  for ((i = 0; i < repeats; ++i)); do
    passes=$(python3 -c "print(max(1, round($spp * $budget / $(median "sobol-$spp"))))")
    render sobol-baseline-time --spp "$passes" --set path.sampler=sobol
  done
  names+=(baseline-$spp sobol-baseline-time)
fi
for name in "${names[@]}"; do compare "$name"; done

python3 - "$work" "$spp" "$(lscpu | sed -n 's/^Model name: *//p' | head -1)" "$(nproc)" \
  "$(git rev-parse --short HEAD)" "${names[@]}" <<'PYTHON'
import json, statistics, sys
work, spp, cpu, cores, commit = sys.argv[1:6]
names = sys.argv[6:]
def load(name):
    stats = json.load(open(f'{work}/{name}.json'))
    whole = json.load(open(f'{work}/{name}-whole.json'))
    walls = json.load(open(f'{work}/{name}-walls.json'))
    seconds = statistics.median(map(float, open(f'{work}/{name}.seconds')))
    return seconds, stats['path']['spp'], whole, walls
base = load(f'independent-{spp}')
print(f'machine: {cpu}, {cores} cores; commit {commit}')
print(f'{"run":26s} {"seconds":>8s} {"spp":>5s} {"RMSE":>9s} {"relMSE":>9s} {"RMSE walls":>10s} '
      f'{"MSE/ind":>8s} {"walls/ind":>9s} {"eff/ind":>8s} {"walls eff":>9s}')
for name in names:
    seconds, passes, whole, walls = load(name)
    if name.startswith('baseline'):
        base = load(name)  # the rows after it are relative to the baseline
        print('relative to the baseline:')
    mse, mse_walls = whole['rmse'] ** 2, walls['rmse'] ** 2
    base_mse, base_walls = base[2]['rmse'] ** 2, base[3]['rmse'] ** 2
    efficiency = (base[0] * base_mse) / (seconds * mse)
    efficiency_walls = (base[0] * base_walls) / (seconds * mse_walls)
    print(f'{name:26s} {seconds:8.2f} {passes:5d} {whole["rmse"]:9.5f} {whole["relative_mse"]:9.5f} '
          f'{walls["rmse"]:10.5f} {mse / base_mse:8.3f} {mse_walls / base_walls:9.3f} '
          f'{efficiency:8.2f} {efficiency_walls:9.2f}')
PYTHON
