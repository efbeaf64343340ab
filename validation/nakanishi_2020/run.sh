#!/usr/bin/env bash
# Validation case 1 — Nakanishi et al. 2020 lugged wheel, DEM code-to-code (README.md).
#
#   validation/nakanishi_2020/run.sh [--cdt | --smoke | --sensitivity [--only NAMES] | --scm]
#                                    [--out-dir DIR] [--jobs N] [--force]
#
# The case (no option): the published soil with the published rolling resistance, Yade's rolling
# spring krot 5e-5 N m/rad without a cap (wheelsim's rolling_friction krot,
# nakanishi_2020_krot.in), at the 8 published slips (sweep.toml): prepares its 78 577-sphere bin
# once, runs the points through wheel-sweep (resumable: a re-run skips finished points; one rank
# per point, two points at a time), then writes into this folder results.csv, comparison.png (the
# cdt mapping's curve in grey), comparison.md, curves.csv and provenance.toml (git hash, command,
# machine, wall time). About 2 h on 2 cores (README "Cost"). Run it in the background: nohup ... &
# Its runs go to runs/validation/nakanishi_2020/sensitivity/krot (the curve first ran there as a
# sensitivity; the folder is kept so that its finished points resume).
# --cdt: the same 8 slips with the rolling resistance mapped on LIGGGHTS' cdt, mu_r 0.05
#          (sweep_cdt.toml; the case's answer until 2026-11-28, kept as the mapping's record) on a
#          bin of its own: results_cdt.csv, comparison_cdt.png/md, curves_cdt.csv and
#          provenance_cdt.toml here; runs in runs/validation/nakanishi_2020.
# --sensitivity: only the sensitivity sweeps: on the cdt sweep's bed (run --cdt first): time
#          step halved at 35.42 % (sweep_dt.toml) against the same point repeated on that bed
#          (sweep_bed_repeat.toml), the published 3.25 s test phase at 77.97-86.8 %
#          (sweep_window.toml); each on its own bed: the rolling friction mu_r 0 and 0.1 at
#          35.42 % (sweep_mur.toml), a bed poured frictionless at 35.42 % (sweep_pour_mu0.toml),
#          the grain size: every diameter x 1.25 and x 0.8 at 35.42 % (sweep_grain_x1.25.toml,
#          sweep_grain_x0.8.toml; the x 0.8 point ~2.5 x a main point), a frictionless box
#          (wall_mu 0) at 35.42 % (sweep_wallmu0.toml) — all these with cdt — and with krot: on
#          the case's bed (run the case first) the time step halved at 35.42 %
#          (sweep_krot_dt.toml) and the published 3.25 s test phase at 77.97-86.8 %
#          (sweep_krot_window.toml), on a bed of its own spheres x 1.25 at 35.42 %
#          (sweep_krot_x1.25.toml); writes results_<name>.csv, comparison_<name>.md and
#          provenance_<name>.toml here.
#          --only NAMES: just these, comma-separated from bed_repeat, dt_0.6e-4, window_3.25,
#          krot_dt_0.6e-4, krot_window_3.25, mur, pour_mu0, grain_x1.25, grain_x0.8, wall_mu0,
#          krot_x1.25 (the last six prepare their own beds).
# --scm: the SCM half (sweep_scm.toml: the same rig on the SCM soil the soil lab fitted to the
#          cdt DEM soil, inputs/scm_soils/from_dem/nakanishi_2020.toml; seconds per point):
#          writes results_scm.csv, comparison_scm.md/png (against the cdt DEM curve, the soil it
#          was fitted to) and provenance_scm.toml here.
# --smoke: the CI version (the krot soil on a 0.40 m bin, its bed-hold check 0.05 s, one slip,
#          0.3 s of test phase; minutes): same pipeline, outputs into --out-dir only (nothing in
#          this folder changes).
set -euo pipefail
# The rest is one brace group, read whole before it runs (common/case.sh says why).
{
source "$(dirname "${BASH_SOURCE[0]}")/../common/case.sh"   # here, root, build_dir, python
# The sensitivity sweeps: on the cdt sweep's bed, on the case's (krot) bed, and on beds of their
# own (NAME:CONFIG, run one after the other, window test seconds 1.0-2.4). --only takes a subset
# of the names.
main_bed_sensitivities="bed_repeat,dt_0.6e-4,window_3.25"
krot_bed_sensitivities="krot_dt_0.6e-4,krot_window_3.25"
own_bed_sweeps=(mur:sweep_mur.toml pour_mu0:sweep_pour_mu0.toml grain_x1.25:sweep_grain_x1.25.toml
                grain_x0.8:sweep_grain_x0.8.toml wall_mu0:sweep_wallmu0.toml
                krot_x1.25:sweep_krot_x1.25.toml)
own_bed_names=$(IFS=,; echo "${own_bed_sweeps[*]%%:*}")
sensitivities="$main_bed_sensitivities,$krot_bed_sensitivities,$own_bed_names"
smoke=0 cdt=0 sensitivity=0 scm=0 only=$sensitivities out="" sweep_args=() args=("$@")
while (($#)); do
  case "$1" in
    --smoke) smoke=1; shift ;;
    --cdt) cdt=1; shift ;;
    --sensitivity) sensitivity=1; shift ;;
    --scm) scm=1; shift ;;
    --only) only=${2:-}; shift 2 ;;
    --out-dir) out=$2; shift 2 ;;
    --jobs|-j) sweep_args+=(--jobs "$2"); shift 2 ;;
    --force) sweep_args+=(--force); shift ;;
    -h|--help) sed -n '2,/^set -euo pipefail/{/^set -euo/!p}' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
