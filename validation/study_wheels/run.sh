#!/usr/bin/env bash
# Validation case 3 — the reference study wheels at full size (README.md).
#
#   validation/study_wheels/run.sh [--smoke | --only PARTS] [--out-dir DIR] [--force] [--points GLOBS]
#                                  [--tables]
#
# PARTS (comma-separated, default dem,scm): dem — study wheels 1 and 5 at six slips on the tiled
# DEM dry-sand bin, 0.8 m deep (sweep.toml; prepares the bin once; ~1 h 5 min per point estimated
# on 2 idle cores with the active domain, README "Cost"); scm — the same wheels and slips on the
# fitted SCM soil and on SCM dry sand of the tables (sweep_scm.toml; minutes); scm_onset — SCM's
# jump at slip = lug height / R_eff: wheel 1 and the smooth wheel at 6 slips around it
# (sweep_scm_onset.toml; a minute), scm_onset_tips the same sheared at the lug tips; scm_tips — the SCM half sheared at the lug tips
# (sweep_scm_tips.toml, terrain.shear_surface = "lug_tips"; minutes); scm_deep — the same on the
# sand refitted with plates to 0.3 m and with shear boxes to 0.5 L (sweep_scm_deep.toml); grain — wheel 1 at
# 20 % slip on 12-30 mm grains (sweep_grain.toml, its own bin); goal — issue 12's goal point: wheel 1
# at 20 % on 21-52 mm grains, time step scaled with the grain (sweep_goal.toml, its own bin;
# measured 23 min + a 4 min bed); and issue 12's active-domain check,
# on the first (0.40 m) bin of the soil before its calibration (dry_sand_coarse_mur0.3.in, a bed of
# its own): active_domain — wheel 1 at 20 % with the active domain (sweep_active_domain.toml;
# ~40 min); full_domain — the same without it (sweep_full_domain.toml; ~75 min); repeat — the
# active-domain point on another ranks' grid (sweep_repeat.toml; ~40 min): the run-to-run scatter
# the full_domain comparison reads against; and the same check on the goal's 0.76 m bed: goal_full
# — the goal point without the active domain (sweep_goal_full.toml; ~45 min), goal_repeat — the
# goal point on another ranks' grid (sweep_goal_repeat.toml; ~25 min), compared in
# comparison_goal_active_domain.md; goal_wide_dt — goal_wide's point at the case's 4.4e-5 s step
# instead of 5.7e-5 (sweep_goal_wide_dt.toml, the same bed; ~41 min): the grain size at one step,
# since on cdt the step moves the answer as a soil parameter would; goal_wide_repour — goal_wide's
# point again on its bed as poured now (sweep_goal_wide_repour.toml; ~27 min): bed-to-bed scatter,
# and the step on one bed against goal_wide_dt; allowance — wheel 1 at 50 % with the active domain's sinkage
# allowance at 0.45 m instead of 0.3 (sweep_allowance.toml, the same bed; ~1.5 h): what the
# deepest points' active_domain_sinkage warning costs; wheel_mu — wheel 1 at 20 % with the
# wheel-sand friction at the grains' 0.7869 instead of 0.5 (sweep_wheel_mu.toml, the same bed;
# ~1.2 h): how much of the DEM-SCM traction gap is the interface; speed — wheel 1 at 20 % at half
# the wheel speed, 0.525 rad/s, over the same travel (sweep_speed.toml: test phase 12 s, window
# 4-12 s; ~2.4 h estimated, 6 h measured on a slow machine): how much of the case depends on the
# speed; dt — wheel 1 at 20 % at half the time step, 2.2e-5 s (sweep_dt.toml; ~2.5 h): how much
# depends on the step; dt4 — the same at a quarter of the step, 1.1e-5 s (sweep_dt4.toml; ~5 h):
# whether it converges; epsdt — wheel 1 at 20 % on the epsdt recipe of the sand (a capped rolling
# spring; sweep_epsdt.toml, its own bed; ~1.5 h with the bed), epsdt_dt — the same at half the step
# (sweep_epsdt_dt.toml; ~2.6 h): whether the wheel converges in the step on a rolling spring as the
# lab's plate does; scm_epsdt — the SCM half on that recipe's lab fit (dsc_epsdt.toml, sheared at the
# lug tips; sweep_scm_epsdt.toml; ~2 min), compared with the epsdt DEM points in comparison_epsdt.md.
# Resumable: a re-run skips
# finished points. Writes here results.csv (DEM), results_<part>.csv (the others), comparison.md
# and comparison.png (the case), comparison_active_domain.md (the check) and
# provenance[_<part>].toml (git hash, command, machine, wall time); finished DEM points are kept in points/ (committed) and restored on the
# next run. Run it in the background: nohup ... &
# --points GLOBS: only these points of each sweep (wheel-sweep --points, e.g. 'wheel1/*/s0.200').
# --tables: run nothing; write the results tables, comparison and provenance from the points
#          finished so far (in runs/ or kept in points/), e.g. beside a sweep still running or after
#          a session's stop killed one. A point still running (no run.h5 yet) is left out.
# --smoke: the CI version (sweep_smoke.toml: a 1.6 m bin, its bed-hold check 0.05 s, one slip, 0.2 s
#          of test phase; about a minute): same pipeline, outputs into --out-dir only (nothing in
#          this folder changes).
set -euo pipefail
# The rest is one brace group, read whole before it runs (common/case.sh says why).
{
source "$(dirname "${BASH_SOURCE[0]}")/../common/case.sh"   # here, root, build_dir, python
smoke=0 tables=0 only="dem,scm" out="" sweep_args=() args=("$@")
while (($#)); do
  case "$1" in
    --smoke) smoke=1; shift ;;
    --only) only=${2:-}; shift 2 ;;
    --out-dir) out=$2; shift 2 ;;
    --force) sweep_args+=(--force); shift ;;
    --points) sweep_args+=(--points "${2:-}"); shift 2 ;;
    --tables) tables=1; shift ;;
    -h|--help) sed -n '2,/^set -euo pipefail/{/^set -euo/!p}' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
