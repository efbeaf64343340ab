# Sourced first by validation/<case>/run.sh: sets here (the case's folder), root (the checkout),
# build_dir ($WHEELSIM_BUILD_DIR, else <root>/build) and python (Debian's, with numpy, h5py and
# matplotlib), and brings write_provenance (provenance.sh).
here=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)
root=$(cd "$here/../.." && pwd)
build_dir=${WHEELSIM_BUILD_DIR:-$root/build}
python=/usr/bin/python3
source "$root/validation/common/provenance.sh"
