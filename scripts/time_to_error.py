#!/usr/bin/env python3
"""Time to error, strata against Blender Cycles (issue 43); Python 3 stdlib only.

    scripts/time_to_error.py SCENE [SCENE ...] [--width 128] [--height 128]
        [--spp 4,16,64,256] [--rounds 3] [--ref-spp 4096] [--threads 2]
        [--max-depth 16] [--strata build/strata] [--strata-arg='ARGS' ...]
        [--cycles-arg='ARGS' ...] [--adaptive [--noise-threshold 0.01]]
        [--strata-reference] [--reference cycles|strata|own] [--two-sided-emission]
        [--time render|sampling|wall]
        [--out DIR] [--ref-cache DIR] [--json FILE] [--blender blender]
        [--cycles-peer ../shared/peers/cycles/cycles_render.py]

For each scene it renders, in alternated rounds (strata, Cycles, strata,
Cycles, ...; the order flips every round), each --spp with both renderers on
the same size, pixel filter (1-pixel box), path depth and threads, and takes
relMSE (`strata compare`) against one common reference. It prints a markdown
table per scene (medians over the rounds) and the time each renderer needs to
reach a few relMSE levels both reach (log-log interpolation of relMSE against
time): Cycles' time over strata's. With --adaptive, Cycles also runs with
adaptive sampling (--noise-threshold, Cycles' default 0.01; --spp is then
its cap), and strata too if its `render --help` offers --noise-threshold.

Matching (../shared/peers/cycles/README.md says what differs):
  - strata --max-depth D  <->  Cycles --max-bounces D - 1;
  - strata --filter box (radius 0.5)  <->  Cycles --filter box --filter-width 1;
  - threads: lavapipe's LP_NUM_THREADS=T  <->  Cycles --threads T;
  - Cycles --material lambert (the default): the same BRDF as strata's only
    for Lambert scenes (KHR_materials_specular factor 0, metallic 0);
  - emission: Cycles' is two-sided; use closed emitters, lamps with nothing
    behind them, or doubleSided emitters (scenes/many-lights.gltf), or give
    --two-sided-emission, which renders a copy of the scene whose emissive
    materials are doubleSided (the Cornell box's lamp, 0.02 below the
    ceiling, makes Cycles' image 21% brighter than strata's without it).
  - seeds: round r uses seed r + 1 in both; the references use seed 1000003.
  - --strata-arg='--light-sampler power' (say) passes flags to strata render
    and reference alone; --cycles-arg to the peer.

Times (both are kept; --time picks the one the ratios use):
  - render (default): strata's `--stats-json` render.seconds (the render
    loop: submissions and read-back, after load, BVH, upload and pipelines)
    against Cycles' PEER_RESULT render_s (the bpy render call after the
    import: Cycles' scene sync and Embree BVH build, the sampling and the
    EXR write). Cycles' part before its first sample ("sync_s", from its
    log) is reported too, so the difference can be judged.
  - sampling: strata's render.seconds against Cycles' render_s less that
    sync (Cycles' log has 0.01 s steps): the sampling alone on both sides.
  - wall: the whole process of each (strata render; blender with start-up
    and import), measured here.

With --reference own each renderer's relMSE is against its own reference
(strata's and Cycles', both at --ref-spp): the time each takes to its own
converged image. That is the fair race where the two BRDFs differ (a
glTF metal against Cycles' Principled conductor, --material lambert keeping
metals as Principled), and it still counts either renderer's bias against
its own answer as error only where that bias fades with spp.

The reference (default: Cycles at --ref-spp) is cached in --ref-cache keyed
by the scene's bytes, size, depth, spp and renderer, and reused. With
--strata-reference a strata reference (`strata reference`, same spp) is made
too, and the relMSE between the two references is printed: with unbiased,
matching estimators it is the two references' noise alone.

Needs Blender for the peer (not in scripts/debian-packages.txt, which is
for `make test`):
    apt-get install -y --no-install-recommends blender python3-numpy
(Debian 12: Blender 3.4.1). One render process runs at a time.
"""

