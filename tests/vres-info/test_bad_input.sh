#!/usr/bin/env bash
# vres-info on bad input, under AddressSanitizer: one message naming the file and what is
# wrong, exit 1 (2 for usage errors), nothing on stdout, no sanitizer report.
source "$(dirname "$0")/../harness.sh"
INFO=$ASAN/vres-info

MAKER=$ROOT/$VRES_BUILD/tests/test_store
if ! VRES_TEST_STORE_OUT=$T/s.h5 VRES_TEST_FOREIGN_OUT=$T/foreign.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_store)"
    exit 1
fi
: >"$T/empty.h5"
echo "<case>text, not HDF5</case>" >"$T/text.h5"
head -c 3000 "$T/s.h5" >"$T/trunc.h5"
size=$(stat -c %s "$T/s.h5")
head -c $((size - 100)) "$T/s.h5" >"$T/trunc_end.h5"
mkdir "$T/norun" "$T/run"
cp "$T/s.h5" "$T/run/snap_00000.h5"
cp "$T/trunc.h5" "$T/run/snap_00001.h5"

# bad NAME PATTERN ARGS...: exit 1, stderr one line matching PATTERN, stdout empty.
bad() {
    local name=$1 pat=$2; shift 2
    expect_err 1 "$pat" "$name" "$INFO" "$@"
    check "$name: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
    check "$name: nothing on stdout" [ ! -s "$OUT" ]
}

bad "missing file" "missing\.h5: cannot open: No such file" "$T/missing.h5"
bad "empty file" "empty\.h5: empty file" "$T/empty.h5"
bad "text file" "text\.h5: not an HDF5 file" "$T/text.h5"
bad "truncated store" "trunc\.h5: damaged or truncated" "$T/trunc.h5"
bad "store missing its last bytes" "trunc_end\.h5: damaged or truncated" "$T/trunc_end.h5"
bad "foreign HDF5" "foreign\.h5: not a vres store" "$T/foreign.h5"
# the oldest HDF5 format (what vres wrote before, and h5copy writes): refused before it is parsed,
# with the conversion that makes it readable (a store vres-gencase wrote before the change)
cp "$ROOT/tests/fuzz/regress/store/v0-format-hydrostatic2d.h5" "$T/old.h5"
bad "store in the oldest HDF5 format" "old\.h5: HDF5 file format without checksums \(superblock version 0\).*h5repack -L" "$T/old.h5"
h5repack -L "$T/old.h5" "$T/converted.h5"
run "$INFO" "$T/converted.h5"
check "converted with h5repack -L: read" [ "$STATUS" -eq 0 ]
bad "truncated store on stdin" "\(stdin\): damaged or truncated" - <"$T/trunc.h5"
bad "text on stdin" "\(stdin\): not an HDF5 file" - <"$T/text.h5"
bad "empty stdin" "\(stdin\): empty input" - </dev/null
bad "directory without snapshots" "norun: no snapshots" "$T/norun"
bad "run with a truncated snapshot" "snap_00001\.h5: damaged or truncated" "$T/run"
bad "-o in a missing directory" "nodir/x\.txt: cannot write" -o "$T/nodir/x.txt" "$T/s.h5"
expect_err 2 "Try 'vres-info --help'" "no argument is a usage error" "$INFO"
expect_err 2 "too many arguments" "two stores is a usage error" "$INFO" "$T/s.h5" "$T/s.h5"
