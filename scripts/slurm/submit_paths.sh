#!/usr/bin/env bash
# Renders SCENE with N paths as K array tasks of path ranges and merges them in a job that
# depends on the array (docs/cluster.md). Prints the merge job's id.
# Usage: submit_paths.sh SCENE N K OUT [irad render options...]
#   IRAD (default: irad on PATH), SBATCH_OPTS (e.g. "--partition=p --time=1:00:00").
# SCENE, OUT and IRAD must lie on a filesystem every node sees under the same path.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fail() { echo "submit_paths: error: $*" >&2; exit 1; }
[ $# -ge 4 ] || fail "usage: submit_paths.sh SCENE N K OUT [irad render options...]"
scene="$1" paths="$2" tasks="$3" out="$4"
shift 4
[[ "$tasks" =~ ^[1-9][0-9]*$ ]] || fail "K: '$tasks' is not a positive number of tasks"
[[ "$paths" =~ ^[1-9][0-9]*$ ]] || fail "N: '$paths' is not a positive number of paths"
[ "$tasks" -le "$paths" ] || fail "K: $tasks tasks for $paths paths leave some empty"
# shellcheck source=submit_common.sh
source "$here/submit_common.sh"
check_submission "$scene" "$out"
export PATHS="$paths" IRAD_OPTS="$*"
# shellcheck disable=SC2086 # SBATCH_OPTS is a list of options
array=$(sbatch --parsable --export=ALL --chdir="$OUT" --array="0-$((tasks - 1))" \
  ${SBATCH_OPTS:-} "$here/paths.sbatch") || fail "sbatch: the array was not accepted"
# shellcheck disable=SC2086
merge=$(sbatch --parsable --export=ALL --chdir="$OUT" --dependency="afterok:${array%%;*}" \
  --kill-on-invalid-dep=yes ${SBATCH_OPTS:-} "$here/merge.sbatch") ||
  fail "sbatch: the merge was not accepted"
echo "${merge%%;*}"
