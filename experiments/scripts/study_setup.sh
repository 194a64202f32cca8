# Sourced first by the study scripts, which take OUT [ARBOR_BINARY]: sets $out (absolute) and $arbor (default
# build/bin/arbor, relative to where the script was started), makes the repository root the working directory
# (the converters default to the data shipped in data/), and defines `once`.
out=$(realpath -m "${1:?usage: $0 OUT [ARBOR_BINARY]}")
arbor=$(realpath "${2:-build/bin/arbor}")
cd "$(dirname "$0")/../.."

# `once DIR ARBOR_ARGS...` runs "$arbor" ARBOR_ARGS --quiet --out DIR unless DIR/result.json exists (so an
# interrupted study resumes), writing into DIR.partial and renaming it when the run finished. Keeps
# result.json, trajectory.tum, map.csv and associations.csv (the smoother reads the latter); drops the
# per-step files unless the study sets KEEP_STEPS=1 (steps.csv is then kept).
once() {
  local dir=$1
  shift
  [ -f "$dir/result.json" ] && return 0
  rm -rf "$dir.partial"
  "$arbor" "$@" --quiet --out "$dir.partial" > /dev/null
  [ "${KEEP_STEPS:-0}" = 1 ] || rm -f "$dir.partial/steps.csv"
  rm -f "$dir.partial/trajectory_mean.tum"
  mv "$dir.partial" "$dir"
}
