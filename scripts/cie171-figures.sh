#!/usr/bin/env bash
# The figures and table of docs/validation/cie171.md: `candela validate cie171`
# in full into docs/images/validation/cie171/ (cie171.csv, summary.csv, results.json, each case's
# scene, points and plot), then table.md — the pass/fail table the page quotes — from summary.csv.
# Usage: scripts/cie171-figures.sh [candela-binary]   (about 40 minutes on 2 cores)
#        CASES=5.12,5.13 scripts/cie171-figures.sh      (those cases again, merged into the rest:
#                                                         their rows of the CSVs and results.json
#                                                         replaced, their plots and files rewritten)
set -euo pipefail
cd "$(dirname "$0")/.."
candela="${1:-build/cli/candela}"
out=docs/images/validation/cie171
mkdir -p "$out"
status=0
if [ -n "${CASES:-}" ]; then
  partial=$(mktemp -d)
  trap 'rm -rf "$partial"' EXIT
  "$candela" validate cie171 --cases "$CASES" --out "$partial" || status=$?
  [ "$status" -le 1 ] || exit "$status"
  python3 - "$out" "$partial" <<'PY'
import csv, io, json, shutil, sys
from pathlib import Path
out, partial = Path(sys.argv[1]), Path(sys.argv[2])
def merge_csv(name):
    old = list(csv.reader(open(out / name)))
    new = list(csv.reader(open(partial / name)))
    rerun = {row[0] for row in new[1:]}
    rows, placed = [old[0]], False
    for row in old[1:]:
        if row[0] in rerun:
            if not placed:
                rows += new[1:]
                placed = True
            continue
        rows.append(row)
    if not placed:
        rows += new[1:]
    text = io.StringIO()
    csv.writer(text, lineterminator="\n").writerows(rows)
    (out / name).write_text(text.getvalue())
merge_csv("summary.csv")
merge_csv("cie171.csv")
results = json.load(open(out / "results.json"))
results["cases"].update(json.load(open(partial / "results.json"))["cases"])
results["failures"] = sum(not m["passed"] for case in results["cases"].values()
                          for m in case["methods"].values())
(out / "results.json").write_text(json.dumps(results, indent=2) + "\n")
for f in partial.iterdir():
    if f.name not in ("summary.csv", "cie171.csv", "results.json"):
        shutil.copy(f, out / f.name)
PY
else
  "$candela" validate cie171 --out "$out" || status=$?
  [ "$status" -le 1 ] || exit "$status"  # 1: a method out of its tolerance somewhere (the table says where)
fi
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
