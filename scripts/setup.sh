#!/bin/sh
# setup.sh: installs the Debian packages the project needs, only those that
# are missing (idempotent; needs root or sudo when something is missing).
PKGS="freefem++ libfreefem++-dev libsuitesparse-dev gmsh libopenblas0-pthread \
gnuplot-nox libcmocka-dev liblapack-dev make gcc g++ clang libclang-rt-14-dev valgrind \
libmumps-dev libscalapack-openmpi-dev openmpi-bin libopenmpi-dev libpetsc-real-dev"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
        || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "setup: installing$missing"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || exit 1
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null || exit 1
echo "setup: done"
