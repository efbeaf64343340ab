#!/usr/bin/env bash
# Configures and builds wheelsim (Release) into build/ — or $WHEELSIM_BUILD_DIR — after making sure
# the Debian packages are installed. Extra arguments go to cmake's configure step.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}

"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build_dir" -j "$(nproc)"
