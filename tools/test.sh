#!/usr/bin/env bash
# Kontakt2D: the whole test suite in one command.
#   tools/test.sh [ctest options]          (BUILD_TYPE=Debug tools/test.sh for the Debug build,
#                                           K2D_MPI=1 tools/test.sh for the MPI build in build-mpi/,
#                                           K2D_SANITIZE=1 for AddressSanitizer and UBSan in build-<type>-asan/)
# Installs missing Debian packages, builds, and runs every test through ctest;
# the last lines are ctest's summary.
set -euo pipefail
source "$(dirname "$0")/setup.sh"

type=${BUILD_TYPE:-Release}
dir="$K2D_ROOT/build"
[ "$type" != "Release" ] && dir="$K2D_ROOT/build-$(echo "$type" | tr '[:upper:]' '[:lower:]')"
[ "$K2D_MPI" = 1 ] && dir="$dir-mpi"
[ "$K2D_SANITIZE" = 1 ] && dir="$dir-asan"

k2d_ensure_packages
k2d_build "$type" "$dir"
cd "$dir"
exec ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
