#!/usr/bin/env bash
# Submits a strata render as K shards (a Slurm array job, strata-shards.sbatch)
# and their merge (strata-merge.sbatch), which starts once every shard has
# succeeded (--dependency=afterok). Prints the two job ids. docs/distributed.md.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

synopsis="usage: $0 -k SHARDS [-o OUTPUT]... [options] [-- SBATCH_OPTION...]"
usage() {
  cat <<EOF
$synopsis

Renders \$SCENE as SHARDS Slurm array tasks (strata render --shard I/SHARDS)
and merges their states into OUTPUT once every task has succeeded. Prints
array_job_id=ID and merge_job_id=ID.

options:
  -k, --shards K          the number of shards, array tasks 0..K-1 (or \$SHARDS)
  -o, --output FILE       a merged output, .exr, .png or .state; may be given
                          more than once (default: \$OUTDIR/merged.exr)
  -p, --parallel P        run at most P shards at a time (--array=0-(K-1)%P)
  -m, --merge-sbatch OPT  an sbatch option for the merge job only; may be given
                          more than once (e.g. -m --partition=cpu)
  --no-check              do not run strata render/merge --dry-run here first
  -h, --help              print this help
  -- SBATCH_OPTION...     sbatch options for the shard array (e.g.
                          --partition=gpu --gres=gpu:1 --time=1:00:00)

environment:
  STRATA        the strata executable (default: strata on PATH)
  SCENE         the glTF scene (required)
  SPP           samples per pixel of the whole image (default: 1024)
  WIDTH HEIGHT  image size (default: strata's)
  OUTDIR        the folder for states, outputs and logs (default: ./strata-farm);
                it must be on a filesystem that every node shares
  STRATA_FLAGS  more strata render flags for every shard, split at spaces
EOF
}
# Bad arguments: the error and the synopsis; anything else: the error alone.
usage_error() { printf 'submit.sh: error: %s\n%s (--help for more)\n' "$*" "$synopsis" >&2; exit 2; }
bad() { echo "submit.sh: error: $*" >&2; exit 2; }

K=${SHARDS:-}
outputs=()
merge_opts=()
parallel=""
check=1
while [ $# -gt 0 ]; do
  case $1 in
    -k | --shards) [ $# -ge 2 ] || usage_error "$1 needs a value"; K=$2; shift 2 ;;
    --shards=*) K=${1#*=}; shift ;;
    -o | --output) [ $# -ge 2 ] || usage_error "$1 needs a value"; outputs+=("$2"); shift 2 ;;
    --output=*) outputs+=("${1#*=}"); shift ;;
    -p | --parallel) [ $# -ge 2 ] || usage_error "$1 needs a value"; parallel=$2; shift 2 ;;
    --parallel=*) parallel=${1#*=}; shift ;;
    -m | --merge-sbatch) [ $# -ge 2 ] || usage_error "$1 needs a value"; merge_opts+=("$2"); shift 2 ;;
    --merge-sbatch=*) merge_opts+=("${1#*=}"); shift ;;
    --no-check) check=0; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; break ;;
    *) usage_error "unknown argument '$1'" ;;
  esac
done
shard_opts=("$@")

[ -n "$K" ] || usage_error "no shard count: give -k K (or set SHARDS)"
[[ $K =~ ^[1-9][0-9]*$ ]] || usage_error "shard count '$K' is not a positive whole number"
[ -z "$parallel" ] || [[ $parallel =~ ^[1-9][0-9]*$ ]] || usage_error "--parallel '$parallel' is not a positive whole number"
[ -n "${SCENE:-}" ] || bad "SCENE is not set (the glTF scene to render)"
[ -f "$SCENE" ] || bad "SCENE: '$SCENE' is not a file"
STRATA=$(command -v "${STRATA:-strata}") || bad "STRATA: '${STRATA:-strata}' is not an executable (set STRATA to strata's path)"
command -v sbatch >/dev/null 2>&1 || bad "sbatch is not on PATH"

# Absolute paths: the jobs may start in another folder on another node.
SCENE=$(realpath "$SCENE")
OUTDIR=${OUTDIR:-$PWD/strata-farm}
mkdir -p "$OUTDIR/logs" || bad "OUTDIR: cannot create '$OUTDIR/logs'"
OUTDIR=$(realpath "$OUTDIR")
[ ${#outputs[@]} -gt 0 ] || outputs=("$OUTDIR/merged.exr")
for i in "${!outputs[@]}"; do outputs[i]=$(realpath -m "${outputs[i]}"); done
SPP=${SPP:-1024}
SHARDS=$K
export STRATA SCENE SPP OUTDIR SHARDS

# The jobs' command lines, checked here with --dry-run before anything queues.
if [ "$check" -eq 1 ]; then
  flags=()
  [ -z "${WIDTH:-}" ] || flags+=(--width "$WIDTH")
  [ -z "${HEIGHT:-}" ] || flags+=(--height "$HEIGHT")
  read -r -a extra <<<"${STRATA_FLAGS:-}"
  flags+=("${extra[@]}")
  states=()
  for ((i = 0; i < K; i++)); do
    "$STRATA" render "$SCENE" --spp "$SPP" "${flags[@]}" --shard "$i/$K" -o "$OUTDIR/shard_$i.state" \
      --dry-run >/dev/null || bad "shard $i/$K: strata render --dry-run failed (above); --no-check skips this check"
    states+=("$OUTDIR/shard_$i.state")
  done
  merge_outputs=()
  for o in "${outputs[@]}"; do merge_outputs+=(-o "$o"); done
  "$STRATA" merge "${states[@]}" "${merge_outputs[@]}" --dry-run >/dev/null ||
    bad "strata merge --dry-run failed (above); --no-check skips this check"
fi

array="0-$((K - 1))${parallel:+%$parallel}"
array_id=$(sbatch --parsable --export=ALL --array="$array" \
  --output="$OUTDIR/logs/shard_%a-%A.out" "${shard_opts[@]}" "$here/strata-shards.sbatch") ||
  bad "sbatch of the shard array failed"
array_id=${array_id%%;*}  # --parsable prints ID or ID;CLUSTER
merge_id=$(sbatch --parsable --export=ALL --dependency="afterok:$array_id" --kill-on-invalid-dep=yes \
  --output="$OUTDIR/logs/merge-%j.out" "${merge_opts[@]}" "$here/strata-merge.sbatch" "${outputs[@]}") || {
  scancel "$array_id" || true
  bad "sbatch of the merge failed; cancelled the shard array $array_id"
}
merge_id=${merge_id%%;*}
echo "submit.sh: shards $array_id (array $array, $SPP spp of $SCENE), merge $merge_id -> ${outputs[*]}" >&2
echo "array_job_id=$array_id"
echo "merge_job_id=$merge_id"
