#!/usr/bin/env bash
# tests/farm/slurm_test.sh STRATA_EXE SOURCE_DIR (ctest label slurm)
#
# Starts a real, throwaway Slurm cluster on this machine (munged, slurmctld,
# slurmd: tests/farm/slurm_cluster.sh), submits a render of
# scenes/cornell-box.gltf as 4 shards and their merge through
# scripts/slurm/submit.sh, and checks that the merged image equals one
# `strata render` of the same 256 samples bit for bit. Every daemon is
# stopped and the temporary folder removed on exit, pass or fail.
# Fails (does not skip) when slurm-wlm or munge is missing, or when not root.
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: $0 STRATA_EXE SOURCE_DIR" >&2; exit 2; }
STRATA=$(realpath "$1")
src=$(realpath "$2")
[ -x "$STRATA" ] || { echo "FAIL: $STRATA is not an executable" >&2; exit 1; }
SHARDS=4 SPP=256 SIZE=48
BOUND=${STRATA_SLURM_TEST_BOUND:-300}  # seconds for all jobs together

# shellcheck source=tests/farm/slurm_cluster.sh
source "$src/tests/farm/slurm_cluster.sh"
cluster_require || { echo "FAIL: the Slurm test cannot run" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/strata-slurm.XXXXXX")
chmod 755 "$tmp"  # munged's socket folder must be reachable by all
cleanup() {
  cd /
  cluster_stop
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 143' TERM
trap 'exit 130' INT
cd "$tmp"  # the jobs' working folder: nothing is left in the caller's

start=$SECONDS
fail() {
  echo "FAIL: $*" >&2
  echo "===== jobs" >&2
  scontrol show job -o 2>&1 | sed 's/^/  /' >&2 || true
  local f
  for f in "$tmp"/out/logs/*.out "$tmp"/smoke.out; do
    [ -f "$f" ] || continue
    echo "===== job log $f" >&2
    cat "$f" >&2
  done
  echo "===== slurm and munge logs" >&2
  cluster_logs >&2
  exit 1
}

# job_states ID: the JobState of each of the job's (array) tasks, one a line.
job_states() { scontrol show job -o "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2; }

# wait_jobs DEADLINE ID...: until every task of every job has COMPLETED;
# fails at once when one ended otherwise.
wait_jobs() {
  local deadline=$1 id s states; shift
  while :; do
    local finished=1
    for id in "$@"; do
      states=$(job_states "$id")
      [ -n "$states" ] || fail "job $id is unknown to slurmctld"
      for s in $states; do
        case $s in
          COMPLETED) ;;
          PENDING | CONFIGURING | RUNNING | COMPLETING | SUSPENDED) finished=0 ;;
          *) fail "job $id: a task ended $s" ;;
        esac
      done
    done
    [ $finished -eq 0 ] || return 0
    [ $SECONDS -lt "$deadline" ] || fail "jobs $* not done after $BOUND s"
    sleep 1
  done
}

cluster_start "$tmp/cluster" || fail "the Slurm cluster did not start"
deadline=$((SECONDS + BOUND))
echo "cluster up in $((SECONDS - start)) s"

# The cluster runs a job at all (tells a broken cluster from broken scripts).
smoke=$(env "$(cluster_env)" sbatch --parsable --output="$tmp/smoke.out" --wrap hostname) ||
  fail "sbatch of a hostname job failed"
wait_jobs "$deadline" "$smoke"
[ "$(cat "$tmp/smoke.out")" = "$(hostname)" ] || fail "the hostname job printed '$(cat "$tmp/smoke.out")'"
echo "hostname job done at $((SECONDS - start)) s"

# The render farm: 4 shards and the merge, through scripts/slurm/submit.sh.
scene=$src/scenes/cornell-box.gltf
out=$tmp/out
ids=$(env "$(cluster_env)" STRATA="$STRATA" SCENE="$scene" SPP=$SPP WIDTH=$SIZE HEIGHT=$SIZE OUTDIR="$out" \
  STRATA_FLAGS="--quiet" "$src/scripts/slurm/submit.sh" -k $SHARDS -o "$out/merged.exr" -o "$out/merged.png") ||
  fail "scripts/slurm/submit.sh failed"
array_id=$(sed -n 's/^array_job_id=//p' <<<"$ids")
merge_id=$(sed -n 's/^merge_job_id=//p' <<<"$ids")
[[ -n $array_id && -n $merge_id ]] || fail "submit.sh printed no job ids: $ids"
wait_jobs "$deadline" "$array_id" "$merge_id"
# (A pending array is one record; the tasks are separate once they ran.)
[ "$(job_states "$array_id" | wc -l)" -eq $SHARDS ] || fail "the shard array $array_id did not run $SHARDS tasks"
echo "shards ($array_id) and merge ($merge_id) done at $((SECONDS - start)) s"
for ((i = 0; i < SHARDS; i++)); do
  [ -s "$out/shard_$i.state" ] || fail "no $out/shard_$i.state"
done

# The same image in one render, and the two compared bit for bit.
"$STRATA" render "$scene" --spp $SPP --width $SIZE --height $SIZE --quiet \
  -o "$tmp/single.exr" -o "$tmp/single.png" || fail "the single strata render failed"
"$STRATA" compare "$out/merged.exr" "$tmp/single.exr" --json "$tmp/compare.json" >/dev/null ||
  fail "strata compare of the merged and the single image failed (sizes?)"
# json_value KEY: the number strata compare wrote for KEY.
json_value() { sed -n "s/^ *\"$1\": *\([-+.0-9eE]*\),\{0,1\} *\$/\1/p" "$tmp/compare.json"; }
values=$(json_value values) non_finite=$(json_value non_finite) max_abs=$(json_value max_abs)
[ "$values" = $((SIZE * SIZE * 3)) ] || fail "not $SIZE x $SIZE RGB values compared: $(cat "$tmp/compare.json")"
[ "$non_finite" = 0 ] || fail "non-finite values: $(cat "$tmp/compare.json")"
awk -v x="$max_abs" 'BEGIN { exit !(x != "" && x + 0 == 0) }' ||
  fail "the merged image differs from the single render: largest absolute error $max_abs"
cmp "$out/merged.png" "$tmp/single.png" || fail "the merged PNG differs from the single render's"
echo "PASS: $SHARDS shards merged on Slurm equal one $SPP spp render bit for bit ($((SECONDS - start)) s)"