# the parts besides dem: sweep_<part>.toml into runs/validation/study_wheels_<part>, results_<part>.csv
parts=(scm scm_tips scm_deep scm_onset scm_onset_tips grain goal active_domain full_domain repeat goal_full goal_repeat goal_wide goal_wide_dt goal_wide_repour allowance wheel_mu speed dt dt4 epsdt epsdt_dt scm_epsdt)
for part in ${only//,/ }; do
  [[ " dem ${parts[*]} " == *" $part "* ]] || {
    echo "run.sh: --only: unknown part '$part' (expected dem ${parts[*]})" >&2; exit 2; }
done
for w in wheel1 wheel5; do
  [[ -f $build_dir/meshes/$w.stl ]] || {
    echo "run.sh: $build_dir/meshes/$w.stl missing: build first (scripts/build.sh)" >&2; exit 2; }
done
# Window: test-phase seconds 2-6 (10 lug passes; the first 2 s are the approach to steady
# sinkage at the new slip); smoke: the second half of its 0.2 s.
window=(--window-start 2.0 --window-end 6.0)
# A part whose wheel turns at another speed averages over the same stretch of bed: its window in
# seconds scaled (sweep_speed.toml: half the speed, 4-12 s).
declare -A part_window=([sweep_speed.toml]="--window-start 4.0 --window-end 12.0")
status=0

# part CONFIG OUT RESULTS PROVENANCE: one sweep, its results table and provenance file. The full
# case keeps its finished DEM points in the committed points/<OUT's name>/ (wheel-sweep --archive;
# README "Resuming across sessions").
part() {
  local config=$1 dir=$2 results=$3 provenance=$4 t0 t0_utc runs rc=0
  local archive=() kept_dir=""
  t0=$(date +%s); t0_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
  # the smoke keeps nothing: its OUT may share a name with the full case's sweep; nor do SCM
  # sweeps (seconds per point, ~2 MB per run file: run them again)
  if ((!smoke)) && ! "$python" -c 'import sys, tomllib
sys.exit(tomllib.load(open(sys.argv[1], "rb")).get("terrain") != "scm")' "$here/$config"; then
    kept_dir=$here/points/${dir##*/}; archive=(--archive "$kept_dir")
  fi
  if ((!tables)); then
    "$root/scripts/wheel-sweep" "$here/$config" --out-dir "$dir" --build-dir "$build_dir" \
      "${archive[@]}" "${sweep_args[@]}" || rc=$?
    stop_if_signalled "$rc" "$config"
    ((rc == 0)) || status=1
  fi
  mapfile -t runs < <(finished_runs "$dir" "$kept_dir")
  ((${#runs[@]})) || { echo "run.sh: no finished run under $dir" >&2; status=1; return 0; }
  mkdir -p "$dir"   # --tables on a machine whose runs/ holds none of them: curves.csv goes there
  table_kept=1   # stays 1 if no table is written
  local win=("${window[@]}")
  [[ -n ${part_window[$config]:-} ]] && read -ra win <<< "${part_window[$config]}"
  if "$root/postprocess/wheelsim-post" curves "${runs[@]}" "${win[@]}" --results "$results.new" \
    --csv "$dir/curves.csv"; then keep_table "$results.new" "$results"; else status=1; fi
  # --tables: the provenance of a table whose rows did not change stays that of the run that made it
  if ((tables && table_kept)); then return 0; fi
  write_provenance "$provenance" validation/study_wheels \
    "validation/study_wheels/run.sh${args[*]:+ }${args[*]}" "$t0_utc" "$t0" "$dir"
}

if ((smoke)); then
  out=${out:-$root/runs/validation/study_wheels_smoke}; sweep_args+=("${smoke_sweep_args[@]}")
  window=(--window-start 0.1 --window-end 0.2)
  part sweep_smoke.toml "$out" "$out/results.csv" "$out/provenance.toml"
  "$python" "$here/compare.py" "$out/results.csv" --md "$out/comparison.md" \
    --png "$out/comparison.png" --window 0.1-0.2 || status=1
  exit $status
fi
[[ -z $out ]] || { echo "run.sh: --out-dir is for --smoke only (the case's sweeps name their bed under runs/validation/study_wheels)" >&2; exit 2; }
runs_dir=$root/runs/validation
wanted() { [[ ,$only, == *,$1,* ]]; }
if wanted dem; then
  part sweep.toml "$runs_dir/study_wheels" "$here/results.csv" "$here/provenance.toml"
fi
for p in "${parts[@]}"; do
  if wanted "$p"; then
    part "sweep_$p.toml" "$runs_dir/study_wheels_$p" "$here/results_$p.csv" "$here/provenance_$p.toml"
  fi
done
if [[ -f $here/results.csv ]]; then
  extra=()
  [[ -f $here/results_scm.csv ]] && extra+=(--scm "$here/results_scm.csv")
  [[ -f $here/results_scm_tips.csv ]] && extra+=(--scm "$here/results_scm_tips.csv")
  [[ -f $here/results_scm_deep.csv ]] && extra+=(--scm "$here/results_scm_deep.csv")
  # each side study's table, if in, under compare.py's option of the part's name (_ -> -)
  for p in grain goal goal_wide goal_wide_dt goal_wide_repour allowance wheel_mu speed dt dt4 \
           epsdt epsdt_dt; do
    [[ -f $here/results_$p.csv ]] && extra+=("--${p//_/-}" "$here/results_$p.csv")
  done
  "$python" "$here/compare.py" "$here/results.csv" "${extra[@]}" \
    --md "$here/comparison.md" --png "$here/comparison.png" || status=1
fi
if [[ -f $here/results_epsdt.csv && -f $here/results_scm_epsdt.csv ]]; then
  # the case on the epsdt recipe: its DEM points against SCM on the recipe's own lab fit
  "$python" "$here/compare.py" "$here/results_epsdt.csv" --scm "$here/results_scm_epsdt.csv" \
    --label sweep_epsdt.toml --md "$here/comparison_epsdt.md" --png "$here/comparison_epsdt.png" || status=1
fi
if [[ -f $here/results_active_domain.csv ]]; then
  extra=()
  [[ -f $here/results_full_domain.csv ]] && extra+=(--full-domain "$here/results_full_domain.csv")
  [[ -f $here/results_repeat.csv ]] && extra+=(--repeat "$here/results_repeat.csv")
  "$python" "$here/compare.py" "$here/results_active_domain.csv" "${extra[@]}" \
    --label sweep_active_domain.toml --md "$here/comparison_active_domain.md" || status=1
fi
if [[ -f $here/results_goal.csv && ( -f $here/results_goal_full.csv || -f $here/results_goal_repeat.csv ) ]]; then
  extra=()
  [[ -f $here/results_goal_full.csv ]] && extra+=(--full-domain "$here/results_goal_full.csv")
  [[ -f $here/results_goal_repeat.csv ]] && extra+=(--repeat "$here/results_goal_repeat.csv")
  [[ -f $here/results_goal_wide.csv ]] && extra+=(--wide "$here/results_goal_wide.csv")
  "$python" "$here/compare.py" "$here/results_goal.csv" "${extra[@]}" \
    --label sweep_goal.toml --md "$here/comparison_goal_active_domain.md" || status=1
fi
exit $status
}
