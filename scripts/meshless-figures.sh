#!/usr/bin/env bash
# The pictures of the rooms section of docs/methods/meshless.md (seed 002 ch. 6): the
# thesis's scenes A–D (scenes/meshless/room-{a,b,c,d}.json) solved by `--method meshless`.
#   room-X-{radial,normalized,shepard}.png   the global illumination with each basis (002 Figures
#                                            6.2–6.5)
#   room-X-{direct,indirect,hybrid}.png      the normalized basis: η interpolated (Figure 6.1 /
#                                            6.3–6.5 (a)), λ − η interpolated, and the hybrid
#                                            display (direct light traced per pixel + indirect)
#   room-a-sites.png                         room A's sites drawn over its image (--show-sites)
#   rooms.md                                 per room: sites, transfer entries, density, memory,
#                                            iterations and times, from --stats
# Usage: scripts/meshless-figures.sh [candela-binary] [output-directory]   (about 3 minutes on 2
# cores, most of it the radial basis's effective areas)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/meshless}"
mkdir -p "$out"
stats="$(mktemp -d)"
trap 'rm -rf "$stats"' EXIT

render() {  # render ROOM NAME [options...]: $out/room-ROOM-NAME.png, statistics in $stats
  local room="$1" name="$2"
  shift 2
  "$candela" render "scenes/meshless/room-$room.json" -q --method meshless "$@" \
    -o "$out/room-$room-$name.png" --stats "$stats/room-$room-$name.json"
  echo "wrote $out/room-$room-$name.png"
}

for room in a b c d; do
  for basis in radial normalized shepard; do
    render "$room" "$basis" --set "meshless.basis=\"$basis\""
  done
  for display in direct indirect hybrid; do
    render "$room" "$display" --set 'meshless.basis="normalized"' --set "meshless.display=\"$display\""
  done
done
render a normalized-with-sites --set 'meshless.basis="normalized"' --show-sites "$out/room-a-sites.png"
rm -f "$out/room-a-normalized-with-sites.png"

python3 - "$stats" "$out/rooms.md" <<'PY'
import json, sys
stats, table = sys.argv[1], sys.argv[2]
lines = ["| room | basis | sites | transfer entries | density | memory (MiB) | iterations | areas (s) | transfer (s) | total (s) |",
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
bad = []
for room in "abcd":
    for basis in ("radial", "normalized", "shepard"):
        s = json.load(open(f"{stats}/room-{room}-{basis}.json"))
        m = s["meshless"]
        if not m["converged"] or m["iterations"] >= 1000:
            bad.append(f"room {room} {basis}: not converged after {m['iterations']} iterations")
        lines.append(f"| {room.upper()} | {basis} | {m['sites']:,} | {m['transfer_entries']:,} | {m['transfer_density']:.2f} | "
                     f"{m['transfer_memory_mib']:.1f} | {m['iterations']} | {m['area_seconds']:.1f} | {m['transfer_seconds']:.2f} | "
                     f"{s['total_seconds']:.1f} |")
open(table, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
for b in bad:
    print("WARNING:", b, file=sys.stderr)
PY
