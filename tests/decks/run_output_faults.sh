#!/usr/bin/env bash
# Output faults (issue 17, item 8): the program against a disk that fills and
# against output paths that are its inputs.
#   run_output_faults.sh EXE PYTHON SOURCE_DIR WORK
#
# 1. -o or -l naming the deck or its .msh: exit 2, the input untouched.
# 2. -l /dev/full (every write fails; gfortran reports none of them): exit 3,
#    "cannot write the listing", the result file's status says the run failed.
# 3. A tmpfs of 30 sizes from 8 kB to 1.9 MB (root only; skipped with a
#    message where it cannot be mounted), filled by a contact deck that writes
#    20 increments (about 300 kB beside a 1 MB reserve): every run ends with
#    exit 3 (or 0 when it fits), never a signal or a runtime trace, the
#    failure named; the result file, when there is one, opens, counts as
#    completed exactly the groups that are complete and readable, marks no
#    unreadable group converged, and (exit 3) its status says where the run
#    failed: at set-up or at the increment after the last complete one
#    (check_output_faults.py reads it through k2d.results); no reserve file
#    is left.  The sizes cover every stage: no room for the reserve, for the
#    mesh, for an increment, for the listing or the XDMF file, and none.
set -u
exe=$1 py=$2 src=$3 work=$4
deck=$src/tests/decks/contact/v1_plane_q4.dat
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
trace='Fortran runtime|Backtrace|SIGSEGV|Segmentation|internal error|HDF5-DIAG'
# a tmpfs left mounted by an interrupted run would make the clean-up fail
umount "$work/output_faults/mnt" 2>/dev/null
rm -rf "$work/output_faults" && mkdir -p "$work/output_faults" && cd "$work/output_faults" || exit 1
trap 'umount "$work/output_faults/mnt" 2>/dev/null' EXIT

# 1. outputs that are inputs
cp "$src/tests/gmsh/strip22.dat" "$src/tests/gmsh/strip22.msh" .
sum0=$(cat strip22.dat strip22.msh | md5sum)
for args in "-o strip22.dat" "-o ./strip22.msh" "-o x.h5 -l strip22.dat"; do
  # shellcheck disable=SC2086
  err=$("$exe" strip22.dat -q $args 2>&1 >/dev/null); rc=$?
  [ "$rc" = 2 ] || fail "$args: exit $rc, expected 2"
  echo "$err" | grep -Eq 'is the (input deck|mesh file of the deck): give another path' || fail "$args: message: $err"
done
[ "$(cat strip22.dat strip22.msh | md5sum)" = "$sum0" ] || fail "an input file was overwritten"
cp strip22.dat strip22.h5
err=$("$exe" strip22.h5 -q 2>&1 >/dev/null); rc=$?
[ "$rc" = 2 ] || fail "deck strip22.h5 with the default result name: exit $rc, expected 2 ($err)"

# 2. a listing that cannot be written
if [ -w /dev/full ]; then
  err=$("$exe" "$deck" -q -o full_listing.h5 -l /dev/full 2>&1 >/dev/null); rc=$?
  [ "$rc" = 3 ] || fail "-l /dev/full: exit $rc, expected 3 ($err)"
  echo "$err" | grep -q 'cannot write the listing /dev/full' || fail "-l /dev/full: message: $err"
  echo "$err" | grep -Eq "$trace" && fail "-l /dev/full: a runtime trace: $err"
  PYTHONPATH=$src/tools "$py" "$src/tests/decks/check_output_faults.py" full_listing.h5 --failed || fail "-l /dev/full: result file"
else
  echo "skipped: /dev/full is not writable"
fi

# 3. a disk that fills
mnt=$work/output_faults/mnt
mkdir -p "$mnt"
if [ "$(id -u)" = 0 ] && mount -t tmpfs -o size=64k tmpfs "$mnt" 2>/dev/null; then
  umount "$mnt"
  stages=""
  for kb in 8 24 48 72 240 1000 1024 1040 1100 1200 1280 1290 1300 1310 1320 1340 1360 1400 1440 1480 1520 1560 1600 \
            1640 1680 1720 1760 1800 1850 1900; do
    mount -t tmpfs -o size=${kb}k tmpfs "$mnt" || { fail "mount ${kb}k"; continue; }
    err=$("$exe" "$deck" -q -o "$mnt/r.h5" -l "$mnt/r.lis" 2>&1 >/dev/null); rc=$?
    # the deck completes with doubts (exit 4: its law drift) when the disk has room
    if [ "$rc" != 3 ] && [ "$rc" != 4 ]; then fail "${kb}k: exit $rc, expected 3 or 4 ($err)"; fi
    echo "$err" | grep -Eq "$trace" && fail "${kb}k: a runtime trace: $err"
    if [ "$rc" = 3 ]; then
      echo "$err" | grep -Eq 'HDF5|listing|XDMF|no room on the disk' || fail "${kb}k: the message does not say what failed: $err"
      [ -e "$mnt/r.h5" ] || echo "$err" | grep -q 'r.h5.reserve' || fail "${kb}k: no result file, and no word of the reserve: $err"
      for w in 'reserve (' 'the mesh' 'the results of increment' 'listing' 'XDMF'; do
        echo "$err" | grep -q "$w" && stages="$stages|$w"
      done
    fi
    PYTHONPATH=$src/tools "$py" "$src/tests/decks/check_output_faults.py" "$mnt/r.h5" --exit "$rc" || fail "${kb}k: result file"
    echo "${kb}k: exit $rc: $(echo "$err" | grep -v 'is doubtful' | head -1)"
    umount "$mnt"
  done
  # the sizes must reach the stages they are there for (a change of the file's size moves them)
  for w in 'reserve (' 'the mesh' 'the results of increment'; do
    echo "$stages" | grep -q "$w" || fail "no size ended the run at: $w"
  done
  [ "$rc" = 4 ] || fail "the largest size did not complete the run (exit $rc)"
else
  echo "skipped: the disk-full runs need a tmpfs, which only root can mount here"
fi
[ "$fails" = 0 ] && echo "output faults: all checks passed"
exit $((fails > 0))
