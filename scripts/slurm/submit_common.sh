# Sourced by submit_paths.sh and submit_frames.sh (which define fail()): checks what every
# submission needs and exports IRAD, SCENE and OUT as absolute paths for the jobs.
# Usage: check_submission SCENE OUT
check_submission() {
  local scene="$1" out="$2" irad ping
  [ -f "$scene" ] || fail "$scene: no such scene file"
  irad="${IRAD:-$(command -v irad || true)}"
  [ -x "$irad" ] || fail "IRAD: no irad binary (set IRAD=/path/to/irad)"
  command -v sbatch >/dev/null || fail "sbatch: not installed (is this a Slurm login node?)"
  ping="$(scontrol ping 2>&1 || true)"
  grep -q 'is UP' <<<"$ping" || fail "Slurm is not reachable: scontrol ping: $(head -1 <<<"$ping")"
  mkdir -p "$out" || fail "$out: cannot create the output folder"
  IRAD="$(realpath "$irad")" SCENE="$(realpath "$scene")" OUT="$(realpath "$out")"
  export IRAD SCENE OUT
}
