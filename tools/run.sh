#!/usr/bin/env bash
# Kontakt2D: the main job in one command.
#   tools/run.sh [DECK] [kontakt2d options] [--pairs LIST] [--increments LIST] [--approach-nodes A,B]
#                [--loop-pairs LIST]
# Installs missing Debian packages, builds (Release) if needed, solves DECK
# (default: inputs/punch_5_1.dat, the paper's example 5.1 with Coulomb friction
# 0.2 -- Table 1, column 2, and Table 2 -- on the cheapest model within 1 % of a
# converged reference), writes the HDF5 results,
# the listing and a plot into results/<deck name>/ and says where they are; for a history
# with contact also the history plots (docs/history.md): for a cyclic deck such as
# inputs/joint_cycle.dat the shear-slip loops (<name>_loops.png) and, where the result file has
# periodic histories (/cycles), the energy per cycle against the amplitude (<name>_energy.png).
# A deck whose MESH block names a missing .msh gets it made by gmsh from the
# .geo of the same name beside it.
set -euo pipefail
source "$(dirname "$0")/setup.sh"

deck=${1:-$K2D_ROOT/inputs/punch_5_1.dat}
[ $# -gt 0 ] && shift
k2d_args=()
plot_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --pairs|--increments|--approach-nodes|--loop-pairs)
      if [ $# -lt 2 ]; then k2d_log "$1 needs a value"; exit 2; fi
      plot_args+=("$1" "$2"); shift 2 ;;
    --pairs=*|--increments=*|--approach-nodes=*|--loop-pairs=*) plot_args+=("$1"); shift ;;
    *) k2d_args+=("$1"); shift ;;
  esac
done
if [ ! -f "$deck" ]; then k2d_log "no such deck: $deck"; exit 2; fi

k2d_ensure_packages
k2d_build Release "$K2D_ROOT/build"
k2d_mesh_deck "$deck"

name=$(basename "${deck%.*}")
out="$K2D_ROOT/results/$name"
mkdir -p "$out"
rc=0
"$K2D_ROOT/build/kontakt2d" "$deck" -o "$out/$name.h5" "${k2d_args[@]}" || rc=$?
# exit code 4: completed with doubts (the increments and pairs are named above): the results
# are complete, so they are plotted, and the code is passed on
[ "$rc" = 0 ] || [ "$rc" = 4 ] || exit "$rc"
"$K2D_PYTHON" "$K2D_ROOT/tools/plot_results.py" "$out/$name.h5" -o "$out/$name.png"
rm -f "$out/${name}"_{approach,pairs,interface,slip,loops,energy}.png "$out/${name}_stages.md"
"$K2D_PYTHON" "$K2D_ROOT/tools/plot_history.py" "$out/$name.h5" --stages-file "$out/${name}_stages.md" "${plot_args[@]}"
echo "results: $out/$name.h5 (HDF5), $out/$name.xdmf (for ParaView), $out/$name.lis (listing), $out/$name.png (plot)"
# a deck with a pretension section (LOADS/PRETENSION): the joint diagram, the pressure cone and the
# joint's figures (docs/bolts.md)
if grep -qiE '^[[:space:]]*PRETENSION' "$deck"; then
  rm -f "$out/${name}"_{joint,cone}.png "$out/${name}_joint.md"
  "$K2D_PYTHON" "$K2D_ROOT/tools/plot_joint.py" "$out/$name.h5" -o "$out/$name" > /dev/null
  echo "joint: $out/${name}_joint.png (joint diagram), $out/${name}_cone.png (pressure cone), $out/${name}_joint.md"
fi
exit "$rc"
