# Sourced first by validation/<case>/run.sh: sets here (the case's folder), root (the checkout),
# build_dir ($WHEELSIM_BUILD_DIR, else <root>/build), python (Debian's, with numpy, h5py and
# matplotlib) and smoke_sweep_args, and brings write_provenance (provenance.sh) and
# stop_if_signalled.
# Each run.sh wraps everything after `set -euo pipefail` in one brace group, so bash reads it
# whole before it runs: bash otherwise reads a script as it goes, and an edit of a run.sh (or an
# update of the checkout) during a run of hours would change what the running case does next.
here=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)
root=$(cd "$here/../.." && pwd)
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}
python=/usr/bin/python3
# What every case's --smoke passes to wheel-sweep: a bed-hold check of 0.05 s, not 0.2 s (CI time;
# the same deck and verdict on a quarter of the steps; the 0.2 s check was ~2/3 of the blind
# smoke's LIGGGHTS steps and ~1/10 of the study-wheels smoke's wall time).
smoke_sweep_args=(--bed-hold 0.05)
source "$root/validation/common/provenance.sh"

# stop_if_signalled RC WHAT: wheel-sweep exited 128 + N (stopped by signal N, e.g. at a session's
# end): its points are unfinished, so exit RC before any results table or provenance is written.
stop_if_signalled() {
  if (($1 > 128)); then
    echo "run.sh: wheel-sweep stopped by signal $(($1 - 128)) ($2): no results written" >&2
    exit "$1"
  fi
}

# finished_runs OUT [KEPT]: the run.h5 of every finished point under OUT (<wheel>/<soil>/<slip>/;
# a failed point is reported by wheel-sweep and left out), each by its committed copy in KEPT (the
# case's points/<sweep>/, wheel-sweep --archive) where that copy is the same run (the same
# done.json), and the points only KEPT holds, i.e. those OUT has no done.json for (a machine whose
# runs/ lost them; a point OUT records as failed or re-ran is OUT's): a results table then names
# run files every clone has.
finished_runs() {
  local out=${1%/} kept=${2:-} run rel
  kept=${kept%/}
  {
    while IFS= read -r run; do
      rel=${run#"$out/"}
      if [[ -n $kept && -f $kept/$rel ]] \
        && cmp -s "$kept/${rel%run.h5}done.json" "$out/${rel%run.h5}done.json"; then
        echo "$kept/$rel"
      else
        echo "$run"
      fi
    done < <(find "$out" -mindepth 4 -maxdepth 4 -name run.h5 -not -path "*/beds/*" 2>/dev/null)
    if [[ -n $kept && -d $kept ]]; then
      while IFS= read -r run; do
        rel=${run#"$kept/"}
        [[ -f $out/${rel%run.h5}done.json ]] || echo "$run"
      done < <(find "$kept" -mindepth 4 -maxdepth 4 -name run.h5)
    fi
  } | sort -u
}

# keep_table NEW DEST: DEST becomes NEW, unless DEST already holds the same rows (its lines other
# than the # comments): a re-run that skipped every finished point computes the same numbers under
# a new git and command line, and the committed table keeps the record of the run that made them.
# Sets table_kept (1: DEST kept as it was, 0: replaced).
keep_table() {
  if [[ -f $2 ]] && cmp -s <(grep -v '^#' "$1") <(grep -v '^#' "$2"); then
    rm -f "$1"
    table_kept=1
  else
    mv -f "$1" "$2"
    table_kept=0
  fi
}
