#!/usr/bin/python3
"""tests/farm/check_k8s.py STRATA_EXE SOURCE_DIR (ctest label unit)

Checks the Kubernetes manifests of scripts/k8s statically (no cluster):
every YAML file parses (Debian's python3-yaml, hence /usr/bin/python3),
kinds and apiVersions are right, the shards Job is an Indexed Job whose
completions equal the K of its --shard $(JOB_COMPLETION_INDEX)/K, its
JOB_COMPLETION_INDEX comes from the completion index, the merge Job reads
exactly shard_0..K-1.state, both mount the claim of strata-pvc.yaml at /data.
Then each container command line, with $(JOB_COMPLETION_INDEX) set to each
index and /data mapped to a temporary folder, runs with --dry-run appended
and must exit 0.

Last, broken copies of the manifests (a wrong completions count, a shard
missing from the merge, an unknown strata flag, ...) must each be caught:
the check can fail.
"""
import copy
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

try:
    import yaml
except ImportError:
    sys.exit("FAIL: no PyYAML for %s (Debian package python3-yaml, in "
             "scripts/debian-packages.txt; make test installs it)" % sys.executable)

INDEX_VAR = "JOB_COMPLETION_INDEX"
INDEX_FIELD = "metadata.annotations['batch.kubernetes.io/job-completion-index']"
KINDS = {"Job": "batch/v1", "PersistentVolumeClaim": "v1"}
VAR_REF = re.compile(r"\$\(([A-Za-z_][A-Za-z0-9_]*)\)")


def expand(arg, env):
    """Kubernetes' $(VAR) expansion of command and args (a $(VAR) naming no
    env entry stays as written; $$ is a literal $)."""
    out, i = [], 0
    while i < len(arg):
        if arg.startswith("$$", i):
            out.append("$")
            i += 2
            continue
        m = VAR_REF.match(arg, i)
        if m and m.group(1) in env:
            out.append(env[m.group(1)])
            i = m.end()
            continue
        out.append(arg[i])
        i += 1
    return "".join(out)


def container_of(job):
    containers = job["spec"]["template"]["spec"]["containers"]
    if len(containers) != 1:
        raise ValueError("%d containers, not 1" % len(containers))
    return containers[0]


def command_of(container):
    argv = list(container.get("command") or []) + list(container.get("args") or [])
    if not argv or not all(isinstance(a, str) for a in argv):
        raise ValueError("the command is not a list of strings: %r" % argv)
    return argv


def check_volume(name, job, claims, errors):
    pod = job["spec"]["template"]["spec"]
    container = container_of(job)
    volumes = {v.get("name"): v for v in pod.get("volumes") or []}
    mounts = [m for m in container.get("volumeMounts") or [] if m.get("mountPath") == "/data"]
    if len(mounts) != 1:
        errors.append("%s: no single volume mounted at /data" % name)
        return
    claim = (volumes.get(mounts[0].get("name")) or {}).get("persistentVolumeClaim", {}).get("claimName")
    if claim not in claims:
        errors.append("%s: /data is not the claim of a PersistentVolumeClaim manifest (%r, claims %s)"
                      % (name, claim, sorted(claims)))
    if pod.get("restartPolicy") not in ("Never", "OnFailure"):
        errors.append("%s: a Job's restartPolicy must be Never or OnFailure" % name)


