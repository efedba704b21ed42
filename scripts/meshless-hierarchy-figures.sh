#!/usr/bin/env bash
# The tables of docs/methods/meshless-hierarchy.md, from the Cornell box and room A:
#   1. scaling: `candela bench --solve meshless` with the hierarchical transport at about 5k, 20k and
#      80k sites (and 100k on the Cornell box), the entries' fitted exponent, time and peak memory;
#   2. accuracy at equal precomputation time: the flat and the hierarchical transport at several
#      spacings, each image's RMSE against the path-traced reference of scripts/validation-figures.sh
#      (without the lamp, its mask) beside its precomputation seconds (sites + areas + hierarchy + S).
#   3. pictures: the Cornell box's indirect light by either transport, and the relighting page of
#      the point-lit Cornell box over a light path of eight frames (with a screenshot when chromium
#      is installed).
# Writes docs/images/meshless-hierarchy/{scaling,accuracy}.csv, tables.md and the pictures. Run it
# alone on the machine (the seconds are the figures); about 4 minutes on 2 cores, after the
# validation reference.
# Usage: scripts/meshless-hierarchy-figures.sh [candela-binary]
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=docs/images/meshless-hierarchy
work="${WORK:-/tmp/candela-validation}"
mkdir -p "$out"
reference="$work/reference.exr"
mask="$work/no-lamp-mask.png"
[ -f "$reference" ] && [ -f "$mask" ] || { echo "run scripts/validation-figures.sh first (it renders $reference)" >&2; exit 1; }

# 1. Scaling. Spacings from the default's 2,626 sites on the Cornell box (Δ = 0.325): n ∝ 1/Δ².
echo "scene,spacing,sites,levels,entries,links,s_mib,sampling_s,areas_s,hierarchy_s,transfer_s,precompute_s,peak_mib" > "$out/scaling.csv"
scale() {
  local scene=$1 spacing=$2 grid=$3 angle=$4
  "$candela" bench --solve meshless "$scene" --quiet --json "$work/bench.json" --set meshless.transport=hierarchical \
    --set meshless.cluster_angle="$angle" --set meshless.spacing="$spacing" --set meshless.grid="$grid" \
    --set meshless.rounds=6 --set meshless.max_sites=400000 > /dev/null
  python3 - "$work/bench.json" "$scene" "$spacing" "$angle" >> "$out/scaling.csv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["meshless"]["runs"][0]
pre = r["sampling_seconds"] + r["area_seconds"] + r["hierarchy_seconds"] + r["transfer_seconds"]
print(f'{sys.argv[2]} (cluster_angle {sys.argv[4]}),{sys.argv[3]},{r["sites"]},{r["hierarchy_levels"]},{r["transfer_entries"]},'
      f'{r["cluster_links"]},{r["transfer_memory_mib"]:.1f},{r["sampling_seconds"]:.2f},{r["area_seconds"]:.2f},'
      f'{r["hierarchy_seconds"]:.2f},{r["transfer_seconds"]:.2f},{pre:.2f},{r["peak_memory_mib"]:.0f}')
PY
}
for angle in 0.5 0.15; do
  for spacing in 0.235 0.1177 0.0589; do scale scenes/cornell-box.json $spacing 256 $angle; done
done
scale scenes/cornell-box.json 0.0527 256 0.5
scale scenes/cornell-box.json 0.0527 256 0.15
for spacing in 1.9 0.95 0.47; do scale scenes/meshless/room-a.json $spacing 256 0.5; done

