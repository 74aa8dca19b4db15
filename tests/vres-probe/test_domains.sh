#!/usr/bin/env bash
# vres-probe on a store of two resolutions: the still-water tank of tests/lib/test_probe.c
# (tank_domains(): a root at dp 0.02 m and two sibling refinement boxes at dp 0.01 m, A under
# water at x [0.4, 0.6] z [-0.1, 0.3], B across the free surface at x [0.7, 0.9] z [0.2, 0.5];
# the root's fluid holds the linear fields f(x), the boxes' fluid 1.1 f(x) + an offset, and every
# buffer particle absurd values: p 1e7 Pa, rho 1 kg/m^3, v 500 m/s, mass 10 kg).
# Expected: each point reads the pressure of the domain that owns it, exactly up to the float
# rounding of the stored fields (a few 1e-4 Pa on 5000: tolerance 0.01 Pa), whatever the buffers
# hold; the free surface is at z = 0.4 m through A's top face and inside B.
source "$(dirname "$0")/../harness.sh"
PROBE=$BIN/vres-probe

MAKER=$ROOT/$VRES_BUILD/tests/test_probe
if ! VRES_TEST_TANK_OUT=$T/tank.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_probe)"
    exit 1
fi
check "the store has three domains" [ "$(h5ls "$T/tank.h5/Domains" | wc -l)" = 3 ]

# points: x z and the domain that owns each (0 root, 1 box A, 2 box B); a quarter spacing
# either side of the faces, in the middle of the boxes, and away from both
cat >"$T/where.txt" <<'PTS'
0.5 0.15 1
0.4025 0.15 1
0.3975 0.15 0
0.605 0.15 0
0.5 0.2975 1
0.5 0.305 0
0.8 0.3 2
0.695 0.3 0
0.8 0.195 0
0.2 0.2 0
PTS
awk '{print $1, 0, $2}' "$T/where.txt" >"$T/pts.txt"
expect 0 "probe the pressure at 10 points" "$PROBE" --points "$T/pts.txt" --vars p "$T/tank.h5"
# the fields of tests/lib/test_probe.c: root p = 5000 + 300 x + 50 y - 9810 z, boxes 1.1 p + 700
paste "$T/where.txt" <(awk -F'\t' '!/^#/ {print $6}' "$OUT") >"$T/got.txt"
check "10 values" [ "$(wc -l <"$T/got.txt")" = 10 ]
bad=$(awk '{p = 5000 + 300 * $1 - 9810 * $2; if ($3 > 0) p = 1.1 * p + 700; d = $4 - p
            if (d > 0.01 || d < -0.01) printf "(%s, %s) domain %s: %s, want %.4f; ", $1, $2, $3, $4, p}' "$T/got.txt")
check "each point reads its own domain's pressure, not a buffer's ${bad:+($bad)}" [ -z "$bad" ]

expect 0 "--surface through box A's top face, inside box B and beside them" \
    "$PROBE" --surface --line 0.5,0,0.05:0.5,0,0.6:551 --line 0.8,0,0.05:0.8,0,0.6:551 --line 0.2,0,0.05:0.2,0,0.6:551 "$T/tank.h5"
bad=$(awk -F'\t' '!/^#/ {d = $5 - 0.4; if (d > 0.001 || d < -0.001) printf "line %s at %s; ", $2, $5}' "$OUT")
check "the free surface at z = 0.4 m within 0.001 m on every line, no false one at a box face ${bad:+($bad)}" \
    [ -z "$bad" ] && [ "$(grep -vc '^#' "$OUT")" = 3 ]