def check_shards(job, errors):
    """Returns (K, the command lines of the K pods) of the shards Job."""
    spec = job["spec"]
    container = container_of(job)
    argv = command_of(container)
    if spec.get("completionMode") != "Indexed":
        errors.append("strata-shards: completionMode is %r, not Indexed" % spec.get("completionMode"))
    if argv[:2] != ["strata", "render"]:
        errors.append("strata-shards: the command is not strata render: %s" % argv[:2])
    shard = [argv[i + 1] for i, a in enumerate(argv[:-1]) if a == "--shard"]
    m = re.fullmatch(r"\$\(%s\)/([1-9][0-9]*)" % INDEX_VAR, shard[0]) if len(shard) == 1 else None
    if not m:
        errors.append("strata-shards: not one --shard $(%s)/K: %s" % (INDEX_VAR, shard))
        return None, []
    k = int(m.group(1))
    completions = spec.get("completions")
    if completions != k:
        errors.append("strata-shards: completions is %r, the command's K is %d" % (completions, k))
    parallelism = spec.get("parallelism", 1)
    if not isinstance(parallelism, int) or not 1 <= parallelism <= k:
        errors.append("strata-shards: parallelism %r is not in [1, %d]" % (parallelism, k))
    outputs = [argv[i + 1] for i, a in enumerate(argv[:-1]) if a in ("-o", "--output")]
    if outputs != ["/data/out/shard_$(%s).state" % INDEX_VAR]:
        errors.append("strata-shards: the outputs are %s, not /data/out/shard_$(%s).state"
                      % (outputs, INDEX_VAR))
    # The index must come from the Job's completion index: an env entry of
    # that name from the annotation (or none: the Job controller adds it).
    env = {}
    for e in container.get("env") or []:
        if e.get("name") == INDEX_VAR:
            field = (e.get("valueFrom") or {}).get("fieldRef", {}).get("fieldPath")
            if field != INDEX_FIELD:
                errors.append("strata-shards: %s is not the completion index (%r)" % (INDEX_VAR, field))
        elif "value" in e:
            env[e["name"]] = str(e["value"])
    lines = []
    for i in range(k):
        env_i = dict(env, **{INDEX_VAR: str(i)})
        lines.append([expand(a, env_i) for a in argv])
    return k, lines


def check_merge(job, k, errors):
    container = container_of(job)
    argv = command_of(container)
    env = {e["name"]: str(e["value"]) for e in container.get("env") or [] if "value" in e}
    argv = [expand(a, env) for a in argv]
    if argv[:2] != ["strata", "merge"]:
        errors.append("strata-merge: the command is not strata merge: %s" % argv[:2])
    inputs, i = [], 2
    while i < len(argv):
        if argv[i] in ("-o", "--output"):
            i += 2
        elif argv[i].startswith("-"):
            i += 1
        else:
            inputs.append(argv[i])
            i += 1
    if k is not None:
        want = ["/data/out/shard_%d.state" % s for s in range(k)]
        if inputs != want:
            errors.append("strata-merge: reads %s, not shard_0..%d.state of the %d shards"
                          % ([os.path.basename(p) for p in inputs], k - 1, k))
    return argv