# 2. Accuracy at equal precomputation time (render.seed 1, as the validation page).
echo "transport,cluster_angle,spacing,sites,entries,precompute_s,rmse_without_lamp" > "$out/accuracy.csv"
accuracy() {
  local transport=$1 angle=$2 spacing=$3
  "$candela" render scenes/cornell-box.json --method meshless --set meshless.transport="$transport" \
    --set meshless.cluster_angle="$angle" --set meshless.spacing="$spacing" --set render.seed=1 -q \
    -o "$work/hierarchy.exr" --stats "$work/hierarchy.json"
  "$candela" compare "$work/hierarchy.exr" "$reference" --mask "$mask" --json "$work/hierarchy-compare.json" > /dev/null
  python3 - "$work" "$transport" "$angle" "$spacing" >> "$out/accuracy.csv" <<'PY'
import json, sys
work = sys.argv[1]
m = json.load(open(f"{work}/hierarchy.json"))["meshless"]
c = json.load(open(f"{work}/hierarchy-compare.json"))
pre = m["sampling_seconds"] + m["area_seconds"] + m["hierarchy_seconds"] + m["transfer_seconds"]
print(f'{sys.argv[2]},{sys.argv[3] if sys.argv[2] == "hierarchical" else "—"},{sys.argv[4]},{m["sites"]},{m["transfer_entries"]},{pre:.2f},{c["rmse"]:.5f}')
PY
}
for spacing in 0.325 0.28 0.25 0.22; do accuracy flat 0.15 $spacing; done
for spacing in 0.325 0.25 0.2 0.16 0.14; do accuracy hierarchical 0.15 $spacing; done

python3 - "$out" <<'PY'
import csv, math, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/scaling.csv")))
lines = ["| scene | Δ | sites | levels | entries | cluster links | S MiB | areas s | S s | precomputation s | peak MiB |",
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
for r in rows:
    lines.append(f'| {r["scene"]} | {r["spacing"]} | {int(r["sites"]):,} | {r["levels"]} | {int(r["entries"]):,} | {int(r["links"]):,} | '
                 f'{r["s_mib"]} | {r["areas_s"]} | {r["transfer_s"]} | {r["precompute_s"]} | {r["peak_mib"]} |')
lines.append("")
for scene in dict.fromkeys(r["scene"] for r in rows):
    mine = [r for r in rows if r["scene"] == scene]
    if len(mine) < 2: continue
    xs = [math.log(float(r["sites"])) for r in mine]; ys = [math.log(float(r["entries"])) for r in mine]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    lines.append(f"- {scene}: entries ∝ n^{slope:.2f} (least squares over {len(mine)} sizes)")
lines.append("")
acc = list(csv.DictReader(open(f"{out}/accuracy.csv")))
lines += ["| transport | cluster angle | Δ | sites | entries | precomputation s | RMSE without the lamp |",
          "| --- | --- | --- | --- | --- | --- | --- |"]
for r in acc:
    lines.append(f'| {r["transport"]} | {r["cluster_angle"]} | {r["spacing"]} | {int(r["sites"]):,} | {int(r["entries"]):,} | {r["precompute_s"]} | {r["rmse_without_lamp"]} |')
open(f"{out}/tables.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

# 3. Pictures.
for transport in flat hierarchical; do
  "$candela" render scenes/cornell-box.json --method meshless --set meshless.transport=$transport \
    --set meshless.display=indirect -q -o "$out/cornell-indirect-$transport.png"
done
python3 - "$work/light-path.json" <<'PY'
import json, math, sys
frames = []
for k in range(8):  # a lamp circling under the ceiling, then the red wall painted green (an albedo edit)
    angle = 2 * math.pi * k / 8
    frames.append({"name": f"lamp{k}", "lights": [{"type": "point", "position": [5 + 3 * math.cos(angle), 7.5, 5 + 3 * math.sin(angle)],
                                                   "intensity": [48, 48, 44], "attenuation": "inverse-square"}]})
frames.append({"name": "red-wall-painted-green", "lights": frames[0]["lights"], "materials": {"red": {"kd": [0.15, 0.7, 0.2]}}})
json.dump({"frames": frames}, open(sys.argv[1], "w"), indent=1)
PY
mkdir -p "$out/relight"
"$candela" render scenes/cornell-box-point.json --method meshless --set meshless.transport=hierarchical \
  --set camera.width=192 --set camera.height=192 --relight "$work/light-path.json" -q \
  -o "$out/relight/cornell.png" --relight-page "$out/relight/index.html"
if command -v chromium > /dev/null; then
  chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 --window-size=900,1250 \
    --screenshot="$out/relight-page.png" "file://$PWD/$out/relight/index.html#3" > /dev/null 2>&1 || true
fi
