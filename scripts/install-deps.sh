#!/usr/bin/env bash
# Installs the Debian 12 packages wheelsim needs, if any is missing (apt-get update, then
# apt-get install --no-install-recommends: the `liggghts` package would otherwise pull ParaView).
# Run as root, or as a user with sudo. Safe to re-run: does nothing when all are present.
set -euo pipefail

packages=(
  # toolchain
  g++ make cmake git ca-certificates
  # the C++ format check (format.check; Debian 12: clang-format 14)
  clang-format
  # the sanitizer tier's compiler (tests/sanitize/run_sanitize.cmake: a third less CPU than g++)
  # and its ASan/UBSan runtime (only recommended by clang: --no-install-recommends skips it)
  clang libclang-rt-dev
  # LIGGGHTS 3.8 (library, headers, and Debian's own binary for reference runs) and MPI
  liggghts libliggghts-dev libopenmpi-dev openmpi-bin
  # C++ libraries
  libeigen3-dev libassimp-dev libzmq3-dev cppzmq-dev libhdf5-dev libgtest-dev
  libtomlplusplus-dev libcli11-dev
  # post-processing (Debian's interpreter and modules; no PyPI)
  python3 python3-numpy python3-h5py python3-matplotlib
  # the sweep driver writes rig configs with a real TOML writer
  python3-tomli-w
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} Debian packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: not root and no sudo; as root run:" >&2
  echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update
"${as_root[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
