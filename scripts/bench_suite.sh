#!/bin/bash
# The traversal comparison of docs/benchmarks.md on any device:
# generates the bench scenes, runs `strata bench --only traversal` for the
# BVH2 and both four-wide stacks, then the full `strata bench` (default
# choices) per scene, and prints one table. Usage:
#   scripts/bench_suite.sh [--strata PATH] [--out DIR] [--size WxH] [--reps R]
#                          [--rounds N] [--triangles "100000 1000000"] [--device I]
# Results: DIR/traversal_<scene>_<variant>_<round>.json, DIR/bench_<scene>.json
# and .txt, DIR/summary.txt. Needs python3 (scene generation, the table).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
strata="$here/../build/strata"
out=bench-suite
size=1024x768
reps=5
rounds=2
triangles="100000 1000000"
device=()
while [ $# -gt 0 ]; do
    case "$1" in
        --strata) strata=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --size) size=$2; shift 2 ;;
        --reps) reps=$2; shift 2 ;;
        --rounds) rounds=$2; shift 2 ;;
        --triangles) triangles=$2; shift 2 ;;
        --device) device=(--device "$2"); shift 2 ;;
        *) echo "bench_suite.sh: error: unknown option '$1'" >&2; exit 2 ;;
    esac
done
width=${size%x*}
height=${size#*x}
mkdir -p "$out"
"$strata" devices > "$out/devices.txt"
scenes=("$here/../scenes/cornell-box.gltf")
for n in $triangles; do
    python3 "$here/make_bench_scene.py" --triangles "$n" -o "$out/spheres-$n.glb" > /dev/null
    scenes+=("$out/spheres-$n.glb")
done
variants=("bvh2:--bvh 2" "registers:--bvh-stack registers" "memory:--bvh-stack memory")
for ((r = 1; r <= rounds; ++r)); do
    for scene in "${scenes[@]}"; do
        name=$(basename "$scene"); name=${name%.*}
        for v in "${variants[@]}"; do
            # shellcheck disable=SC2086  # the variant's flags are two words
            "$strata" bench "$scene" --only traversal --reps "$reps" --width "$width" --height "$height" \
                ${v#*:} "${device[@]}" --json "$out/traversal_${name}_${v%%:*}_$r.json" > /dev/null
        done
    done
done
for scene in "${scenes[@]}"; do
    name=$(basename "$scene"); name=${name%.*}
    "$strata" bench "$scene" "${device[@]}" --json "$out/bench_$name.json" > "$out/bench_$name.txt"
done
python3 - "$out" <<'PY' | tee "$out/summary.txt"
import glob, json, os, statistics, sys
out = sys.argv[1]
print(open(os.path.join(out, "devices.txt")).read().strip())
rows = {}
for f in sorted(glob.glob(os.path.join(out, "traversal_*.json"))):
    scene, variant, _ = os.path.basename(f)[len("traversal_"):-len(".json")].rsplit("_", 2)
    t = json.load(open(f))["traversal"]
    for ray, v in t["rays"].items():
        rows.setdefault((scene, variant, ray), []).append(v["mrays_per_s"])
print("traversal, Mrays/s (median of rounds), primary / diffuse / occlusion:")
for scene in sorted({k[0] for k in rows}):
    base = {ray: statistics.median(rows[(scene, "bvh2", ray)]) for ray in ("primary", "diffuse", "occlusion")}
    for variant in ("bvh2", "registers", "memory"):
        cells = []
        for ray in ("primary", "diffuse", "occlusion"):
            m = statistics.median(rows[(scene, variant, ray)])
            cells.append("%.2f (%.2fx)" % (m, m / base[ray]) if base[ray] > 0 else "%.2f" % m)
        print("  %-22s %-10s %s" % (scene, variant, " / ".join(cells)))
for f in sorted(glob.glob(os.path.join(out, "bench_*.json"))):
    p = json.load(open(f))["path_tracing"]
    print("path tracing %-22s %.3f Msamples/s, %.3f Mrays/s" %
          (os.path.basename(f)[6:-5], p["msamples_per_s"], p["mrays_per_s"]))
PY
