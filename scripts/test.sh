#!/usr/bin/env bash
# Runs the test suite: installs missing Debian packages, builds, then ctest (every label but long:
# unit and integration, real LIGGGHTS runs under MPI included). Extra arguments go to ctest,
# e.g. `scripts/test.sh -L unit` or `scripts/test.sh -R soilbin`.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}

"$root/scripts/build.sh"
# Tests that run 2 MPI ranks declare PROCESSORS 2, so -j counts them as two slots. Tests labelled
# long (minutes each, kept out of CI's time budget) run only with WHEELSIM_TEST_LONG=1, or
# directly: ctest --test-dir build -L long.
skip_long=(-LE long)
[[ ${WHEELSIM_TEST_LONG:-0} == 1 ]] && skip_long=()
# At the end, the slowest tests of this run (scripts/test_times.py, from ctest's JUnit report):
# CI's budget is 25 min for the whole .ci/run, build included (README "Tests").
junit=$build_dir/Testing/ctest-junit.xml
rm -f "$junit"
start=$(date +%s)
rc=0
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "${skip_long[@]}" \
  --output-junit "$junit" "$@" || rc=$?
if [[ -f $junit ]]; then
  /usr/bin/python3 "$root/scripts/test_times.py" "$junit" --wall "$(($(date +%s) - start))" || true
fi
exit "$rc"
