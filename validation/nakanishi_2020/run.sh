#!/usr/bin/env bash
# Validation case 1 — Nakanishi et al. 2020 lugged wheel, DEM code-to-code (README.md).
#
#   validation/nakanishi_2020/run.sh [--smoke] [--out-dir DIR] [--jobs N] [--force]
#
# Full case: prepares the 80 000-sphere bin once, runs the 8 published slips through wheel-sweep
# (resumable: a re-run skips finished points), then writes into this folder results.csv,
# comparison.png, comparison.md and provenance.toml (git hash, command, machine, wall time).
# About 1 h on 2 cores (README "Cost"). Run it in the background: nohup ... &
# --smoke: the CI version (a 0.40 m bin, one slip, 0.3 s of test phase; minutes): same pipeline,
#          outputs into --out-dir only (nothing in this folder changes).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
source "$root/validation/common/provenance.sh"
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}
python=/usr/bin/python3
smoke=0 out="" sweep_args=()
while (($#)); do
  case "$1" in
    --smoke) smoke=1; shift ;;
    --out-dir) out=$2; shift 2 ;;
    --jobs|-j) sweep_args+=(--jobs "$2"); shift 2 ;;
    --force) sweep_args+=(--force); shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
if ((smoke)); then config=$here/sweep_smoke.toml; out=${out:-$root/runs/validation/nakanishi_2020_smoke}
else config=$here/sweep.toml; out=${out:-$root/runs/validation/nakanishi_2020}; fi
[[ -f $build_dir/meshes/nakanishi_2020.stl ]] || {
  echo "run.sh: $build_dir/meshes/nakanishi_2020.stl missing: build first (scripts/build.sh)" >&2; exit 2; }

start=$(date +%s)
started_utc=$(date -u +%Y-%m-%dT%H:%M:%SZ)
status=0
"$root/scripts/wheel-sweep" "$config" --out-dir "$out" --build-dir "$build_dir" "${sweep_args[@]}" || status=$?
# results of every finished point (a failed point is reported by wheel-sweep and left out)
mapfile -t runs < <(find "$out" -mindepth 4 -name run.h5 -not -path "*/beds/*" | sort)
((${#runs[@]})) || { echo "run.sh: no finished run under $out" >&2; exit 1; }
# Window: test-phase seconds 1.0 .. end (the first second is the approach to steady sinkage, as
# the published runs average after 1 s of driving); smoke: the second half of its 0.3 s.
if ((smoke)); then window=(--window-start 0.15 --window-end 0.3); dest=$out
else window=(--window-start 1.0 --window-end 2.4); dest=$here; fi
"$root/postprocess/wheelsim-post" curves "${runs[@]}" "${window[@]}" --results "$dest/results.csv" \
  --csv "$dest/curves.csv"
"$python" "$here/compare.py" "$dest/results.csv" "$here/reference.csv" --r-eff 0.11 \
  --png "$dest/comparison.png" --md "$dest/comparison.md"
write_provenance "$dest/provenance.toml" validation/nakanishi_2020 \
  "validation/nakanishi_2020/run.sh$( ((smoke)) && echo " --smoke" )" \
  "$started_utc" "$start" "$out"
exit $status
