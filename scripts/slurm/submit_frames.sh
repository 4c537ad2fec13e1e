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
[ -f "$scene" ] || fail "$scene: no such scene file"
irad="${IRAD:-$(command -v irad || true)}"
[ -x "$irad" ] || fail "IRAD: no irad binary (set IRAD=/path/to/irad)"
command -v sbatch >/dev/null || fail "sbatch: not installed (is this a Slurm login node?)"
ping="$(scontrol ping 2>&1 || true)"
grep -q 'is UP' <<<"$ping" || fail "Slurm is not reachable: scontrol ping: $(head -1 <<<"$ping")"
mkdir -p "$out" || fail "$out: cannot create the output folder"
export IRAD="$(realpath "$irad")" SCENE="$(realpath "$scene")" FRAMES="$frames" \
  OUT="$(realpath "$out")" IRAD_OPTS="$*"
# shellcheck disable=SC2086
array=$(sbatch --parsable --export=ALL --chdir="$OUT" --array="0-$((tasks - 1))" \
  ${SBATCH_OPTS:-} "$here/frames.sbatch") || fail "sbatch: the array was not accepted"
echo "${array%%;*}"
