# Sourced by the study scripts: `once DIR ARBOR_ARGS...` runs "$arbor" ARBOR_ARGS --quiet --out DIR unless
# DIR/result.json exists (so an interrupted study resumes), writing into DIR.partial and renaming it when the
# run finished. Keeps result.json, trajectory.tum, map.csv and associations.csv (the smoother reads the
# latter); drops the per-step files.
once() {
  local dir=$1
  shift
  [ -f "$dir/result.json" ] && return 0
  rm -rf "$dir.partial"
  "$arbor" "$@" --quiet --out "$dir.partial" > /dev/null
  rm -f "$dir.partial/steps.csv" "$dir.partial/trajectory_mean.tum"
  mv "$dir.partial" "$dir"
}
