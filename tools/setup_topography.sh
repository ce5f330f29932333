#!/usr/bin/env bash
# The virtual environment of `tools/calibrate.py topography` (docs/calibration.md, "From a
# measured surface"): Debian's /usr/bin/python3 -m venv with the pinned wheels of
# tools/requirements-topography.txt (SurfaceTopography, ContactMechanics, numpy, scipy, ...).
#   tools/setup_topography.sh            create or update it; prints its python on stdout
# K2D_TOPOGRAPHY_VENV chooses the folder (default build/venv-topography under the source root).
# Nothing is installed unless the requirements changed since the last installation (a copy of
# them is kept in the environment).  Needs python3-venv and access to PyPI (about 60 MB, 1 min).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
req="$root/tools/requirements-topography.txt"
venv=${K2D_TOPOGRAPHY_VENV:-$root/build/venv-topography}
log() { printf '[kontakt2d] %s\n' "$*" >&2; }
if [ -x "$venv/bin/python" ] && cmp -s "$req" "$venv/k2d-requirements.txt"; then
  echo "$venv/bin/python"; exit 0
fi
log "creating the topography environment in $venv (pinned wheels from PyPI, about a minute)"
mkdir -p "$(dirname "$venv")"
if ! /usr/bin/python3 -m venv "$venv" >&2; then
  log "cannot create a virtual environment: install Debian's python3-venv"; exit 1
fi
if ! "$venv/bin/pip" install -q --disable-pip-version-check --only-binary=:all: -r "$req" >&2; then
  log "pip could not install $req into $venv (network? a wheel missing for this Python?)"; exit 1
fi
"$venv/bin/python" -c "import SurfaceTopography, ContactMechanics, numpy, scipy, matplotlib, h5py" >&2
cp "$req" "$venv/k2d-requirements.txt"
log "topography environment ready: $venv"
echo "$venv/bin/python"
