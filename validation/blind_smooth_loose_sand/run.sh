#!/usr/bin/env bash
# Validation case 2 — blind prediction: smooth wheel on loose sand (README.md).
#
#   validation/blind_smooth_loose_sand/run.sh [--smoke | --sensitivity | --scm] [--out-dir DIR] [--jobs N] [--force]
#
# Full case: prepares the ~74 000-sphere bin once and runs the 9 slips (signed convention, each set
# by the wheel speed at 0.1 m/s; 0.12 m of test travel) through wheel-sweep (resumable: a re-run
# skips finished points), then the same 9 slips at steady sinkage (0.25 m of travel on a 0.52 m
# bin, README "The steady-state sweep"), and writes into this folder results.csv, curves.csv,
# prediction.png, results_travel_0.25.csv and provenance.toml (git hash, command, machine, wall
# time). results.csv is the steady-state sweep's table (sinkage against the long bed's equivalent
# surface, surface_loose_1330_long.csv) once all its nine slips are in, with the 0.12 m windows
# then in results_window_0.12.csv; until then the 0.12 m windows' table. Many hours on 2 cores
# (README "Cost"): run it in the background, nohup ... &; a point that cannot finish before the
# machine goes is parked (README "Resuming across sessions").
# --sensitivity: afterwards also the speed (0.05 m/s), bed-depth (0.063 m; then ~0.155 m at
#          s = 0.9 alone), time-step (half, at s = 0.9 alone) and grain-size sweeps (1.5 x the
#          main size, 4.5-7.9 mm; then the calibrated 2-3.5 mm spheres), in that order, at 2
#          slips each but the deeper bed and the time step: results_speed_0.05.csv,
#          results_depth_0.06.csv, results_depth_0.15.csv, results_dt_0.5.csv,
#          results_grain_2.25.csv, results_grain_1.0.csv and sensitivity.png here.
# --scm:   only the SCM half (sweep_scm.toml: the same rig and slips on the SCM soil the soil lab
#          fitted to the DEM soil, inputs/scm_soils/from_dem/loose_sand_1330.toml; ~1 min per
#          point): results_scm.csv, comparison_scm.md/png (DEM against SCM) and
#          provenance_scm.toml here; then the same at the steady-state sweep's travel
#          (sweep_scm_travel.toml): results_scm_travel_0.25.csv and
#          comparison_scm_travel_0.25.md. Not part of the blind prediction (README).
# Finished points are kept in points/ (committed) and restored on the next run (README).
# --smoke: the CI version (a tiny bin, its bed-hold check 0.05 s, slip -0.5, 0.05 s of test phase;
#          minutes): same pipeline, outputs into --out-dir only (nothing in this folder changes).
set -euo pipefail
# The rest is one brace group, read whole before it runs (common/case.sh says why).
{
source "$(dirname "${BASH_SOURCE[0]}")/../common/case.sh"   # here, root, build_dir, python
smoke=0 sensitivity=0 scm=0 out="" sweep_args=() args=("$@")
while (($#)); do
  case "$1" in
    --smoke) smoke=1; shift ;;
    --sensitivity) sensitivity=1; shift ;;
    --scm) scm=1; shift ;;
    --out-dir) out=$2; shift 2 ;;
    --jobs|-j) sweep_args+=(--jobs "$2"); shift 2 ;;
    --force) sweep_args+=(--force); shift ;;
    -h|--help) sed -n '2,/^set -euo pipefail/{/^set -euo/!p}' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
((smoke + sensitivity + scm > 1)) && { echo "run.sh: --smoke, --sensitivity and --scm exclude each other" >&2; exit 2; }
if ((smoke)); then out=${out:-$root/runs/validation/blind_smooth_loose_sand_smoke}; sweep_args+=("${smoke_sweep_args[@]}")
else out=${out:-$root/runs/validation/blind_smooth_loose_sand}; fi
if ((scm)); then
  soil=$root/inputs/scm_soils/from_dem/loose_sand_1330.toml
  [[ -f $soil ]] || { echo "run.sh: --scm needs $soil (soil_lab/soil-lab run loose_sand_1330 ..., then soil-lab scm)" >&2; exit 2; }
  [[ -f $here/results.csv ]] || { echo "run.sh: --scm compares with the DEM half's $here/results.csv: run the case first" >&2; exit 2; }
fi
[[ -f $build_dir/meshes/smooth_r58_w50.stl ]] || {
  echo "run.sh: $build_dir/meshes/smooth_r58_w50.stl missing: build first (scripts/build.sh)" >&2; exit 2; }

