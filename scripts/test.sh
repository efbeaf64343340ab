#!/usr/bin/env bash
# Runs the whole test suite: installs missing Debian packages, builds, then ctest (all labels:
# unit and integration, real LIGGGHTS runs under MPI included). Extra arguments go to ctest,
# e.g. `scripts/test.sh -L unit` or `scripts/test.sh -R soilbin`.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}

"$root/scripts/build.sh"
# Tests that run 2 MPI ranks declare PROCESSORS 2, so -j counts them as two slots.
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "$@"
