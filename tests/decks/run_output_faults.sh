#!/usr/bin/env bash
# Output faults (issue 17, item 8): the program against a disk that fills and
# against output paths that are its inputs.
#   run_output_faults.sh EXE PYTHON SOURCE_DIR WORK
#
# 1. -o or -l naming the deck or its .msh: exit 2, the input untouched.
# 2. -l /dev/full (every write fails; gfortran reports none of them): exit 3,
#    "cannot write the listing", the result file's status says the run failed.
# 3. A tmpfs of 18 sizes from 4 kB to 240 kB (root only; skipped with a
#    message where it cannot be mounted), filled by a contact deck that writes
#    20 increments (about 300 kB): every run ends with exit 3 (or 0 when it
#    fits), never a signal or a runtime trace, the failed increment named; the
#    result file, when it can be opened, counts as completed exactly the
#    groups that are complete and readable, and no unreadable group is marked
#    converged (check_output_faults.py reads it through k2d.results).
set -u
exe=$1 py=$2 src=$3 work=$4
deck=$src/tests/decks/contact/v1_plane_q4.dat
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
trace='Fortran runtime|Backtrace|SIGSEGV|Segmentation|internal error'
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
  for kb in 4 8 12 24 36 48 60 72 84 96 112 128 144 160 176 192 208 240; do
    mount -t tmpfs -o size=${kb}k tmpfs "$mnt" || { fail "mount ${kb}k"; continue; }
    err=$("$exe" "$deck" -q -o "$mnt/r.h5" -l "$mnt/r.lis" 2>&1 >/dev/null); rc=$?
    if [ "$rc" != 3 ] && [ "$rc" != 0 ]; then fail "${kb}k: exit $rc, expected 3 ($err)"; fi
    echo "$err" | grep -Eq "$trace" && fail "${kb}k: a runtime trace: $err"
    if [ "$rc" = 3 ]; then
      echo "$err" | grep -Eq 'HDF5|listing|XDMF' || fail "${kb}k: the message does not say what failed: $err"
    fi
    PYTHONPATH=$src/tools "$py" "$src/tests/decks/check_output_faults.py" "$mnt/r.h5" || fail "${kb}k: result file"
    echo "${kb}k: exit $rc: $(echo "$err" | head -1)"
    umount "$mnt"
  done
else
  echo "skipped: the disk-full runs need a tmpfs, which only root can mount here"
fi
[ "$fails" = 0 ] && echo "output faults: all checks passed"
exit $((fails > 0))
