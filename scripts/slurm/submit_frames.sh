#!/usr/bin/env bash
# Renders the frames A:B of a walkthrough of SCENE as K array tasks (docs/cluster.md).
# Usage: submit_frames.sh SCENE A:B K OUT [irad walkthrough options...]; prints the array's id.
# IRAD, SBATCH_OPTS and the shared filesystem as for submit_paths.sh.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fail() { echo "submit_frames: error: $*" >&2; exit 1; }
[ $# -ge 4 ] || fail "usage: submit_frames.sh SCENE A:B K OUT [irad walkthrough options...]"
scene="$1" frames="$2" tasks="$3" out="$4"
shift 4
[[ "$frames" =~ ^[0-9]+:[0-9]+$ ]] || fail "A:B: '$frames' is not a frame range"
[[ "$tasks" =~ ^[1-9][0-9]*$ ]] || fail "K: '$tasks' is not a positive number of tasks"
# shellcheck source=submit_common.sh
source "$here/submit_common.sh"
check_submission "$scene" "$out"
export FRAMES="$frames" IRAD_OPTS="$*"
# shellcheck disable=SC2086
array=$(sbatch --parsable --export=ALL --chdir="$OUT" --array="0-$((tasks - 1))" \
  ${SBATCH_OPTS:-} "$here/frames.sbatch") || fail "sbatch: the array was not accepted"
echo "${array%%;*}"