((smoke + cdt + sensitivity + scm > 1)) && { echo "run.sh: --smoke, --cdt, --sensitivity and --scm exclude each other" >&2; exit 2; }
runs_dir=$root/runs/validation/nakanishi_2020   # the cdt sweep's; its bed serves three sensitivities
if ((smoke)); then config=$here/sweep_smoke.toml; out=${out:-${runs_dir}_smoke}; sweep_args+=("${smoke_sweep_args[@]}")
elif ((scm)); then config=$here/sweep_scm.toml; out=${out:-${runs_dir}_scm}
elif ((cdt || sensitivity)); then config=$here/sweep_cdt.toml; out=${out:-$runs_dir}
else config=$here/sweep.toml; out=${out:-$runs_dir/sensitivity/krot}; fi
[[ -f $build_dir/meshes/nakanishi_2020.stl ]] || {
  echo "run.sh: $build_dir/meshes/nakanishi_2020.stl missing: build first (scripts/build.sh)" >&2; exit 2; }

start=$(date +%s)
started_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
status=0
if ((scm)); then  # the SCM half runs the main path below with its own outputs (tag _scm)
  soil=$root/inputs/scm_soils/from_dem/nakanishi_2020.toml
  [[ -f $soil ]] || { echo "run.sh: --scm needs $soil: soil_lab/soil-lab run nakanishi_2020 ... then soil-lab scm (README.md \"DEM against SCM on the same soil\")" >&2; exit 2; }
  [[ -f $here/results_cdt.csv ]] || { echo "run.sh: --scm compares with the cdt DEM curve its soil was fitted to, $here/results_cdt.csv: run.sh --cdt first" >&2; exit 2; }
