#!/usr/bin/env bash
# The figures and tables of docs/validation/form-factors.md: `candela validate
# form-factors` into docs/images/validation/form-factors/ (form_factors.csv, furnace.csv,
# results.json, convergence_flat.png, convergence_curved.png), then tables.md — the Markdown
# tables the page quotes — from the CSVs.
# Usage: scripts/form-factor-figures.sh [candela-binary]   (about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=docs/images/validation/form-factors
mkdir -p "$out"
"$candela" validate form-factors --out "$out"
python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/form_factors.csv")))
results = json.load(open(f"{out}/results.json"))
levels = max(int(r["level"]) for r in rows) + 1
lines = ["| case | Howell | F (closed form) | method | " + " | ".join(f"level {l}" for l in range(levels)) + " | order |",
         "| --- | --- | --- | --- | " + " | ".join("---" for _ in range(levels)) + " | --- |"]
cases = []
for r in rows:
    if r["case"] not in cases: cases.append(r["case"])
for case in cases:
    for method in ("hemicube", "ray-cast"):
        mine = [r for r in rows if r["case"] == case and r["method"] == method]
        errors = [f"{100 * float(r['relative_error']):+.3f} %" for r in mine] + ["—"] * (levels - len(mine))
        order = results["order"][case][method]
        order = "—" if order is None else f"{order:.1f}"
        lines.append(f"| {case} | {mine[0]['catalogue'] or '—'} | {float(mine[0]['expected']):.6f} | {method} | {' | '.join(errors)} | {order} |")
furnace = list(csv.DictReader(open(f"{out}/furnace.csv")))
lines += ["", "| method | ρ | E/(1 − ρ) | image mean | mean error | largest pixel error | seconds |",
          "| --- | --- | --- | --- | --- | --- | --- |"]
for f in furnace:
    lines.append(f"| {f['method']} | {f['albedo']} | {float(f['expected']):.3f} | {float(f['mean']):.4f} | "
                 f"{100 * float(f['mean_relative_error']):+.3f} % | {100 * float(f['largest_pixel_error']):.2f} % | {float(f['seconds']):.1f} |")
open(f"{out}/tables.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
