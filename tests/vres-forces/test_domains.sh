#!/usr/bin/env bash
# vres-forces across a refinement interface: the still-water tank of tests/lib/test_forces.c
# (tank(): water 1 m wide and 0.4 m deep over a bottom wall, mkbound 1, of three DBC rows)
# at one resolution (dp 0.02 m) and with a child box at dp 0.01 m holding 0.2 m of the bottom,
# its wall crossing both side faces, the root's wall drawn across the box too, and every
# buffer particle holding absurd values (1e7 Pa). The bottom carries the same load in both to
# 8e-10 (why the single-resolution value is exact to that: tests/lib/test_forces.c): the
# tolerance 1e-6 leaves room for the table's 9 printed digits; each wall point is listed once.
source "$(dirname "$0")/../harness.sh"
FORCES=$BIN/vres-forces

MAKER=$ROOT/$VRES_BUILD/tests/test_forces
if ! VRES_TEST_TANK_OUT=$T "$MAKER" >/dev/null 2>&1; then
    notok "make the test stores with $MAKER (build it: make $VRES_BUILD/tests/test_forces)"
    exit 1
fi
expect 0 "one resolution" "$FORCES" --mk 1 --centre 0,0,0 "$T/one.h5" -o "$T/one.tsv"
expect 0 "two resolutions" "$FORCES" -v --mk 1 --centre 0,0,0 "$T/two.h5" -o "$T/two.tsv"
row() { grep -v '^#' "$1"; }
fz1=$(row "$T/one.tsv" | cut -f4) fz2=$(row "$T/two.tsv" | cut -f4)
my1=$(row "$T/one.tsv" | cut -f6) my2=$(row "$T/two.tsv" | cut -f6)
close() { awk -v a="$1" -v b="$2" 'BEGIN {e = a / b - 1; exit !(b != 0 && e < 1e-6 && e > -1e-6)}'; }
check "the bottom's fz across the box ($fz2 N/m) is the single-resolution one ($fz1 N/m), not doubled" close "$fz2" "$fz1"
check "and its moment ($my2 against $my1 N m/m)" close "$my2" "$my1"
check "about the water's weight (3924 N/m, less the kernel's 0.78%)" \
    awk -v f="$fz1" 'BEGIN {e = -f / 3924 - 1; exit !(e < 0 && e > -0.01)}'
check "header: each wall point once over 2 domains" \
    grep -q '^# vres-forces: .*mkbound 1 (fixed walls, 204 particles in 2 domains)' "$T/two.tsv"
check "header: what the domains contribute" \
    grep -q "^# 2 domains: each domain's fluid where that domain owns it.* (48 more lie where another domain owns" "$T/two.tsv"
check "-v: shared particles counted" grep -q '204 body particles (+ 48 where another domain owns)' "$ERR"
check "one domain: no domain line" [ "$(grep -c '^# [0-9]* domains:' "$T/one.tsv")" = 0 ]