def dry_run(name, argv, strata, root, source, errors):
    """Runs argv (strata first) with --dry-run, /data mapped to root."""
    mapped = [strata] + [root + a[len("/data"):] if a == "/data" or a.startswith("/data/") else a
                         for a in argv[1:]]
    p = subprocess.run(mapped + ["--dry-run"], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        errors.append("%s: %s exits %d: %s" % (name, " ".join(mapped + ["--dry-run"]), p.returncode,
                                              (p.stderr or p.stdout).strip()))


def check(docs, strata, source):
    """docs: {file name: [documents]}. Returns the errors found."""
    errors = []
    jobs, claims = {}, set()
    for fname, file_docs in docs.items():
        for doc in file_docs:
            if doc is None:
                continue
            kind, api = doc.get("kind"), doc.get("apiVersion")
            if kind not in KINDS:
                errors.append("%s: unexpected kind %r" % (fname, kind))
                continue
            if api != KINDS[kind]:
                errors.append("%s: %s has apiVersion %r, not %s" % (fname, kind, api, KINDS[kind]))
            name = (doc.get("metadata") or {}).get("name")
            if kind == "PersistentVolumeClaim":
                claims.add(name)
            else:
                jobs[name] = doc
    for name in ("strata-shards", "strata-merge"):
        if name not in jobs:
            errors.append("no Job named %s" % name)
    if errors:
        return errors
    try:
        for name in ("strata-shards", "strata-merge"):
            check_volume(name, jobs[name], claims, errors)
        k, shard_lines = check_shards(jobs["strata-shards"], errors)
        merge_line = check_merge(jobs["strata-merge"], k, errors)
        images = {container_of(jobs[n]).get("image") for n in ("strata-shards", "strata-merge")}
        if len(images) != 1 or None in images:
            errors.append("the two Jobs do not run one image: %s" % images)
    except (KeyError, TypeError, ValueError, AttributeError) as e:
        errors.append("malformed Job: %s: %s" % (type(e).__name__, e))
        return errors
    # The command lines themselves, as strata parses them.
    with tempfile.TemporaryDirectory(prefix="strata-k8s.") as root:
        os.makedirs(os.path.join(root, "out"))
        shutil.copytree(os.path.join(source, "scenes"), os.path.join(root, "scenes"))
        for i, argv in enumerate(shard_lines):
            dry_run("strata-shards index %d" % i, argv, strata, root, source, errors)
        dry_run("strata-merge", merge_line, strata, root, source, errors)
    return errors


def breakages(docs):
    """(what, broken copy of docs) pairs that check() must reject."""
    def mutate(what, fn):
        broken = copy.deepcopy(docs)
        jobs = {d["metadata"]["name"]: d for f in broken.values() for d in f if d and d.get("kind") == "Job"}
        fn(jobs)
        return what, broken

    def cmd(jobs, name):
        return container_of(jobs[name])["command"]

    def replace(lst, old, new):
        lst[lst.index(old)] = new

    k = docs_k(docs)
    return [
        mutate("completions one more than K",
               lambda j: j["strata-shards"]["spec"].__setitem__("completions", k + 1)),
        mutate("completionMode NonIndexed",
               lambda j: j["strata-shards"]["spec"].__setitem__("completionMode", "NonIndexed")),
        mutate("the merge without its last shard",
               lambda j: cmd(j, "strata-merge").remove("/data/out/shard_%d.state" % (k - 1))),
        mutate("the merge reading shard 0 twice",
               lambda j: replace(cmd(j, "strata-merge"), "/data/out/shard_1.state", "/data/out/shard_0.state")),
        mutate("shard outputs without the index",
               lambda j: replace(cmd(j, "strata-shards"), "/data/out/shard_$(%s).state" % INDEX_VAR,
                                 "/data/out/shard.state")),
        mutate("apiVersion batch/v2",
               lambda j: j["strata-merge"].__setitem__("apiVersion", "batch/v2")),
        mutate("an unknown strata render flag (dry run)",
               lambda j: cmd(j, "strata-shards").append("--no-such-flag")),
        mutate("a merge output of no known format (dry run)",
               lambda j: cmd(j, "strata-merge").__setitem__(-1, "/data/out/merged.txt")),
    ]


def docs_k(docs):
    for f in docs.values():
        for d in f:
            if d and (d.get("metadata") or {}).get("name") == "strata-shards":
                return d["spec"]["completions"]
    return 1


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: check_k8s.py STRATA_EXE SOURCE_DIR")
    strata, source = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    files = sorted(glob.glob(os.path.join(source, "scripts", "k8s", "*.yaml")))
    if not files:
        sys.exit("FAIL: no scripts/k8s/*.yaml")
    docs = {}
    for f in files:
        try:
            with open(f) as fh:
                docs[os.path.basename(f)] = list(yaml.safe_load_all(fh))
        except yaml.YAMLError as e:
            sys.exit("FAIL: %s does not parse: %s" % (f, e))
    errors = check(docs, strata, source)
    if errors:
        print("FAIL: scripts/k8s:\n  " + "\n  ".join(errors))
        return 1
    print("scripts/k8s: %s pass (%d shards)" % (", ".join(sorted(docs)), docs_k(docs)))
    missed = []
    for what, broken in breakages(docs):
        found = check(broken, strata, source)
        if not found:
            missed.append(what)
        else:
            print("  broken copy caught, %s: %s" % (what, found[0]))
    if missed:
        print("FAIL: the check missed broken manifests: " + "; ".join(missed))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
