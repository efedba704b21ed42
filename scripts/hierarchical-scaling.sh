#!/usr/bin/env bash
# Hierarchical radiosity's scaling (docs/benchmarks.md "Hierarchical radiosity"): the
# Cornell box of scenes/cornell-box.json with one mesh standing in it — UV spheres of about 10k,
# 100k and 1M triangles, the 100,000-triangle dragon and the 268,686-triangle Igea of
# ../shared/models — solved by radiosity.solver "hierarchical" through `candela bench --solve radiosity`;
# prints input triangles, links, leaves, solve seconds and peak memory per scene, then the
# exponents of links and of time against input triangles fitted by least squares on the logs.
# SIZES="10000 100000" leaves the million out; THREADS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${CANDELA:-build/cli/candela}"
work="${WORK:-/tmp/candela-hierarchical-scaling}"
models="$(cd .. && pwd)/shared/models"
mkdir -p "$work"
place() {  # place SCENE MESH TRANSFORM: the Cornell box with MESH in it
  python3 - scenes/cornell-box.json "$1" "$2" "$3" <<'PYTHON'
import sys
text = open(sys.argv[1]).read()
last = text.rindex(']')
mesh = (',\n    {"name": "mesh", "type": "mesh", "file": "%s", "material": "light-grey", "transform": %s}\n  '
        % (sys.argv[3], sys.argv[4]))
open(sys.argv[2], 'w').write(text[:last].rstrip() + mesh + text[last:])
PYTHON
}
sphere() {  # sphere N OBJ: a UV sphere of about N triangles, radius 1 about the origin
  python3 - "$1" "$2" <<'PYTHON'
import math, sys
n, path = int(sys.argv[1]), sys.argv[2]
stacks = max(3, int(round(math.sqrt(n / 4))))
slices = max(3, int(round(n / (2 * stacks))))
with open(path, 'w') as out:
    out.write('v 0 1 0\n')
    for i in range(1, stacks):
        t = math.pi * i / stacks
        for j in range(slices):
            p = 2 * math.pi * j / slices
            out.write('v %.9f %.9f %.9f\n' % (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)))
    out.write('v 0 -1 0\n')
    ring = lambda i, j: 2 + (i - 1) * slices + j % slices
    last = 2 + (stacks - 1) * slices
    for j in range(slices):
        out.write('f 1 %d %d\n' % (ring(1, j + 1), ring(1, j)))
        out.write('f %d %d %d\n' % (last, ring(stacks - 1, j), ring(stacks - 1, j + 1)))
    for i in range(1, stacks - 1):
        for j in range(slices):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
            out.write('f %d %d %d\nf %d %d %d\n' % (a, b, c, a, c, d))
PYTHON
}
scenes=()
for n in ${SIZES:-10000 100000 1000000}; do
  [ -f "$work/sphere-$n.obj" ] || sphere "$n" "$work/sphere-$n.obj"
  place "$work/sphere-$n.json" "$work/sphere-$n.obj" '[{"scale": 1.5}, {"translate": [6, 1.5, 6]}]'
  scenes+=("sphere-$n")
done
place "$work/dragon.json" "$models/dragon_100k.obj" \
  '[{"scale": 0.33}, {"rotate": {"angle": -30, "axis": [0, 1, 0]}}, {"translate": [4.6, 0, 6.6]}]'
place "$work/igea.json" "$models/igea.obj" '[{"scale": 2.5}, {"translate": [5, 2.2, 6]}]'
scenes+=(dragon igea)
for name in "${scenes[@]}"; do
  "$candela" bench --solve radiosity "$work/$name.json" --set radiosity.solver=hierarchical \
    --threads "${THREADS:-2}" --json "$work/$name.bench.json" -q > /dev/null 2> "$work/$name.log"
done
python3 - "$work" "${scenes[@]}" <<'PYTHON'
import json, math, sys
work, names = sys.argv[1], sys.argv[2:]
rows = []
print(f"{'scene':14s} {'input':>9s} {'links':>10s} {'leaves':>9s} {'clusters':>9s} {'solve s':>8s} {'peak MiB':>9s}")
for name in names:
    run = json.load(open(f"{work}/{name}.bench.json"))["radiosity"]["runs"][0]
    n = run["input_triangles"]
    rows.append((n, run["links"], run["solve_seconds"]))
    print(f"{name:14s} {n:9d} {run['links']:10d} {run['leaves']:9d} {run['clusters']:9d} "
          f"{run['solve_seconds']:8.2f} {run['peak_memory_mib']:9.0f}")
def exponent(points):
    xs = [math.log(x) for x, _ in points]; ys = [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
if len(rows) > 1:
    print(f"fitted exponent: links {exponent([(n, l) for n, l, _ in rows]):.3f}, "
          f"time {exponent([(n, t) for n, _, t in rows]):.3f}")
PYTHON