fi
if ((sensitivity)); then
  # sens NAME CONFIG WINDOW_START WINDOW_END: one sensitivity sweep into $out/sensitivity/NAME and
  # its results_NAME.csv / comparison_NAME.md / provenance_NAME.toml here (window in test-phase
  # seconds)
  sens() {
    local name=$1 config=$2 w0=$3 w1=$4 runs t0 t0_utc rc=0
    t0=$(date +%s); t0_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
    "$root/scripts/wheel-sweep" "$here/$config" --out-dir "$out/sensitivity/$name" \
      --build-dir "$build_dir" "${sweep_args[@]}" || rc=$?
    stop_if_signalled "$rc" "$config"
    mapfile -t runs < <(finished_runs "$out/sensitivity/$name")
    ((${#runs[@]})) || { echo "run.sh: no finished run under $out/sensitivity/$name" >&2; return 1; }
    "$root/postprocess/wheelsim-post" curves "${runs[@]}" --window-start "$w0" --window-end "$w1" \
      --results "$here/results_$name.csv.new" --csv "$out/sensitivity/$name/curves.csv"
    keep_table "$here/results_$name.csv.new" "$here/results_$name.csv"
    "$python" "$here/compare.py" "$here/results_$name.csv" "$here/reference.csv" --r-eff 0.11 \
      --md "$here/comparison_$name.md"
    write_provenance "$here/provenance_$name.toml" validation/nakanishi_2020 \
      "validation/nakanishi_2020/run.sh${args[*]:+ }${args[*]}" "$t0_utc" "$t0" \
      "$out/sensitivity/$name"
    return $rc
  }
  wanted() { [[ ,$only, == *,$1,* ]]; }
  for name in ${only//,/ }; do
    [[ ,$sensitivities, == *,$name,* ]] || {
      echo "run.sh: --only: unknown sensitivity '$name' (expected ${sensitivities//,/, })" >&2; exit 2; }
  done
  # the sensitivity sweeps name the cdt sweep's bed under the default runs directory
  [[ $out == "$runs_dir" ]] || {
    echo "run.sh: --sensitivity runs in the default runs directory (its sweeps name the cdt sweep's bed there): leave out --out-dir" >&2; exit 2; }
  if wanted bed_repeat || wanted dt_0.6e-4 || wanted window_3.25; then
    [[ -f $out/beds/nakanishi_bin/soilbin_nakanishi_2020.restart ]] || {
      echo "run.sh: bed_repeat, dt_0.6e-4 and window_3.25 run on the cdt sweep's bed, $out/beds/nakanishi_bin/soilbin_nakanishi_2020.restart: run.sh --cdt first (or --only $own_bed_names)" >&2; exit 2; }
  fi
  # the two one-point sweeps side by side (one rank each), then the three window points
  pids=()
  if wanted bed_repeat; then sens bed_repeat sweep_bed_repeat.toml 1.0 2.4 & pids+=($!); fi
  if wanted dt_0.6e-4; then sens dt_0.6e-4 sweep_dt.toml 1.0 2.4 & pids+=($!); fi
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
  if wanted window_3.25; then sens window_3.25 sweep_window.toml 1.0 3.25 || status=1; fi
  if wanted krot_dt_0.6e-4 || wanted krot_window_3.25; then
    krot_bed=$out/sensitivity/krot/beds/krot/soilbin_nakanishi_2020_krot.restart
    if [[ -f $krot_bed ]]; then
      if wanted krot_dt_0.6e-4; then sens krot_dt_0.6e-4 sweep_krot_dt.toml 1.0 2.4 || status=1; fi
      if wanted krot_window_3.25; then
        sens krot_window_3.25 sweep_krot_window.toml 1.0 3.25 || status=1
      fi
    else
      echo "run.sh: krot_dt_0.6e-4 and krot_window_3.25 run on the case's bed, $krot_bed: run the case first" >&2
      status=1
    fi
  fi
  for entry in "${own_bed_sweeps[@]}"; do
    if wanted "${entry%%:*}"; then sens "${entry%%:*}" "${entry#*:}" 1.0 2.4 || status=1; fi
  done
  exit $status
fi
"$root/scripts/wheel-sweep" "$config" --out-dir "$out" --build-dir "$build_dir" "${sweep_args[@]}" || status=$?
stop_if_signalled "$status" "$config"
# results of every finished point (a failed point is reported by wheel-sweep and left out)
mapfile -t runs < <(finished_runs "$out")
((${#runs[@]})) || { echo "run.sh: no finished run under $out" >&2; exit 1; }
# Window: test-phase seconds 1.0 .. end (the first second is the approach to steady sinkage, as
# the published runs average after 1 s of driving); smoke: the second half of its 0.3 s.
# --cdt and --scm: the same window, tables tagged _cdt / _scm beside the case's; the SCM half is
# compared with the cdt curve (its soil was fitted to that DEM soil), the case with the cdt curve
# in grey.
tag="" mode="" dest=$here curves=$here/curves.csv window=(--window-start 1.0 --window-end 2.4)
dem=$here/results.csv extra=()
if ((smoke)); then
  window=(--window-start 0.15 --window-end 0.3) dest=$out curves=$out/curves.csv mode=" --smoke"
  dem=$out/results.csv
elif ((cdt)); then
  tag=_cdt mode=" --cdt" curves=$here/curves_cdt.csv dem=$here/results_cdt.csv
elif ((scm)); then
  tag=_scm mode=" --scm" curves=$out/curves.csv dem=$here/results_cdt.csv
  extra=(--scm "$here/results_scm.csv")
else
  extra=(--label "wheelsim (krot)")
  if [[ -f $here/results_cdt.csv ]]; then
    extra+=(--also "wheelsim, cdt μr 0.05 (mapping)=$here/results_cdt.csv")
  fi
fi
"$root/postprocess/wheelsim-post" curves "${runs[@]}" "${window[@]}" \
  --results "$dest/results$tag.csv.new" --csv "$curves"
keep_table "$dest/results$tag.csv.new" "$dest/results$tag.csv"
"$python" "$here/compare.py" "$dem" "$here/reference.csv" --r-eff 0.11 "${extra[@]}" \
  --png "$dest/comparison$tag.png" --md "$dest/comparison$tag.md"
write_provenance "$dest/provenance$tag.toml" validation/nakanishi_2020 \
  "validation/nakanishi_2020/run.sh$mode" "$started_utc" "$start" "$out"
exit $status
}