start=$(date +%s)
started_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
status=0

# sweep NAME CONFIG WINDOW_START WINDOW_END RESULTS: run one sweep into $out/NAME and write its
# results table (and $out/NAME/curves.csv; RESULTS "": no table, the caller writes it) (window in test-phase seconds: 0.05 m of travel after
# the approach to steady sinkage, README "Averaging window"). A failed point is reported by
# wheel-sweep and left out; a sweep stopped by a signal (the session's end) writes nothing. The
# full case keeps its finished points in the committed points/NAME/ (wheel-sweep --archive;
# README "Resuming across sessions").
# kept_points NAME: the committed folder of sweep NAME's finished points (none for the smoke run
# and for SCM, whose points take a minute)
kept_points() { ((smoke || scm)) || echo "$here/points/$1"; }

sweep() {
  local name=$1 config=$2 w0=$3 w1=$4 results=$5 archive=() kept
  kept=$(kept_points "$name")
  [[ -z $kept ]] || archive=(--archive "$kept")
  local rc=0
  "$root/scripts/wheel-sweep" "$config" --out-dir "$out/$name" --build-dir "$build_dir" \
    "${archive[@]}" "${sweep_args[@]}" || rc=$?
  stop_if_signalled "$rc" "$name"
  ((rc == 0)) || status=$rc
  [[ -z $results ]] || window_table "$name" "$w0" "$w1" "$results"
}

