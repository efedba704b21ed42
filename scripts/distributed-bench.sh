#!/usr/bin/env bash
# Measures distributed rendering on this machine (docs/distributed.md): each workload in one
# process with 1 and all threads, and with `mpirun -np 2` (one thread a rank, and all threads a
# rank), checks that every image is byte-identical to the single-process one, and prints the
# times, speed-ups and what crossed between the ranks (rank 0's --stats "distributed" facts).
# Usage: scripts/distributed-bench.sh [BUILD_DIR]   (needs python3 and an MPI build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
candela="$PWD/$build/cli/candela"
scenes="$PWD/scenes"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$work"

workloads=(
  "path|$scenes/cornell-box.json --method path --spp 128 --set camera.width=256 --set camera.height=256"
  "whitted|$scenes/sphere-field-10584.json --method whitted --set camera.width=1024 --set camera.height=1024 --set aa.mode=jittered --set aa.n=3"
  "radiosity|$scenes/cornell-box.json --method radiosity --set radiosity.patch_size=1.2 --set radiosity.element_size=0.6"
  "meshless|$scenes/cornell-box.json --method meshless --set meshless.spacing=0.2"
)
runs=(
  "alone-1t||--threads 1"
  "alone-2t||"
  "mpi2-1t|mpirun -np 2|--threads 1"
  "mpi2-2t|mpirun -np 2 --bind-to none|"
)

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; commit $(git -C "$OLDPWD" rev-parse --short HEAD)"
for workload in "${workloads[@]}"; do
  name="${workload%%|*}"
  arguments="${workload#*|}"
  for run in "${runs[@]}"; do
    label="${run%%|*}"; rest="${run#*|}"; launcher="${rest%%|*}"; options="${rest#*|}"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    $launcher "$candela" render $arguments $options -q -o "$name-$label.pfm" --stats "$name-$label.json"
    end=$(date +%s.%N)
    echo "$name $label $(echo "$end - $start" | bc)" >> times.txt
    cmp -s "$name-$label.pfm" "$name-alone-1t.pfm" || { echo "$name $label: image differs from one process" >&2; exit 1; }
  done
done

python3 - <<'PY'
import json
times = {}
for line in open("times.txt"):
    name, label, seconds = line.split()
    times[(name, label)] = float(seconds)
names = sorted({n for n, _ in times}, key=["path", "whitted", "radiosity", "meshless"].index)
print("| workload | 1 process, 1 thread | 2 ranks × 1 thread | speed-up | 1 process, 2 threads | 2 ranks × 2 threads | rank 0 sent / received | collectives |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for n in names:
    stats = json.load(open(f"{n}-mpi2-1t.json"))
    d = stats.get("distributed", {})
    a, b = times[(n, "alone-1t")], times[(n, "mpi2-1t")]
    print(f"| {n} | {a:.2f} s | {b:.2f} s | {a / b:.2f} | {times[(n, 'alone-2t')]:.2f} s | {times[(n, 'mpi2-2t')]:.2f} s | "
          f"{d.get('rank0_bytes_sent', 0) / 1e6:.2f} / {d.get('rank0_bytes_received', 0) / 1e6:.2f} MB "
          f"({d.get('rank0_messages_sent', 0)} / {d.get('rank0_messages_received', 0)} messages) | "
          f"{d.get('collectives', 0)}, {d.get('collective_bytes', 0) / 1e6:.2f} MB |")
    if n in ("radiosity", "meshless"):
        facts = stats[n]
        keys = ["patches", "elements", "form_factor_seconds", "solve_seconds", "sites", "transfer_entries", "transfer_seconds", "area_seconds"]
        alone = json.load(open(f"{n}-alone-1t.json"))[n]
        print("  " + n + ": " + ", ".join(f"{k} {facts[k]} (alone {alone[k]})" for k in keys if k in facts))
    print(f"  {n}: tiles by rank {d.get('tiles_by_rank')}, rounds {d.get('rounds', '-')}, rank 0 waiting {d.get('rank0_waiting_seconds', 0):.3f} s")
PY
