#!/bin/bash
# The shipped scenes' table of docs/benchmarks.md: `strata bench --only traversal`
# side by side with the Embree peer (shared/peers/embree-rays, MEDIUM BVH,
# the same threads) in alternated rounds, and path tracing against a
# reference rendered here. Usage:
#   scripts/bench_shipped.sh [--strata PATH] [--embree PATH] [--out DIR]
#                            [--rounds N] [--reps R] [--size WxH] [--threads T]
#                            [--pt-size WxH] [--spp N] [--ref-spp N] [--device I]
#                            [--scene FILE]...
# --scene (repeatable) measures those files instead of the shipped scenes
# (e.g. make_bench_scene.py's); a row is named by the file's stem.
# Without --embree (or when PATH is not executable) only strata's figures are
# taken. References are rendered once into DIR (ref_<scene>.exr, kept for
# later runs of the same --pt-size and --ref-spp). Results:
# DIR/traversal_<scene>_<tool>_<round>.json, DIR/pt_<scene>_<round>.json,
# DIR/summary.md. Needs python3 (the table).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
strata="$root/build/strata"
embree=""
out=bench-shipped
rounds=3
reps=5
size=1024x768
threads=2
ptsize=128x128
spp=64
refspp=2048
device=()
files=()
while [ $# -gt 0 ]; do
    case "$1" in
        --strata) strata=$2; shift 2 ;;
        --embree) embree=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --rounds) rounds=$2; shift 2 ;;
        --reps) reps=$2; shift 2 ;;
        --size) size=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --pt-size) ptsize=$2; shift 2 ;;
        --spp) spp=$2; shift 2 ;;
        --ref-spp) refspp=$2; shift 2 ;;
        --device) device=(--device "$2"); shift 2 ;;
        --scene) files+=("$2"); shift 2 ;;
        *) echo "bench_shipped.sh: error: unknown option '$1'" >&2; exit 2 ;;
    esac
done
if [ ! -x "$strata" ]; then echo "bench_shipped.sh: error: $strata: not an executable (build first)" >&2; exit 2; fi
if [ -n "$embree" ] && [ ! -x "$embree" ]; then
    echo "bench_shipped.sh: error: $embree: not an executable (build the peer with its build.sh)" >&2
    exit 2
fi
width=${size%x*}
height=${size#*x}
ptw=${ptsize%x*}
pth=${ptsize#*x}
mkdir -p "$out"
"$strata" devices > "$out/devices.txt"
scenes=(cornell-box cornell-glass veach-mis furnace furnace-a0.8-le0.1 materials-board materials-board-env
        square-light)
declare -A path
for name in "${scenes[@]}"; do path[$name]="$root/scenes/$name.gltf"; done
if [ ${#files[@]} -gt 0 ]; then
    scenes=()
    for f in "${files[@]}"; do
        name=$(basename "${f%.*}")
        scenes+=("$name")
        path[$name]=$(cd "$(dirname "$f")" && pwd)/$(basename "$f")
    done
fi
# Render options a scene needs: the environment-lit board has no other light.
extra() {
    case "$1" in
        materials-board-env) echo "--env $root/scenes/env/sky.hdr" ;;
        *) echo "" ;;
    esac
}
for name in "${scenes[@]}"; do
    ref="$out/ref_${name}_${ptw}x${pth}_${refspp}.exr"
    if [ ! -f "$ref" ]; then
        # shellcheck disable=SC2046  # extra() gives flags and a path, no spaces inside
        "$strata" reference "${path[$name]}" --spp "$refspp" --width "$ptw" --height "$pth" \
            $(extra "$name") "${device[@]}" --quiet -o "$ref"
    fi
done
for ((r = 1; r <= rounds; ++r)); do
    for name in "${scenes[@]}"; do
        scene="${path[$name]}"
        "$strata" bench "$scene" --only traversal --reps "$reps" --width "$width" --height "$height" \
            "${device[@]}" --json "$out/traversal_${name}_strata_$r.json" > /dev/null
        if [ -n "$embree" ]; then
            "$embree" "$scene" --threads "$threads" --reps "$reps" --width "$width" --height "$height" \
                --json "$out/traversal_${name}_embree_$r.json" > /dev/null
        fi
        # shellcheck disable=SC2046
        "$strata" bench "$scene" --quick --width "$ptw" --height "$pth" --spp "$spp" $(extra "$name") \
            --reference "$out/ref_${name}_${ptw}x${pth}_${refspp}.exr" "${device[@]}" \
            --json "$out/pt_${name}_$r.json" > /dev/null
    done
done
python3 - "$out" "$refspp" "$spp" "${scenes[@]}" <<'PY' | tee "$out/summary.md"
import glob, json, os, statistics, sys
out, refspp, spp, scenes = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
print(open(os.path.join(out, "devices.txt")).read().strip())
print()
rays = ("primary", "diffuse", "occlusion")

def embree_mrays(j):
    # The peer's JSON: rays.<set>.medium.mrays_per_s.
    return {k: j["rays"][k]["medium"]["mrays_per_s"] for k in rays}

def runs(name, tool):
    return [json.load(open(f)) for f in sorted(glob.glob(os.path.join(out, "traversal_%s_%s_*.json" % (name, tool))))]

have_embree = any(runs(n, "embree") for n in scenes)
head = "| scene | triangles | strata, Mrays/s |"
if have_embree:
    head += " Embree MEDIUM, Mrays/s | ratio (per-round range) |"
head += " path tracing: Msamples/s, relMSE (%s-spp reference), efficiency |" % refspp
print(head)
print("|---" * (head.count("|") - 1) + "|")
for name in scenes:
    s = [{k: j["traversal"]["rays"][k]["mrays_per_s"] for k in rays} for j in runs(name, "strata")]
    triangles = runs(name, "strata")[0]["triangles"]
    sm = {k: statistics.median(x[k] for x in s) for k in rays}
    row = "| %s | %s | %s |" % (name, format(triangles, ","), " / ".join("%.1f" % sm[k] for k in rays))
    if have_embree:
        e = [embree_mrays(j) for j in runs(name, "embree")]
        em = {k: statistics.median(x[k] for x in e) for k in rays}
        cells = []
        for k in rays:
            per = [a[k] / b[k] for a, b in zip(s, e)]
            cells.append("%.2f (%.2f-%.2f)" % (sm[k] / em[k], min(per), max(per)))
        row += " %s | %s |" % (" / ".join("%.1f" % em[k] for k in rays), " / ".join(cells))
    p = [json.load(open(f))["path_tracing"] for f in sorted(glob.glob(os.path.join(out, "pt_%s_*.json" % name)))]
    ms = statistics.median(x["msamples_per_s"] for x in p)
    rel = statistics.median(x["relmse"] for x in p)
    eff = [x["efficiency"] for x in p if x["efficiency"] is not None]
    row += " %.2f, %.2g, %s |" % (ms, rel, "%.3g" % statistics.median(eff) if eff else "-")
    print(row)
print()
print("traversal: medians of the rounds; path tracing at %s spp, medians of the rounds" % spp)
PY