# window_table NAME WINDOW_START WINDOW_END RESULTS [CURVES [CURVES_ARGS...]]: the results table
# of sweep NAME's finished runs (kept ones from points/NAME) over the window, into RESULTS (and
# CURVES, default $out/NAME/curves.csv; CURVES_ARGS go to `wheelsim-post curves`, e.g.
# --sinkage-offset); the table's run_file column is relative to RESULTS' folder, so a table is
# written where it is kept, never copied there from another folder.
window_table() {
  local name=$1 w0=$2 w1=$3 results=$4 curves=${5:-$out/$1/curves.csv} runs
  mapfile -t runs < <(finished_runs "$out/$name" "$(kept_points "$name")")
  ((${#runs[@]})) || { echo "run.sh: no finished run under $out/$name" >&2; exit 1; }
  "$root/postprocess/wheelsim-post" curves "${runs[@]}" --window-start "$w0" --window-end "$w1" \
    "${@:6}" --results "$results.new" --csv "$curves"
  keep_table "$results.new" "$results"
}

if ((scm)); then
  # the main sweep's window, against the DEM table of the same window (results.csv until the
  # steady-state sweep replaces it, results_window_0.12.csv after); no DEM table is touched
  dem=$here/results.csv dem_label="DEM (the prediction)"
  [[ -f $here/results_window_0.12.csv ]] && dem=$here/results_window_0.12.csv dem_label="DEM (0.12 m windows)"
  sweep scm "$here/sweep_scm.toml" 0.7 1.2 "$here/results_scm.csv"
  "$python" "$here/plot.py" --png "$here/comparison_scm.png" \
    --title "DEM and SCM on the same soil (loose_sand_1330; SCM: the soil lab's fit)" \
    "$dem_label=$dem" "SCM, fitted to the DEM soil=$here/results_scm.csv"
  "$python" "$root/validation/common/dem_vs_scm.py" "$dem" "$here/results_scm.csv" \
    --md "$here/comparison_scm.md"
  # and at the steady-state sweep's travel and window (README "The steady-state sweep")
  sweep scm_travel "$here/sweep_scm_travel.toml" 2.0 2.5 "$here/results_scm_travel_0.25.csv"
  if [[ -f $here/results_travel_0.25.csv ]]; then
    "$python" "$root/validation/common/dem_vs_scm.py" "$here/results_travel_0.25.csv" \
      "$here/results_scm_travel_0.25.csv" --md "$here/comparison_scm_travel_0.25.md"
  fi
  write_provenance "$here/provenance_scm.toml" validation/blind_smooth_loose_sand \
    "validation/blind_smooth_loose_sand/run.sh${args[*]:+ }${args[*]}" "$started_utc" "$start" "$out/scm"
  exit $status
fi
if ((smoke)); then
  dest=$out
  sweep main "$here/sweep_smoke.toml" 0.025 0.05 "$dest/results.csv"
else
  dest=$here
  # The prediction is the steady-state sweep once its nine slips are in (README "The steady-state
  # sweep", decided 2026-12-03): results.csv from its runs, with sinkage read against the long
  # bed's equivalent surface; the main sweep's 0.12 m windows then go to results_window_0.12.csv.
  # Until then results.csv is the main sweep's table, as before.
  # (the main sweep's table is written below, to results.csv or results_window_0.12.csv)
  main_window=(0.7 1.2)
  sweep main "$here/sweep.toml" "${main_window[@]}" ""
  sweep travel_0.25 "$here/sweep_travel.toml" 2.0 2.5 "$dest/results_travel_0.25.csv"
  n_slips=$("$python" -c 'import sys, tomllib; print(len(tomllib.load(open(sys.argv[1], "rb"))["slips"]))' "$here/sweep_travel.toml")
  n_travel=$(grep -cv '^#\|^slip,' "$dest/results_travel_0.25.csv")
  if ((n_travel == n_slips)); then
    # the offset: bed depth minus equivalent surface, from the header of the surface profile
    offset=$("$python" - "$here/surface_loose_1330_long.csv" <<'PY'
import re, sys
head = open(sys.argv[1]).read()
depth = float(re.search(r"bed depth ([0-9.e+-]+) m", head).group(1))
surface = float(re.search(r"equivalent surface ([0-9.e+-]+) m", head).group(1))
print(f"{depth - surface:.6f}")
PY
)
    window_table travel_0.25 2.0 2.5 "$dest/results.csv" "$out/prediction_curves.csv" \
      --sinkage-offset "$offset"
    cp "$out/prediction_curves.csv" "$dest/curves.csv"
    window_table main "${main_window[@]}" "$dest/results_window_0.12.csv"
    echo "run.sh: results.csv: the steady-state sweep (0.25 m of travel; sinkage against the equivalent surface, offset $offset m); the 0.12 m windows in results_window_0.12.csv"
  else
    window_table main "${main_window[@]}" "$dest/results.csv"
    cp "$out/main/curves.csv" "$dest/curves.csv"
    echo "run.sh: results.csv: the main sweep (0.12 m windows); the steady-state sweep has $n_travel of its $n_slips slips"
  fi
fi
"$python" "$here/plot.py" --png "$dest/prediction.png" "$dest/results.csv"
if ((sensitivity)); then
  # the order is the order of what each tells: speed (the quasi-static question), depth, time
  # step, grain (dearest); travel ran above (the prediction's sweep)
  sweep speed_0.05 "$here/sweep_speed.toml" 1.4 2.4 "$dest/results_speed_0.05.csv"
  sweep depth_0.06 "$here/sweep_depth.toml" 0.7 1.2 "$dest/results_depth_0.06.csv"
  sweep depth_0.15 "$here/sweep_depth_deep.toml" 0.7 1.2 "$dest/results_depth_0.15.csv"
  sweep dt_0.5 "$here/sweep_dt.toml" 0.7 1.2 "$dest/results_dt_0.5.csv"
  sweep grain_2.25 "$here/sweep_grain_2.25.toml" 0.7 1.2 "$dest/results_grain_2.25.csv"
  sweep grain_1.0 "$here/sweep_grain.toml" 0.7 1.2 "$dest/results_grain_1.0.csv"
  # the sensitivity sweeps average 0.12 m windows: their baseline is the main sweep's table
  # (results_window_0.12.csv once results.csv is the steady-state sweep's)
  baseline=$dest/results.csv
  [[ -f $dest/results_window_0.12.csv ]] && baseline=$dest/results_window_0.12.csv
  "$python" "$here/plot.py" --png "$dest/sensitivity.png" \
    --title "sensitivity: speed, grain size, bed depth, travel, time step (smooth wheel, loose sand 1330)" \
    "main: 0.1 m/s, d50 4.1 mm, bed 0.105 m=$baseline" \
    "0.05 m/s=$dest/results_speed_0.05.csv" "d50 6.2 mm=$dest/results_grain_2.25.csv" \
    "d50 2.75 mm=$dest/results_grain_1.0.csv" \
    "bed 0.063 m=$dest/results_depth_0.06.csv" "bed 0.155 m=$dest/results_depth_0.15.csv" \
    "travel 0.25 m=$dest/results_travel_0.25.csv" "dt 0.825e-5 s=$dest/results_dt_0.5.csv"
fi
write_provenance "$dest/provenance.toml" validation/blind_smooth_loose_sand \
  "validation/blind_smooth_loose_sand/run.sh${args[*]:+ }${args[*]}" \
  "$started_utc" "$start" "$out"
exit $status
}
