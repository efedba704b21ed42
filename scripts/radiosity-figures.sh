#!/usr/bin/env bash
# The pictures of docs/methods/radiosity.md (000 §6.8): scenes/cornell-box.json solved by
# progressive refinement with the hemicube.
#   progressive-N.png, progressive-N-ambient.png   after N = 1, 2, 20, 100 shots, without and with
#                                                  the ambient term (000 Figures 63 and 64), and
#                                                  converged.png; their unshot fractions in
#                                                  progressive.md
#   mesh-uniform.png, mesh-adaptive.png,           the element mesh without and with adaptive
#   adaptive.png                                   subdivision (000 §6.7.2, Figure 65), the adaptive
#                                                  solution in Gouraud display; counts in adaptive.md
#   leak-{flat,gouraud}.png, contacts-{flat,gouraud}.png
#                                                  radiosity.split_at_contacts false / true (the
#                                                  light leak of 000 §6.5.1 and its remedy)
#   views-{front,corner,floor}.png                 the scene's three cameras from one solution
#   display-{flat,ray-traced,elements}.png         the display modes (Gouraud: converged.png)
# Usage: scripts/radiosity-figures.sh [candela-binary] [output-directory]   (about a minute on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out="${2:-docs/images/radiosity}"
scene=scenes/cornell-box.json
mkdir -p "$out"
stats="$(mktemp -d)"
trap 'rm -rf "$stats"' EXIT

# The seed's figures show the Gouraud display (000 §6.5); the method's default is ray-traced (the
# same field), so every render asks for Gouraud unless its overrides name another display.
gouraud=(--set 'radiosity.display="gouraud"')
render() {  # render NAME [overrides...]: $out/NAME.png, statistics in $stats/NAME.json
  local name="$1"
  shift
  "$candela" render "$scene" -q "${gouraud[@]}" "$@" -o "$out/$name.png" --stats "$stats/$name.json"
  echo "wrote $out/$name.png"
}

# (a) Progressive refinement after 1, 2, 20 and 100 shots (000 §6.8, Figures 63 and 64).
for steps in 1 2 20 100; do
  render "progressive-$steps" --set radiosity.max_steps=$steps --set radiosity.ambient=false
  render "progressive-$steps-ambient" --set radiosity.max_steps=$steps --set radiosity.ambient=true
done
render converged
python3 - "$stats" "$out/progressive.md" <<'PY'
import json, sys
stats, table = sys.argv[1], sys.argv[2]
seed = {1: "100 %", 2: "45 %", 20: "34 %", 100: "21 %"}
lines = ["| shots | unshot (candela) | unshot (000 Figure 63) |", "| --- | --- | --- |"]
for steps in (1, 2, 20, 100):
    r = json.load(open(f"{stats}/progressive-{steps}.json"))["radiosity"]
    lines.append(f"| {r['steps']} | {100 * r['unshot_fraction']:.1f} % | {seed[steps]} |")
r = json.load(open(f"{stats}/converged.json"))["radiosity"]
lines.append(f"| {r['steps']} (converged) | {100 * r['unshot_fraction']:.2f} % | 0.1 % (1506 iterations) |")
open(table, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

# (b) Adaptive subdivision (000 §6.7.2, Figure 65): the uniform mesh, the adapted one, its image,
# seen from the "corner" camera (the floor and the boxes' shadows).
adaptive=(--set radiosity.subdivision_threshold=0.03 --set radiosity.min_element_size=0.25)
render mesh-uniform --camera corner --set 'radiosity.display="elements"'
render mesh-adaptive --camera corner "${adaptive[@]}" --set 'radiosity.display="elements"'
render adaptive --camera corner "${adaptive[@]}"
python3 - "$stats" "$out/adaptive.md" <<'PY'
import json, sys
stats, table = sys.argv[1], sys.argv[2]
lines = ["| mesh | patches | elements | subdivision passes | form-factor rows | form factors (MiB) | solve (s) |",
         "| --- | --- | --- | --- | --- | --- | --- |"]
for name in ("mesh-uniform", "mesh-adaptive"):
    r = json.load(open(f"{stats}/{name}.json"))["radiosity"]
    lines.append(f"| {name[5:]} | {r['patches']} | {r['elements']} | {r['subdivision_passes']} | {r['form_factor_rows']} "
                 f"| {r['form_factor_memory_mib']:.1f} | {r['solve_seconds']:.1f} |")
open(table, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

# (c) The light leak (000 §6.5.1) and the remedy: surfaces split where other objects meet them;
# from the "corner" camera, which sees both boxes' bases.
for contacts in false true; do
  name=$([ $contacts = true ] && echo contacts || echo leak)
  render "$name-flat" --camera corner --set radiosity.split_at_contacts=$contacts --set 'radiosity.display="flat"'
  render "$name-gouraud" --camera corner --set radiosity.split_at_contacts=$contacts
done

# (d) One solution, three views (the scene's "cameras").
"$candela" render "$scene" -q "${gouraud[@]}" --camera all -o "$out/views.png"
echo "wrote $out/views-{front,corner,floor}.png"

# (e) The display modes of one solution.
for display in flat ray-traced elements; do  # gouraud: converged.png
  render "display-$display" --set "radiosity.display=\"$display\""
done
