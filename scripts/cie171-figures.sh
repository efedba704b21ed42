#!/usr/bin/env bash
# The figures and table of docs/validation/cie171.md (issue 23, item 5): `candela validate cie171`
# in full into docs/images/validation/cie171/ (cie171.csv, summary.csv, results.json, each case's
# scene, points and plot), then table.md — the pass/fail table the page quotes — from summary.csv.
# Usage: scripts/cie171-figures.sh [candela-binary]   (about 10 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=docs/images/validation/cie171
mkdir -p "$out"
status=0
"$candela" validate cie171 --out "$out" || status=$?
[ "$status" -le 1 ] || exit "$status"  # 1: a method out of its tolerance somewhere (the table says where)
python3 - "$out" <<'PY'
import csv, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/summary.csv")))
methods = ["local", "path", "radiosity", "meshless"]
cases = []
for r in rows:
    if r["case"] not in cases: cases.append(r["case"])
lines = ["| case | what | compared | " + " | ".join(methods) + " |",
         "| --- | --- | --- | " + " | ".join("---" for _ in methods) + " |"]
for case in cases:
    mine = {r["method"]: r for r in rows if r["case"] == case}
    first = next(iter(mine.values()))
    cells = []
    for m in methods:
        if m not in mine:
            cells.append("—")
            continue
        r = mine[m]
        verdict = "pass" if r["passed"] == "pass" else "**FAIL**"
        cells.append(f"{100 * float(r['largest_relative_error']):.2f} % {verdict}")
    lines.append(f"| {case} | {first['title']} | {first['compared']} | " + " | ".join(cells) + " |")
open(f"{out}/table.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
