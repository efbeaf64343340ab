# Sourced by validation/<case>/run.sh: the provenance of a case's committed outputs.
#   write_provenance FILE CASE_DIR COMMAND STARTED_UTC START_EPOCH RUNS_DIR
# writes FILE (TOML): the command, git commit and whether the tree had changes (outside runs/),
# host, cores, start time, this invocation's wall time and where the runs are. The commit is
# taken twice: when this file was sourced (the run's start: git_commit_at_start) and when FILE
# is written (git_commit), as a long run may see commits land in the checkout while it runs.
provenance_git_start=$(git -C "$(dirname "${BASH_SOURCE[0]}")" rev-parse HEAD 2>/dev/null || echo unknown)
write_provenance() {
  local file=$1 case_dir=$2 command=$3 started_utc=$4 start=$5 runs_dir=$6
  local root changes=false
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  [[ -n $(git -C "$root" status --porcelain -- . ':!runs' 2>/dev/null) ]] && changes=true
  cat > "$file" <<TOML
# written by $case_dir/run.sh
command = "$command"
git_commit_at_start = "$provenance_git_start"
git_commit = "$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)"
git_changes = $changes
host = "$(hostname)"
cores = $(nproc)
started_utc = "$started_utc"
wall_s = $(( $(date +%s) - start ))   # this invocation (finished points skipped on a resume cost nothing here)
runs_dir = "$runs_dir"
TOML
}