import argparse
import hashlib
import json
import math
import os
import re
import shlex
import shutil
import statistics
import struct
import subprocess
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
REF_SEED = 1000003
TIME_KEYS = {"render": "render_s", "sampling": "sampling_s", "wall": "wall_s"}


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="time_to_error.py", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+", metavar="SCENE")
    ap.add_argument("--width", type=int, default=128)
    ap.add_argument("--height", type=int, default=128)
    ap.add_argument("--spp", default="4,16,64,256", help="comma-separated spp list")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-depth", type=int, default=16,
                    help="strata's --max-depth D; Cycles gets --max-bounces D-1")
    ap.add_argument("--strata", default=os.path.join(ROOT, "build", "strata"))
    ap.add_argument("--strata-arg", action="append", default=[], metavar="ARGS",
                    help="more arguments for strata render and reference, split as a shell "
                         "would: --strata-arg='--light-sampler power' (repeatable)")
    ap.add_argument("--cycles-arg", action="append", default=[], metavar="ARGS",
                    help="more arguments for the Cycles peer, as --strata-arg")
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--cycles-peer",
                    default=os.path.join(ROOT, "..", "shared", "peers", "cycles", "cycles_render.py"))
    ap.add_argument("--adaptive", action="store_true",
                    help="also run Cycles with adaptive sampling (and strata if it has it)")
    ap.add_argument("--noise-threshold", type=float, default=0.01,
                    help="Cycles' adaptive threshold (its default 0.01)")
    ap.add_argument("--strata-noise-threshold", type=float, default=None,
                    help="strata's (default: --noise-threshold); strata's is another measure: the "
                         "standard error over sqrt(I^2 + 0.01), the root of a pixel's relMSE term")
    ap.add_argument("--reference", choices=["cycles", "strata", "own"], default="cycles",
                    help="the renderer of the common reference (default cycles); own: each "
                         "renderer against its own reference")
    ap.add_argument("--strata-reference", action="store_true",
                    help="also render a strata reference and print its relMSE to Cycles'")
    ap.add_argument("--two-sided-emission", action="store_true",
                    help="render a copy of each .gltf whose emissive materials are doubleSided, "
                         "so that strata emits from both sides as Cycles does")
    ap.add_argument("--time", choices=["render", "sampling", "wall"], default="render",
                    help="the times the ratios use (default render)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "time-to-error"))
    ap.add_argument("--ref-cache", default=None, help="default: OUT/refs")
    ap.add_argument("--json", default=None, help="default: OUT/time_to_error.json")
    ap.add_argument("--keep-images", action="store_true", help="keep every round's EXR")
    a = ap.parse_args(argv)
    a.spp = sorted({int(s) for s in a.spp.split(",") if s.strip()})
    if not a.spp or min(a.spp) < 1:
        ap.error("--spp needs positive integers")
    if a.max_depth < 1:
        ap.error("--max-depth must be at least 1 (Cycles' bounces are D - 1)")
    if a.rounds < 1:
        ap.error("--rounds must be at least 1")
    a.strata_arg = [x for arg in a.strata_arg for x in shlex.split(arg)]
    a.cycles_arg = [x for arg in a.cycles_arg for x in shlex.split(arg)]
    a.ref_cache = a.ref_cache or os.path.join(a.out, "refs")
    a.json = a.json or os.path.join(a.out, "time_to_error.json")
    return a


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd, env=None):
    """Runs cmd (one process at a time); returns (wall seconds, stdout+stderr)."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit("command failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-4000:]))
    return wall, p.stdout


class Renderers:
    def __init__(self, a):
        self.a = a
        self.env = dict(os.environ, LP_NUM_THREADS=str(a.threads))
        help_text = subprocess.run([a.strata, "render", "--help"], stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, text=True).stdout
        self.strata_adaptive = "--noise-threshold" in help_text
        self.strata_id = file_key(a.strata)  # the binary changes under a running project
        # Blender's embedded Python takes its prefix from the first python3 on PATH: a
        # pyenv or virtualenv python3 there hides Debian's numpy from it, so Blender's
        # own folder (/usr/bin) goes first.
        blender = shutil.which(a.blender)
        self.blender_env = dict(os.environ, PATH=os.path.dirname(os.path.realpath(blender)) +
                                os.pathsep + os.environ.get("PATH", ""))
        self.blender_version = subprocess.run([blender, "--version"], stdout=subprocess.PIPE,
                                              stderr=subprocess.DEVNULL, text=True,
                                              env=self.blender_env).stdout.splitlines()[0].strip()

    def strata_common(self, scene):
        a = self.a
        return [scene, "--width", str(a.width), "--height", str(a.height),
                "--max-depth", str(a.max_depth), "--filter", "box"] + a.strata_arg

    def strata(self, scene, spp, seed, out, noise_threshold=0.0, reference=False):
        stats = out[:-4] + ".stats.json"
        cmd = [self.a.strata, "reference" if reference else "render"] + self.strata_common(scene)
        cmd += ["--spp", str(spp), "--seed", str(seed), "-o", out, "--stats-json", stats, "--quiet"]
        if noise_threshold > 0:
            cmd += ["--noise-threshold", str(noise_threshold)]
        wall, _ = run(cmd, self.env)
        with open(stats) as f:
            r = json.load(f)["render"]
        os.remove(stats)
        return {"wall_s": wall, "render_s": r["seconds"], "sampling_s": r["seconds"],
                "device_s": r.get("device_seconds"), "spp_done": r.get("spp")}

    def cycles(self, scene, spp, seed, out, noise_threshold=0.0):
        a = self.a
        cmd = [a.blender, "-b", "--factory-startup", "--python", a.cycles_peer, "--", scene,
               "--out", out, "--spp", str(spp), "--width", str(a.width), "--height", str(a.height),
               "--threads", str(a.threads), "--filter", "box", "--filter-width", "1",
               "--max-bounces", str(a.max_depth - 1), "--seed", str(seed)] + a.cycles_arg
        if noise_threshold > 0:
            cmd += ["--noise-threshold", str(noise_threshold)]
        wall, text = run(cmd, self.blender_env)
        m = re.search(r"^PEER_RESULT .*\brender_s=([0-9.]+) import_s=([0-9.]+)", text, re.M)
        if not m:
            sys.exit("no PEER_RESULT line from the Cycles peer:\n" + text[-4000:])
        # Cycles' log: "Fra:1 ... | Time:00:00.06 | ... | Sample 0/N" marks the first sample.
        sync = None
        for line in text.splitlines():
            t = re.search(r"\| Time:(\d+):(\d+\.\d+) \|.*\| Sample 0/", line)
            if t:
                sync = int(t.group(1)) * 60 + float(t.group(2))
                break
        render = float(m.group(1))
        return {"wall_s": wall, "render_s": render, "import_s": float(m.group(2)),
                "sync_s": sync, "sampling_s": None if sync is None else max(render - sync, 1e-3)}


def compare(strata, image, ref, scratch):
    js = scratch + ".cmp.json"
    run([strata, "compare", image, ref, "--json", js])
    with open(js) as f:
        d = json.load(f)
    os.remove(js)
    return d["relmse"]


def file_key(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()[:12]


def reference(a, rnd, scene, renderer):
    """The cached reference EXR of `renderer` for this scene and settings."""
    os.makedirs(a.ref_cache, exist_ok=True)
    stem = os.path.splitext(os.path.basename(scene))[0]
    # The renderer's identity and extra arguments: a rebuilt strata, another
    # Blender or peer script makes another reference.
    ident = ([rnd.strata_id] + a.strata_arg if renderer == "strata" else
             [rnd.blender_version, file_key(a.cycles_peer)] + a.cycles_arg)
    extra = hashlib.sha256("\0".join(ident).encode()).hexdigest()[:8]
    name = "%s-%s-%dx%d-d%d-%s%d-%s" % (stem, file_key(scene), a.width, a.height, a.max_depth,
                                        renderer, a.ref_spp, extra)
    exr = os.path.join(a.ref_cache, name + ".exr")
    meta = os.path.join(a.ref_cache, name + ".json")
    if os.path.exists(exr) and os.path.exists(meta):
        with open(meta) as f:
            info = json.load(f)
        log("reference %s (cached): %s" % (renderer, exr))
        return exr, info
    log("reference %s: %s at %d spp ..." % (renderer, stem, a.ref_spp))
    tmp = exr[:-4] + ".tmp.exr"
    if renderer == "cycles":
        times = rnd.cycles(scene, a.ref_spp, REF_SEED, tmp)
        version = rnd.blender_version + " Cycles"
    else:
        times = rnd.strata(scene, a.ref_spp, REF_SEED, tmp, reference=True)
        version = "strata %s (sha256 %s)" % (a.strata, rnd.strata_id)
    os.replace(tmp, exr)
    info = {"renderer": renderer, "version": version, "scene": scene, "spp": a.ref_spp,
            "seed": REF_SEED, "width": a.width, "height": a.height, "max_depth": a.max_depth,
            "args": a.strata_arg if renderer == "strata" else a.cycles_arg, "times": times}
    with open(meta, "w") as f:
        json.dump(info, f, indent=1)
    return exr, info


def read_exr(path):
    """A scanline OpenEXR file's channels: (width, height, {name: [floats]}).
    Reads what the two renderers write: no compression (Cycles) or ZIP/ZIPS
    (strata), HALF or FLOAT channels, one part."""
    with open(path, "rb") as f:
        b = f.read()
    if struct.unpack_from("<I", b)[0] != 20000630 or b[5] & 0x1a:  # tiled, deep or multi-part
        raise ValueError("%s: not a single-part scanline OpenEXR file" % path)
    i, attrs = 8, {}
    while b[i] != 0:
        j = b.index(b"\0", i)
        name = b[i:j].decode()
        k = b.index(b"\0", j + 1)
        size = struct.unpack_from("<i", b, k + 1)[0]
        attrs[name] = b[k + 5:k + 5 + size]
        i = k + 5 + size
    i += 1
    chans, k, raw = [], 0, attrs["channels"]
    while raw[k] != 0:
        e = raw.index(b"\0", k)
        chans.append((raw[k:e].decode(), struct.unpack_from("<i", raw, e + 1)[0]))
        k = e + 17
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    comp = attrs["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}.get(comp)
    if lines is None:
        raise ValueError("%s: compression %d is not read here" % (path, comp))
    sizes = {0: 4, 1: 2, 2: 4}
    formats = {0: "I", 1: "e", 2: "f"}
    out = {n: [] for n, _ in chans}
    blocks = (h + lines - 1) // lines
    for n in range(blocks):
        off = struct.unpack_from("<Q", b, i + 8 * n)[0]
        y, size = struct.unpack_from("<ii", b, off)
        data = b[off + 8:off + 8 + size]
        rows = min(lines, y1 + 1 - y)
        expect = rows * w * sum(sizes[t] for _, t in chans)
        if comp != 0 and size < expect:
            t = bytearray(zlib.decompress(data))
            for m in range(1, len(t)):
                t[m] = (t[m - 1] + t[m] - 128) & 0xff
            half = (len(t) + 1) // 2
            data = bytearray(len(t))
            data[0::2], data[1::2] = t[:half], t[half:]
        pos = 0
        for _ in range(rows):
            for name, typ in chans:
                out[name] += struct.unpack_from("<%d%s" % (w, formats[typ]), data, pos)
                pos += w * sizes[typ]
    return w, h, out


def reference_means(strata_ref, cycles_ref):
    """Each reference's mean R, G, B, and the standard error of strata's mean
    from its variance channels (the variance of each pixel's mean)."""
    _, _, s = read_exr(strata_ref)
    _, _, c = read_exr(cycles_ref)
    res = {"strata": [], "cycles": [], "strata_se": [], "noise_relmse": None}
    noise = 0.0
    for ch in "RGB":
        n = len(s[ch])
        res["strata"].append(sum(s[ch]) / n)
        res["cycles"].append(sum(c[ch]) / n)
        var = s.get("variance." + ch)
        res["strata_se"].append(math.sqrt(sum(var)) / n if var else None)
        if var and noise is not None:
            # relMSE's expectation from the two references' noise alone, if Cycles'
            # pixel variances equal strata's: sum 2 var / (r^2 + 0.01), r Cycles'.
            noise += sum(2 * v / (r * r + 0.01) for v, r in zip(var, c[ch]))
        else:
            noise = None
    if noise is not None:
        res["noise_relmse"] = noise / (3 * len(s["R"]))
    return res


def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def loglog_time(points, level):
    """Time at relMSE `level` on the curve of (time, relMSE) points in spp
    order, by linear interpolation of log time against log relMSE; the first
    crossing; None if the curve never reaches `level`."""
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        lo, hi = min(e0, e1), max(e0, e1)
        if lo <= level <= hi and e0 != e1:
            f = (math.log(level) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    for t, e in points:
        if e == level:
            return t
    return None


def levels_both_reach(p, q, count=4):
    """A few relMSE levels, log-spaced, inside the range both curves span."""
    hi = min(max(e for _, e in p), max(e for _, e in q))
    lo = max(min(e for _, e in p), min(e for _, e in q))
    if lo > hi:
        return []
    if count == 1 or hi == lo:
        return [hi]
    return [math.exp(math.log(hi) + i / (count - 1) * (math.log(lo) - math.log(hi)))
            for i in range(count)]


def fmt(x, spec=".3g"):
    return "-" if x is None else format(x, spec)


def two_sided_copy(scene, folder):
    """A copy of a .gltf (buffers and images as data URIs) whose emissive
    materials are doubleSided; returns its path and how many were changed."""
    if not scene.endswith(".gltf"):
        sys.exit("--two-sided-emission needs a .gltf file: %s" % scene)
    with open(scene, encoding="utf-8") as f:
        doc = json.load(f)
    for item in doc.get("buffers", []) + doc.get("images", []):
        if "uri" in item and not item["uri"].startswith("data:"):
            sys.exit("--two-sided-emission: %s names external files" % scene)
    changed = 0
    for m in doc.get("materials", []):
        if any(m.get("emissiveFactor", [0, 0, 0])) and not m.get("doubleSided"):
            m["doubleSided"] = True
            changed += 1
    path = os.path.join(folder, os.path.splitext(os.path.basename(scene))[0] + "-two-sided.gltf")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    return path, changed


def measure_scene(a, rnd, scene):
    stem = os.path.splitext(os.path.basename(scene))[0]
    work = os.path.join(a.out, stem)
    os.makedirs(work, exist_ok=True)
    notes = []
    if a.two_sided_emission:
        scene, changed = two_sided_copy(scene, work)
        notes.append("rendered %s: %d emissive material(s) made doubleSided" % (scene, changed))
    t_start = time.perf_counter()
    own = a.reference == "own"
    if own:
        refs = {n: reference(a, rnd, scene, n) for n in ("cycles", "strata")}
    else:
        refs = {a.reference: reference(a, rnd, scene, a.reference)}
    if a.strata_reference and "strata" not in refs:
        refs["strata"] = reference(a, rnd, scene, "strata")

    series = ["strata", "cycles"]
    if a.adaptive:
        series.append("cycles-adaptive")
        if rnd.strata_adaptive:
            series.append("strata-adaptive")
        else:
            notes.append("strata render has no --noise-threshold: strata-adaptive skipped")
    runs = []
    for r in range(a.rounds):
        order = series if r % 2 == 0 else list(reversed(series))
        for spp in a.spp:
            for s in order:
                img = os.path.join(work, "%s_%s_spp%d_r%d.exr" % (stem, s, spp, r))
                seed = r + 1
                load = os.getloadavg()[0]
                if s == "strata":
                    times = rnd.strata(scene, spp, seed, img)
                elif s == "strata-adaptive":
                    times = rnd.strata(scene, spp, seed, img, noise_threshold=(
                        a.noise_threshold if a.strata_noise_threshold is None else a.strata_noise_threshold))
                elif s == "cycles":
                    times = rnd.cycles(scene, spp, seed, img)
                else:
                    times = rnd.cycles(scene, spp, seed, img, noise_threshold=a.noise_threshold)
                err = {name: compare(a.strata, img, exr, img) for name, (exr, _) in refs.items()}
                if not a.keep_images:
                    os.remove(img)
                mine = ("strata" if s.startswith("strata") else "cycles") if own else a.reference
                run_ = {"series": s, "spp": spp, "round": r, "seed": seed, "load1": load,
                        "relmse": err[mine], "relmse_vs": err, **times}
                runs.append(run_)
                log("  round %d %-16s spp %-5d relMSE %.4g  render %.3f s  wall %.3f s" % (
                    r, s, spp, run_["relmse"], times["render_s"], times["wall_s"]))

    key = TIME_KEYS[a.time]
    summary = {}
    for s in series:
        rows = []
        for spp in a.spp:
            sel = [x for x in runs if x["series"] == s and x["spp"] == spp]
            rows.append({
                "spp": spp,
                "relmse": median([x["relmse"] for x in sel]),
                "relmse_range": [min(x["relmse"] for x in sel), max(x["relmse"] for x in sel)],
                "relmse_vs": {n: median([x["relmse_vs"][n] for x in sel]) for n in refs},
                "render_s": median([x["render_s"] for x in sel]),
                "render_s_range": [min(x["render_s"] for x in sel), max(x["render_s"] for x in sel)],
                "wall_s": median([x["wall_s"] for x in sel]),
                "sampling_s": median([x.get("sampling_s") for x in sel]),
                "device_s": median([x.get("device_s") for x in sel]),
                "sync_s": median([x.get("sync_s") for x in sel]),
                "spp_done": median([x.get("spp_done") for x in sel]),
            })
        summary[s] = rows

    def curve(s):
        return [(row[key], row["relmse"]) for row in summary[s] if row[key] and row["relmse"]]

    tte = {}
    pairs = [("cycles", "strata")]
    if "cycles-adaptive" in summary:
        pairs.append(("cycles-adaptive", "strata"))
    if "strata-adaptive" in summary:
        pairs.append(("cycles-adaptive", "strata-adaptive"))
    for other, mine in pairs:
        p, q = curve(mine), curve(other)
        rows = []
        for level in levels_both_reach(p, q):
            ts, tc = loglog_time(p, level), loglog_time(q, level)
            rows.append({"relmse": level, mine + "_s": ts, other + "_s": tc,
                         "ratio": tc / ts if ts and tc else None})
        tte["%s/%s" % (other, mine)] = rows

    ref_vs = means = None
    if len(refs) > 1:
        ref_vs = compare(a.strata, refs["strata"][0], refs["cycles"][0],
                         os.path.join(work, "refs"))
        means = reference_means(refs["strata"][0], refs["cycles"][0])
    return {"scene": scene, "stem": stem, "series": series, "notes": notes,
            "reference": refs["cycles" if own else a.reference][1],
            "references": {n: i for n, (_, i) in refs.items()},
            "reference_relmse_strata_vs_cycles": ref_vs, "reference_means": means,
            "time_basis": a.time,
            "summary": summary, "time_to_error": tte, "runs": runs,
            "load1_median": median([x["load1"] for x in runs]),
            "elapsed_s": time.perf_counter() - t_start}


def markdown(a, res, rnd):
    out = []
    s = res["summary"]
    basis = {"render": "strata render.seconds (--stats-json) vs Cycles render_s (PEER_RESULT)",
             "sampling": "strata render.seconds vs Cycles render_s less its sync before "
                         "the first sample (from its log, 0.01 s steps)",
             "wall": "whole-process wall time of each"}[a.time]
    ref = res["reference"]
    refs_text = ("each renderer's own, %d spp, seed %d" % (ref["spp"], ref["seed"])
                 if a.reference == "own" else
                 "%s, %d spp, seed %d" % (ref["renderer"], ref["spp"], ref["seed"]))
    out.append("### %s (%dx%d, max depth %d / Cycles bounces %d, %d threads, %d rounds)" % (
        res["stem"], a.width, a.height, a.max_depth, a.max_depth - 1, a.threads, a.rounds))
    out.append("")
    out.append("strata %s (sha256 %s)%s; %s, Cycles peer%s. Reference: %s. "
               "Times: %s. Medians over rounds; 1-minute load average "
               "(median) %.2f." % (
                   a.strata, rnd.strata_id, " " + " ".join(a.strata_arg) if a.strata_arg else "",
                   rnd.blender_version, " " + " ".join(a.cycles_arg) if a.cycles_arg else "",
                   refs_text, basis, res["load1_median"]))
    out.append("")
    head = "| spp | strata relMSE | Cycles relMSE | Cycles/strata relMSE | strata s | Cycles s |"
    sep = "|---:|---:|---:|---:|---:|---:|"
    ad = "cycles-adaptive" in s
    sad = "strata-adaptive" in s
    if ad:
        head += " Cycles adaptive relMSE | Cycles adaptive s |"
        sep += "---:|---:|"
    if sad:
        head += " strata adaptive relMSE | strata adaptive s |"
        sep += "---:|---:|"
    head += " strata wall s | Cycles wall s |"
    sep += "---:|---:|"
    out += [head, sep]
    key = TIME_KEYS[a.time]
    for i, spp in enumerate(a.spp):
        st, cy = s["strata"][i], s["cycles"][i]
        ratio = cy["relmse"] / st["relmse"] if st["relmse"] else None
        line = "| %d | %s | %s | %s | %s | %s |" % (
            spp, fmt(st["relmse"], ".4g"), fmt(cy["relmse"], ".4g"), fmt(ratio, ".2f"),
            fmt(st[key], ".3f"), fmt(cy[key], ".3f"))
        if ad:
            ca = s["cycles-adaptive"][i]
            line += " %s | %s |" % (fmt(ca["relmse"], ".4g"), fmt(ca[key], ".3f"))
        if sad:
            sa = s["strata-adaptive"][i]
            line += " %s | %s |" % (fmt(sa["relmse"], ".4g"), fmt(sa[key], ".3f"))
        line += " %s | %s |" % (fmt(st["wall_s"], ".3f"), fmt(cy["wall_s"], ".3f"))
        out.append(line)
    out.append("")
    sync = median([r["sync_s"] for r in s["cycles"]])
    if sync is not None and a.time == "render":
        out.append("Cycles' render_s includes its scene sync and BVH build before the first "
                   "sample: median %.3f s here; strata's render.seconds excludes its load, "
                   "BVH, upload and pipeline creation." % sync)
        out.append("")
    for name, rows in res["time_to_error"].items():
        other, mine = name.split("/")
        out.append("Time to equal relMSE, %s vs %s (log-log interpolation):" % (other, mine))
        out.append("")
        if not rows:
            out.append("(no relMSE level that both reach)")
            out.append("")
            continue
        out.append("| relMSE | %s s | %s s | %s / %s time |" % (mine, other, other, mine))
        out.append("|---:|---:|---:|---:|")
        for r in rows:
            out.append("| %.4g | %s | %s | %s |" % (r["relmse"], fmt(r[mine + "_s"], ".3f"),
                                                   fmt(r[other + "_s"], ".3f"),
                                                   fmt(r["ratio"], ".2f")))
        out.append("")
    if res["reference_relmse_strata_vs_cycles"] is not None:
        m = res["reference_means"]
        hi = a.spp[-1]
        out.append("References: relMSE(strata reference, Cycles reference) = %.4g; from the "
                   "noise alone (strata's variance channels, Cycles' taken as noisy): about %s. "
                   "At %d spp, strata vs its own / Cycles' reference: %.4g / %.4g; Cycles vs its "
                   "own / strata's: %.4g / %.4g." % (
                       res["reference_relmse_strata_vs_cycles"], fmt(m["noise_relmse"], ".2g"), hi,
                       s["strata"][-1]["relmse_vs"]["strata"], s["strata"][-1]["relmse_vs"]["cycles"],
                       s["cycles"][-1]["relmse_vs"]["cycles"], s["cycles"][-1]["relmse_vs"]["strata"]))
        out.append("")
        ratio = [c / x if x else None for c, x in zip(m["cycles"], m["strata"])]
        z = [(c - x) / (math.sqrt(2) * e) if e else None
             for c, x, e in zip(m["cycles"], m["strata"], m["strata_se"])]
        out.append("Mean R, G, B of the references: strata %s, Cycles %s; Cycles / strata %s; "
                   "(Cycles - strata) in standard errors of strata's mean (times sqrt 2, as if "
                   "Cycles' were as noisy): %s. A ratio off 1 by many standard errors is a bias "
                   "(e.g. Cycles' two-sided emission), not noise." % (
                       "/".join(fmt(v, ".4g") for v in m["strata"]),
                       "/".join(fmt(v, ".4g") for v in m["cycles"]),
                       "/".join(fmt(v, ".3f") for v in ratio),
                       "/".join(fmt(v, ".1f") for v in z)))
        out.append("")
    for n in res["notes"]:
        out.append("Note: " + n)
        out.append("")
    return "\n".join(out)


def main(argv):
    a = parse_args(argv)
    if not os.access(a.strata, os.X_OK):
        sys.exit("no strata executable at %s (--strata PATH)" % a.strata)
    if shutil.which(a.blender) is None:
        sys.exit("no %s: apt-get install -y --no-install-recommends blender python3-numpy"
                 % a.blender)
    if not os.path.exists(a.cycles_peer):
        sys.exit("no Cycles peer at %s (--cycles-peer PATH)" % a.cycles_peer)
    a.cycles_peer = os.path.abspath(a.cycles_peer)
    a.scenes = [os.path.abspath(x) for x in a.scenes]
    os.makedirs(a.out, exist_ok=True)
    rnd = Renderers(a)
    if a.ref_spp < 16 * a.spp[-1]:
        log("warning: --ref-spp %d is under 16x the largest --spp: the reference's own noise "
            "will weigh on the high-spp relMSE" % a.ref_spp)
    results, texts = [], []
    t0 = time.perf_counter()
    for scene in a.scenes:
        res = measure_scene(a, rnd, scene)
        results.append(res)
        text = markdown(a, res, rnd)
        texts.append(text)
        print(text, flush=True)
    doc = {"args": {k: v for k, v in vars(a).items()}, "blender": rnd.blender_version,
           "strata_sha256": rnd.strata_id,
           "strata_has_noise_threshold": rnd.strata_adaptive, "scenes": results,
           "elapsed_s": time.perf_counter() - t0}
    with open(a.json, "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(texts) + "\n")
    log("wrote %s and %s (%.0f s)" % (a.json, os.path.join(a.out, "summary.md"), doc["elapsed_s"]))


if __name__ == "__main__":
    main(sys.argv[1:])
