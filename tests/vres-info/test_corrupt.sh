#!/usr/bin/env bash
# vres-info on stores with a few random bytes overwritten (a damaged disk or transfer):
# it either reads the store (the bytes hit data or unused space) or fails with exit 1 and
# one message naming the file; it never crashes nor prints HDF5's own diagnostics.
# The normal build is used: under AddressSanitizer, HDF5 itself aborts on some damaged
# sizes it tries to allocate (hundreds of GB) where the normal build reports the failure.
source "$(dirname "$0")/../harness.sh"
INFO=$BIN/vres-info

MAKER=$ROOT/$VRES_BUILD/tests/test_store
if ! VRES_TEST_STORE_OUT=$T/s.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_store)"
    exit 1
fi

RANDOM=20261122 # fixed seed: the same damage on every run
bad=0 failed=0 read=0
for i in $(seq 1 40); do
    cp "$T/s.h5" "$T/d.h5"
    for k in $(seq 1 $((1 + RANDOM % 6))); do
        # mostly in the first 4 KiB, where HDF5 keeps the superblock and most headers
        pos=$((RANDOM % 4096))
        printf "\\x$(printf %02x $((RANDOM % 256)))" | dd of="$T/d.h5" bs=1 seek=$pos conv=notrunc 2>/dev/null
    done
    run timeout 20 "$INFO" "$T/d.h5"
    if [ "$STATUS" -eq 0 ]; then
        read=$((read + 1))
    elif [ "$STATUS" -eq 1 ] && [ "$(wc -l <"$ERR")" -eq 1 ] && grep -q "^vres-info: $T/d.h5: " "$ERR"; then
        failed=$((failed + 1))
    else
        bad=$((bad + 1))
        echo "# damage $i: exit $STATUS"; sed 's/^/#   /' "$ERR" | head -5
    fi
done
check "40 damaged stores: $read read, $failed refused with one message, $bad otherwise" [ "$bad" -eq 0 ]
# guards against a vacuous test (damage not applied): about 28 of 40 are refused (the history timestamp shifts a few bytes)
check "damage is noticed ($failed of 40 refused)" [ "$failed" -ge 10 ]
