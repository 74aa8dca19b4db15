#!/usr/bin/env bash
# vres-vtk on bad input, under AddressSanitizer: each case gets one clear message naming the
# culprit, exit 1 (2 for usage errors), and nothing new under the output (not even a
# temporary, nor the output directory it would have created).
source "$(dirname "$0")/../harness.sh"
VTK=$ASAN/vres-vtk

MAKER=$ROOT/$VRES_BUILD/tests/test_vtkio
if ! VRES_TEST_STORE_OUT=$T/syn.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_vtkio)"
    exit 1
fi

# Bad files.
echo "this is text, not HDF5" >"$T/text.h5"
head -c 2000 "$T/syn.h5" >"$T/trunc.h5"
h5copy -i "$T/syn.h5" -o "$T/foreign0.h5" -s /Domains/D0 -d /Other # valid HDF5, not a store
h5repack -L "$T/foreign0.h5" "$T/foreign.h5" # in the checksummed format vres reads (h5copy writes the oldest)
echo "plain file" >"$T/plain"
mkdir "$T/out" "$T/empty_run"

# nothing_new NAME: the output directory $T/out is still empty (and one message was printed).
nothing_new() {
    nothing_in "$T/out" "$1: nothing written"
    check "$1: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
}

expect_err 1 'missing\.h5: cannot open' "missing file" "$VTK" "$T/missing.h5" -o "$T/out"
nothing_new "missing file"
expect_err 1 'text\.h5: not an HDF5 file' "text file" "$VTK" "$T/text.h5" -o "$T/out/x.vtu"
nothing_new "text file"
expect_err 1 'trunc\.h5: .*truncated' "truncated HDF5" "$VTK" "$T/trunc.h5" -o "$T/out"
nothing_new "truncated HDF5"
expect_err 1 'foreign\.h5: not a vres store' "foreign HDF5" "$VTK" "$T/foreign.h5" -o "$T/out"
nothing_new "foreign HDF5"
expect_err 1 'empty_run: no snap_NNNNN\.h5 snapshots' "directory without snapshots" "$VTK" "$T/empty_run" -o "$T/out"
nothing_new "directory without snapshots"

# A bad input after a good one: the good one's file does not appear either.
expect_err 1 'text\.h5' "good then bad input" "$VTK" "$T/syn.h5" "$T/text.h5" -o "$T/out"
nothing_new "good then bad input"

# A run with one bad snapshot among good ones: no .vtu, no .pvd, and the output directory
# this run would have created is gone again.
mkdir "$T/run"
cp "$T/syn.h5" "$T/run/snap_00000.h5"
cp "$T/trunc.h5" "$T/run/snap_00001.h5"
cp "$T/syn.h5" "$T/run/snap_00002.h5"
expect_err 1 'snap_00001\.h5' "run with a bad snapshot" "$VTK" "$T/run" -o "$T/out/new/vtk"
nothing_new "run with a bad snapshot"

# An existing output is left as it was when a later export fails.
"$BIN/vres-vtk" "$T/syn.h5" -o "$T/keep.vtu"
cp "$T/keep.vtu" "$T/keep.orig"
expect_err 1 'text\.h5' "failure keeps the old output" "$VTK" "$T/text.h5" -o "$T/keep.vtu"
cmp -s "$T/keep.vtu" "$T/keep.orig"; check "old output unchanged" [ $? = 0 ]

# A domain the store does not have (exit 1: it is the input's property).
expect_err 1 'syn\.vtu: no domain 5: the store has 2 \(0 to 1\)' "--domain beyond the store" \
    "$VTK" --domain 5 "$T/syn.h5" -o "$T/out"
nothing_new "--domain beyond the store"

# Unwritable outputs.
expect_err 1 'plain/x\.vtu: cannot write' "-o under a regular file" "$VTK" "$T/syn.h5" -o "$T/plain/x.vtu"
expect_err 1 'plain: cannot write: exists and is not a directory' "-o directory is a file" \
    "$VTK" "$T/syn.h5" "$T/syn.h5" -o "$T/plain"
expect_err 1 'nodir/x\.vtu: cannot write' "-o in a missing directory" "$VTK" "$T/syn.h5" -o "$T/nodir/x.vtu"
check "missing directory not created" [ ! -e "$T/nodir" ]
# A directory without write permission (root writes anywhere, so only as a normal user).
if [ "$(id -u)" -ne 0 ]; then
    mkdir "$T/ro" && chmod a-w "$T/ro"
    expect_err 1 'ro/x\.vtu: cannot write: .*not writable' "-o in a read-only directory" \
        "$VTK" "$T/syn.h5" -o "$T/ro/x.vtu"
    nothing_in "$T/ro" "read-only directory: nothing written"
    chmod u+w "$T/ro"
fi
# Two inputs with the same name would overwrite each other.
mkdir "$T/other"
cp "$T/syn.h5" "$T/other/syn.h5"
expect_err 1 'syn\.vtu: two inputs would write' "name clash" "$VTK" "$T/syn.h5" "$T/other/syn.h5" -o "$T/out"
nothing_new "name clash"

# Usage errors: exit 2, the valid fields listed, nothing written.
expect_err 2 "unknown field 'Vorticity'.*valid: Domain, Type, Mk, Id, Velocity" "unknown field" \
    "$VTK" --fields Velocity,Vorticity "$T/syn.h5" -o "$T/out"
nothing_in "$T/out" "unknown field: nothing written"
expect_err 2 "empty field name" "empty field" "$VTK" --fields Velocity, "$T/syn.h5" -o "$T/out"
expect_err 2 'missing -o' "missing -o" "$VTK" "$T/syn.h5"
expect_err 2 "--domain.*integer" "--domain not a number" "$VTK" --domain one "$T/syn.h5" -o "$T/out"
expect_err 2 "--domain -1: not a domain index" "--domain negative" "$VTK" --domain -1 "$T/syn.h5" -o "$T/out"
expect_err 2 'run directory gives one file per snapshot' ".vtu name for a run" "$VTK" "$T/run" -o "$T/out/r.vtu"
expect_err 2 'several inputs' ".vtu name for two inputs" "$VTK" "$T/syn.h5" "$T/foreign.h5" -o "$T/out/r.vtu"
expect_err 2 "standard input .* only once" "stdin twice" "$VTK" - - -o "$T/out"
expect_err 2 "unknown option '--frobnicate'" "unknown option" "$VTK" --frobnicate "$T/syn.h5" -o "$T/out"
expect_err 2 'missing argument' "no input" "$VTK" -o "$T/out"
nothing_in "$T/out" "usage errors: nothing written"
