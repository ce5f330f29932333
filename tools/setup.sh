# Shared set-up for tools/run.sh and tools/test.sh (sourced, not run).
# Installs the Debian packages Kontakt2D needs when any is missing, and
# configures and builds the project with CMake.

K2D_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
K2D_PACKAGES="gfortran gcc make cmake liblapack-dev libblas-dev libopenblas-dev libsuitesparse-dev \
libmumps-seq-dev libmetis-dev libhdf5-dev hdf5-tools gmsh python3 python3-h5py python3-numpy python3-matplotlib"
# K2D_MPI=1: the MPI build instead (cmake -DKONTAKT2D_MPI=ON, in build-mpi/; docs/parallel.md),
# with the MPI MUMPS and OpenMPI.
K2D_MPI=${K2D_MPI:-0}
# K2D_SANITIZE=1: AddressSanitizer and UBSan in every target (cmake -DKONTAKT2D_SANITIZE=ON;
# tools/test.sh builds it in build-<type>-asan/).
K2D_SANITIZE=${K2D_SANITIZE:-0}
[ "$K2D_MPI" = 1 ] && K2D_PACKAGES="$K2D_PACKAGES libmumps-dev libopenmpi-dev openmpi-bin"
# Python tools run on Debian's interpreter with Debian's packages.
K2D_PYTHON=/usr/bin/python3

k2d_log() { printf '[kontakt2d] %s\n' "$*" >&2; }

# Install missing Debian packages (apt-get update first), as root or via sudo.
k2d_ensure_packages() {
  local missing=() p
  for p in $K2D_PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
      k2d_log "missing Debian packages: ${missing[*]}"
      k2d_log "run as root (or install them) and try again"; return 1
    fi
  fi
  k2d_log "installing Debian packages: ${missing[*]}"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q >&2
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
}

# Configure (once) and build.  $1 = build type (Release or Debug), $2 = build dir.
k2d_build() {
  local type=${1:-Release} dir=${2:-$K2D_ROOT/build}
  local mpi=""
  [ "$K2D_MPI" = 1 ] && mpi="-DKONTAKT2D_MPI=ON"
  [ "$K2D_SANITIZE" = 1 ] && mpi="$mpi -DKONTAKT2D_SANITIZE=ON"
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    k2d_log "configuring $type build in $dir ${mpi}"
    cmake -S "$K2D_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE="$type" $mpi >&2
  fi
  k2d_log "building"
  cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)" >&2
}

# Make the .msh that a deck's MESH block names, when it is missing and a .geo
# of the same base name lies beside it (gmsh -2 -format msh41).  $1 = deck.
k2d_mesh_deck() {
  local deck=$1 dir msh geo
  dir=$(dirname "$deck")
  # the GMSH card: keyword in columns 1-10, the path from column 11 (comments dropped)
  msh=$(sed -n 's/#.*//; /^[Gg][Mm][Ss][Hh] /{s/^.\{10\}//; s/^ *//; s/ *$//; p; q}' "$deck")
  [ -z "$msh" ] && return 0
  case "$msh" in /*) ;; *) msh="$dir/$msh" ;; esac
  [ -f "$msh" ] && return 0
  geo="${msh%.*}.geo"
  if [ ! -f "$geo" ]; then
    k2d_log "the deck's mesh $msh is missing, and there is no $geo to make it from"
    return 1
  fi
  if ! command -v gmsh >/dev/null 2>&1; then
    k2d_log "gmsh is needed to make $msh from $geo"; return 1
  fi
  k2d_log "meshing $geo -> $msh"
  gmsh -2 -format msh41 "$geo" -o "$msh" >/dev/null
}
