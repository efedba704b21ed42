#!/usr/bin/env python3
"""Prints Markdown tables from the docs/bench/*.json files that scripts/run-benchmarks.sh writes:
Mrays/s per accelerator, set and thread count, the ratio to Embree, builds and memory."""
import json
import pathlib
import sys

SETS = ["primary", "incoherent", "shadow", "incoherent_occlusion"]

def table(path):
    data = json.loads(path.read_text())
    results = data["results"]
    accels = list(dict.fromkeys(r["accel"] for r in results))
    threads = sorted({r["threads"] for r in results})
    reference = "embree" if "embree" in accels else ("list" if "list" in accels else None)
    out = [f"### {path.stem}: {data['mesh']} ({data['triangles']:,} {'primitives' if data['mesh'].endswith('.json') else 'triangles'})", ""]
    header = "| accel | threads | " + " | ".join(SETS) + " |"
    out += [header, "|" + " --- |" * (len(SETS) + 2)]
    lookup = {(r["accel"], r["set"], r["threads"]): r for r in results}
    for t in threads:
        for a in accels:
            cells = []
            for s in SETS:
                r = lookup.get((a, s, t))
                if not r:
                    cells.append("-")
                    continue
                cell = f"{r['mrays_per_s']:.3g}"
                ref = lookup.get((reference, s, t)) if reference else None
                if ref and a != reference and ref["mrays_per_s"] > 0:
                    ratio = r["mrays_per_s"] / ref["mrays_per_s"]
                    cell += f" ({ratio:.0%})" if reference == "embree" else f" (×{ratio:,.0f})"
                cells.append(cell)
            out.append(f"| {a} | {t} | " + " | ".join(cells) + " |")
    out += ["", "| accel | threads | build s | MiB |", "| --- | --- | --- | --- |"]
    for b in data["builds"]:
        out.append(f"| {b['accel']} | {b['threads']} | {b['seconds']:.3f} | {b['bytes'] / 2**20:.1f} |")
    # Checksums agree across accelerators (the contract); show the first accelerator's.
    out += ["", "Checksums (hits / sum_t / sum_prim) per set, first accelerator: " + "; ".join(
        f"{s}: {lookup[(accels[0], s, threads[0])]['hits']} / {lookup[(accels[0], s, threads[0])]['sum_t']:.10g} / "
        f"{lookup[(accels[0], s, threads[0])]['sum_prim']}" for s in SETS if (accels[0], s, threads[0]) in lookup), ""]
    return "\n".join(out)

def main(directory="docs/bench"):
    for path in sorted(pathlib.Path(directory).glob("*.json")):
        if "results" not in json.loads(path.read_text()):
            continue  # the rasterizer's, radiosity's and meshless runs have their own sections
        print(table(path))
        print()

if __name__ == "__main__":
    main(*sys.argv[1:])
