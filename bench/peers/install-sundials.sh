#!/bin/sh
# SUNDIALS 6 (CVODE, CVODES, IDA, KLU) for the benchmark's peers: the system
# libraries, their headers, and libclang for the bindings sundials-sys
# generates. Only `cd bench && cargo run --release` links them; the test
# command never does.
#
#   sh bench/peers/install-sundials.sh
#
# On Debian, `apt-get install libsundials-dev` brings the headers, but it
# also pulls PETSc, hypre and MPI, which do not install where the system's
# libcurl is newer than the archive's; the headers are then taken from the
# package itself into bench/target/sundials, where bench/.cargo/config.toml
# points sundials-sys.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
export DEBIAN_FRONTEND=noninteractive
apt-get install -y cmake libclang-dev libsuitesparse-dev \
    libsundials-cvode6 libsundials-cvodes6 libsundials-ida6 libsundials-nvecserial6 \
    libsundials-sunlinsol3 libsundials-sunmatrix4
if apt-get install -y libsundials-dev; then
    exit 0
fi
dev=$(mktemp -d)
(cd "$dev" && apt-get download libsundials-dev)
mkdir -p "$here/target/sundials"
dpkg -x "$dev"/libsundials-dev_*.deb "$here/target/sundials"
# The development links point at the runtime libraries installed above.
lib="$here/target/sundials/usr/lib/x86_64-linux-gnu"
for link in "$lib"/*.so; do
    ln -sf "/usr/lib/x86_64-linux-gnu/$(readlink "$link")" "$link"
done
rm -rf "$dev"
echo "SUNDIALS headers in $here/target/sundials"
