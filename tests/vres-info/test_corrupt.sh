#!/usr/bin/env bash
# vres-info on stores with a few random bytes overwritten (a damaged disk or transfer):
# it either reads the store (the bytes hit unused space) or fails with exit 1 and one message
# naming the file; it never crashes, reads out of bounds nor prints HDF5's own diagnostics.
# Stores are written in HDF5 1.10's file format, whose superblock, object headers, heaps and chunk
# indexes carry checksums, and their particle datasets with the Fletcher32 filter: HDF5 refuses
# damage before parsing it. (In the oldest format, which stores had before, a mutation fuzzer
# found flipped bits making HDF5 1.10 read out of bounds under H5Aexists; in the 1.8 format,
# whose chunk index has no checksum, libFuzzer found one under H5Dread: vres refuses both
# formats, tests/fuzz/regress/store.) The AddressSanitizer build is used,
# with allocator_may_return_null so that a damaged size HDF5 tries to allocate fails as in the
# normal build instead of aborting.
source "$(dirname "$0")/../harness.sh"
INFO=$ASAN/vres-info
export ASAN_OPTIONS=$ASAN_OPTIONS:allocator_may_return_null=1

MAKER=$ROOT/$VRES_BUILD/tests/test_store
if ! VRES_TEST_STORE_OUT=$T/s.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_store)"
    exit 1
fi
# superblock version (byte 8): 3 for the 1.10 format (0 for the oldest, 2 for 1.8's), and HDF5's tools read it
check "the store has a version-3 superblock (HDF5 1.10 format)" [ "$(od -A n -t u1 -j 8 -N 1 "$T/s.h5" | tr -d ' ')" = 3 ]
h5dump -H "$T/s.h5" >/dev/null 2>&1; check "h5dump reads it" [ $? -eq 0 ]
check "its particle datasets carry the Fletcher32 filter" grep -q FLETCHER32 <(h5dump -p -H -d /Domains/D0/Position "$T/s.h5" 2>&1)
size=$(stat -c %s "$T/s.h5")

# damage MODE N: N damaged copies read by vres-info; MODE bytes: 1 to 6 bytes set to random values
# in the first 4 KiB, where HDF5 keeps the superblock and most headers; bits: 1 to 6 bits flipped
# anywhere (headers, heaps and compressed particle data)
damage() {
    local mode=$1 n=$2 bad=0 failed=0 read=0
    for i in $(seq 1 "$n"); do
        cp "$T/s.h5" "$T/d.h5"
        for k in $(seq 1 $((1 + RANDOM % 6))); do
            if [ "$mode" = bytes ]; then
                pos=$((RANDOM % 4096)) val=$((RANDOM % 256))
            else
                pos=$(((RANDOM * 32768 + RANDOM) % size))
                val=$(($(od -A n -t u1 -j $pos -N 1 "$T/d.h5") ^ (1 << (RANDOM % 8))))
            fi
            printf "\\x$(printf %02x $val)" | dd of="$T/d.h5" bs=1 seek=$pos conv=notrunc 2>/dev/null
        done
        run timeout 20 "$INFO" "$T/d.h5"
        if grep -q -E 'Sanitizer|runtime error' "$ERR"; then
            bad=$((bad + 1))
            echo "# $mode damage $i: sanitizer report"; grep -m3 -E 'ERROR|runtime error|#[0-4] ' "$ERR" | sed 's/^/#   /'
        elif [ "$STATUS" -eq 0 ]; then
            read=$((read + 1))
        elif [ "$STATUS" -eq 1 ] && [ "$(wc -l <"$ERR")" -eq 1 ] && grep -q "^vres-info: $T/d.h5: " "$ERR"; then
            failed=$((failed + 1))
        else
            bad=$((bad + 1))
            echo "# $mode damage $i: exit $STATUS"; sed 's/^/#   /' "$ERR" | head -5
        fi
    done
    check "$n stores with $mode damaged: $read read, $failed refused with one message, $bad otherwise" [ "$bad" -eq 0 ]
    # guards against a vacuous test (damage not applied); measured: 28 of 30 bytes, 30 of 30 bits refused
    check "damage is noticed ($failed of $n refused)" [ "$failed" -ge $((n * 3 / 4)) ]
}
RANDOM=20261122 # fixed seed: the same damage on every run
damage bytes 30
damage bits 30
