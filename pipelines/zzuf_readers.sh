#!/usr/bin/env bash
# pipelines/zzuf_readers.sh [N] [START] - issue 10's check "a reader given a thousand mutated
# copies of a shipped case and store never crashes, hangs or leaves a file behind", with zzuf
# (Debian's package zzuf, a mutation fuzzer not shipped here: apt-get install zzuf) and the
# AddressSanitizer build of the tools (make asan).
#
# For seeds i = START..N (default 1..1000): zzuf -s i flips a random share (0.002% to 0.2%) of
# the bits of cases/dsph_dambreak2d/dambreak2d_Def.xml (never producing control or non-ASCII
# bytes, so that many copies still parse) and 0.0005% to 0.05% of the bits of a store
# vres-gencase made of it at dp 0.02 m. Each copy is read by a reader in an empty directory:
#   vres-gencase COPY.xml -o out.h5;   vres-info COPY.h5;   vres-partition COPY.h5 -o p.h5
# Verdicts: CRASH (a sanitizer report, a signal, or 60 s without an answer), LEFTOVER (refused
# but a file left in the directory), SILENT (refused without a message), UNREADABLE (accepted
# but its output is not a store vres-info reads); otherwise ok. Prints the tally every 100 seeds
# and at the end; the log of every bad run is build/zzuf/zzuf.log. Exit 1 when any run was bad.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
N=${1:-1000}; START=${2:-1}
A=$ROOT/build/asan/bin
W=$ROOT/build/zzuf
command -v zzuf >/dev/null || { echo "zzuf_readers: needs zzuf (apt-get install zzuf)" >&2; exit 2; }
for t in vres-gencase vres-info vres-partition; do
    [ -x "$A/$t" ] || { echo "zzuf_readers: $A/$t missing (make asan)" >&2; exit 2; }
done
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:allocator_may_return_null=1
export LSAN_OPTIONS=suppressions=$ROOT/tests/lsan.supp:print_suppressions=0
mkdir -p "$W" && cd "$W" || exit 2
CASE=$ROOT/cases/dsph_dambreak2d/dambreak2d_Def.xml
[ -f seed.h5 ] || "$ROOT/bin/vres-gencase" -q --dp 0.02 "$CASE" -o seed.h5 || exit 2
bad=0; ok=0; refused=0; log=zzuf.log
[ "$START" = 1 ] && : > $log
run() { # NAME EXPECTED_OUTPUT CMD...: one reader on one copy, in the empty directory d
    local name=$1 out=$2; shift 2
    rm -rf d; mkdir d
    (cd d && timeout 60 "$@" > ../o.txt 2>&1); local rc=$?
    local left verdict=ok
    left=$(cd d && find . -mindepth 1 | sort | tr '\n' ' ')
    if [ $rc -ge 124 ] || grep -q "AddressSanitizer\|runtime error:\|LeakSanitizer" o.txt; then verdict=CRASH
    elif [ $rc -ne 0 ] && [ -n "$left" ]; then verdict=LEFTOVER
    elif [ $rc -ne 0 ] && ! grep -q . o.txt; then verdict=SILENT
    elif [ $rc -eq 0 ] && [ -n "$out" ] && ! "$ROOT/bin/vres-info" "d/$out" > /dev/null 2>&1; then verdict=UNREADABLE
    fi
    [ $rc -ne 0 ] && refused=$((refused + 1))
    if [ $verdict != ok ]; then
        bad=$((bad + 1)); echo "$verdict $name rc=$rc left=[$left]" >> $log; sed 's/^/    /' o.txt | head -20 >> $log
    else ok=$((ok + 1)); fi
}
for i in $(seq "$START" "$N"); do
    zzuf -s "$i" -r 0.00002:0.002 -R '\x00-\x08\x0b-\x1f\x7f-\xff' < "$CASE" > m.xml
    run "case seed $i vres-gencase" out.h5 "$A/vres-gencase" -q ../m.xml -o out.h5
    zzuf -s "$i" -r 0.000005:0.0005 < seed.h5 > m.h5
    run "store seed $i vres-info" "" "$A/vres-info" ../m.h5
    run "store seed $i vres-partition" p.h5 "$A/vres-partition" ../m.h5 -o p.h5
    [ $(( (i - START + 1) % 100 )) = 0 ] && echo "seeds $START..$i: $ok ok, $bad bad ($refused refused)" | tee -a $log
done
echo "zzuf_readers: seeds $START..$N, $((3 * (N - START + 1))) reader runs: $ok ok, $bad bad ($refused refused with a message)" | tee -a $log
[ $bad = 0 ]
