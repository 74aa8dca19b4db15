#!/bin/sh
# setup.sh - the one set-up command on a fresh Debian 12 machine (run as root):
#   installs the Debian packages vres needs that are not installed yet, builds everything,
#   and runs the demo pipeline (cases -> stores -> VTK series under demo/).
#   ./setup.sh --deps-only   only installs the missing packages.
set -eu
cd "$(dirname "$0")"
PKGS="build-essential pkg-config libhdf5-dev hdf5-tools libxml2-dev libvtk9-dev libopenmpi-dev openmpi-bin
libfftw3-dev parallel gnuplot-nox check git python3-h5py python3-numpy clang libclang-rt-dev libomp-dev"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="$missing $p"
done
if [ -n "$missing" ]; then
    echo "setup: installing:$missing"
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO apt-get update -q
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends $missing
else
    echo "setup: all Debian packages present"
fi
[ "${1:-}" = "--deps-only" ] && exit 0
make -j"$(nproc)"
make demo
echo "setup: done; open demo/vtk/*.pvd in ParaView"
