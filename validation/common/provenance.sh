# Sourced by validation/<case>/run.sh: the provenance of a case's committed outputs.
#   write_provenance FILE CASE_DIR COMMAND STARTED_UTC START_EPOCH RUNS_DIR
# writes FILE (TOML): the command, git commit and whether the tree had uncommitted changes
# (outside runs/) when the run started, host, cores, start time, this invocation's wall time and
# where the runs are. The commit is taken twice: when this file was sourced (the run's start:
# git_commit_at_start) and when FILE is written (git_commit), as a long run may see commits land
# in the checkout while it runs. The changes are taken at the start only: by the end the case's
# own results files have changed (git_changes was always true on a re-run that way).
provenance_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
provenance_git_start=$(git -C "$provenance_root" rev-parse HEAD 2>/dev/null || echo unknown)
provenance_changes=false
[[ -n $(git -C "$provenance_root" status --porcelain -- . ':!runs' 2>/dev/null) ]] &&
  provenance_changes=true
write_provenance() {
  local file=$1 case_dir=$2 command=$3 started_utc=$4 start=$5 runs_dir=$6
  cat > "$file" <<TOML
# written by $case_dir/run.sh
command = "$command"
git_commit_at_start = "$provenance_git_start"
git_commit = "$(git -C "$provenance_root" rev-parse HEAD 2>/dev/null || echo unknown)"
git_changes = $provenance_changes   # uncommitted changes outside runs/ at the start
host = "$(hostname)"
cores = $(nproc)
started_utc = "$started_utc"
wall_s = $(( $(date +%s) - start ))   # this invocation (finished points skipped on a resume cost nothing here)
runs_dir = "$runs_dir"
TOML
}
