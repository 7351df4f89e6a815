#!/bin/sh
# missing.sh: sh scripts/ff -np N without mpiexec, or without the MPI
# plugin, stops at once with a message that names what is missing (not a
# hang, not FreeFEM's "load" error).
cd "$(dirname "$0")/../.." || exit 2
bin=$(mktemp -d)
trap 'rm -rf "$bin"' EXIT
for c in dirname id mktemp rm cat; do ln -s "$(command -v $c)" "$bin/$c"; done
out=$(PATH="$bin" /bin/sh scripts/ff -np 2 tests/edp/test_patch.edp 2>&1)
rc=$?
[ "$rc" -eq 2 ] && echo "$out" | grep -q "needs mpiexec" || { echo "no mpiexec: exit $rc, '$out'"; exit 1; }
out=$(/bin/sh scripts/ff -np two tests/edp/test_patch.edp 2>&1)
rc=$?
[ "$rc" -eq 2 ] && echo "$out" | grep -q "not 'two'" || { echo "bad -np: exit $rc, '$out'"; exit 1; }
# the MPI plugin missing: a copy of scripts/ff in a tree without build/mpi
mkdir -p "$bin/tree/scripts"
cp scripts/ff scripts/ff-rank "$bin/tree/scripts/"
out=$(/bin/sh "$bin/tree/scripts/ff" -np 2 tests/edp/test_patch.edp 2>&1)
rc=$?
[ "$rc" -eq 2 ] && echo "$out" | grep -q "needs the MPI plugin" || { echo "no plugin: exit $rc, '$out'"; exit 1; }
exit 0
