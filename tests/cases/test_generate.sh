#!/usr/bin/env bash
# Every shipped case generates: vres-gencase makes a 2-D store with fluid and wall particles,
# the refinement boxes and the moving/floating bodies its XML defines, at a size that keeps
# the demo fast. The expectations come from each case's XML and README, not from the code.
source "$(dirname "$0")/../harness.sh"

# Counts per (domain, type, mk) of a store, from vres-info -t ("# domain type mk count").
# count FILE TYPE [MK]: particles of TYPE (and MK) in the root domain.
count() {
    awk -F'\t' -v t="$2" -v m="${3-}" \
        '!/^#/ && $1 == 0 && $2 == t && (m == "" || $3 == m) { s += $4 } END { print s + 0 }' "$1"
}
# mks FILE TYPE: the mks of TYPE in the root domain, sorted, space-separated.
mks() {
    awk -F'\t' -v t="$2" '!/^#/ && $1 == 0 && $2 == t { print $3 }' "$1" | sort -n -u | tr '\n' ' ' | sed 's/ $//'
}
# near A B TOL: |A - B| <= TOL * B.
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t * b) }'; }

# name  boxes  floating-mks  moving-mks  tracked-mks (from the case XML: <bufferbox>,
# <floating>, <objreal>, and each box's <tracking mkbound> in the order of the file)
while read -r name boxes floating moving tracked; do
    xml=$CASES/$name/${name}_Def.xml
    h5=$T/$name.h5
    expect 0 "$name: vres-gencase generates it" "$BIN/vres-gencase" "$xml" -o "$h5"
    [ "$STATUS" -eq 0 ] || continue
    run "$BIN/vres-info" -t "$h5"
    cp "$OUT" "$T/$name.tsv"
    run "$BIN/vres-info" "$h5"
    cp "$OUT" "$T/$name.txt"
    tsv=$T/$name.tsv
    fluid=$(count "$tsv" fluid)
    walls=$(( $(count "$tsv" fixed) + $(count "$tsv" moving) + $(count "$tsv" floating) ))
    total=$(( fluid + walls ))
    check "$name: has fluid particles ($fluid)" [ "$fluid" -gt 0 ]
    check "$name: has wall particles ($walls)" [ "$(count "$tsv" fixed)" -gt 0 ]
    # The shipped dp keeps gencase and the demo fast: about 10k to 100k particles.
    check "$name: 8k to 100k particles at the shipped dp ($total)" [ "$total" -ge 8000 -a "$total" -le 100000 ]
    check "$name: 2-D (zero y extent)" grep -q -E '^ *dimension +2' "$T/$name.txt"
    got=$(sed -n -E 's/^refinement boxes: ([0-9]+).*/\1/p' "$T/$name.txt")
    check "$name: $boxes refinement boxes (got ${got:-none})" [ "${got:-x}" = "$boxes" ]
    [ "$floating" = "-" ] && floating=""
    [ "$moving" = "-" ] && moving=""
    got=$(mks "$tsv" floating)
    check "$name: floating bodies mkbound [${floating//,/ }] (got [$got])" [ "$got" = "${floating//,/ }" ]
    got=$(mks "$tsv" moving)
    check "$name: moving bodies mkbound [${moving//,/ }] (got [$got])" [ "$got" = "${moving//,/ }" ]
    [ "$tracked" = "-" ] && tracked=""
    got=$(sed -n -E 's/^  B[0-9]+ in .*tracking mkbound ([0-9]+).*/\1/p' "$T/$name.txt" | tr '\n' ' ' | sed 's/ $//')
    check "$name: boxes tracking mkbound [${tracked//,/ }] (got [$got])" [ "$got" = "${tracked//,/ }" ]
done <<'EOF'
dambreak2d 1 - - -
cylinder_re200 2 - - -
tandem_cylinders 3 - 1,2 1,1,2
wedge 2 1 - 1,1
wedge_entry2d 2 - 1 1,1
EOF

# Geometry checks that follow from the cases' convention: pointref = Dp/2 puts particles at
# cell centres, so a box whose sides are multiples of dp holds exactly (side/dp) nodes a side.
if [ -f "$T/dambreak2d.tsv" ]; then
    # Lobovsky column 0.6 m x 0.3 m at dp 0.005 m: 120 x 60 particles.
    n=$(count "$T/dambreak2d.tsv" fluid 0)
    check "dambreak2d: column of 120 x 60 = 7200 fluid particles ($n)" [ "$n" -eq 7200 ]
    # Halving dp quadruples the column exactly (240 x 120), the walls follow the new dp.
    expect 0 "dambreak2d: generates with --dp 0.0025" "$BIN/vres-gencase" "$CASES/dambreak2d/dambreak2d_Def.xml" \
        --dp 0.0025 -o "$T/db_half.h5"
    run "$BIN/vres-info" -t "$T/db_half.h5"
    n=$(count "$OUT" fluid 0)
    check "dambreak2d --dp 0.0025: 240 x 120 = 28800 fluid particles ($n)" [ "$n" -eq 28800 ]
fi
if [ -f "$T/wedge.tsv" ]; then
    # Wedge polygon area: V of half-breadth 0.25 m and depth 0.25 tan 30 deg = 0.1443 m
    # (0.0361 m^2) under a 0.5 m x 0.1557 m block (0.0778 m^2): 0.1139 m^2 = 1139 dp^2 at
    # dp 0.01. A lattice count differs from area/dp^2 by about half the perimeter (1.3 m)
    # over dp, 65 nodes or 6 %: 10 % tolerance.
    n=$(count "$T/wedge.tsv" floating 1)
    check "wedge: floating particles near its area/dp^2 = 1139 ($n)" near "$n" 1139 0.10
fi
if [ -f "$T/tandem_cylinders.tsv" ]; then
    # Both cylinders have the same radius and their centres are 25 dp apart on the lattice,
    # so they cover the same pattern of nodes.
    a=$(count "$T/tandem_cylinders.tsv" moving 1)
    b=$(count "$T/tandem_cylinders.tsv" moving 2)
    check "tandem_cylinders: both cylinders have the same particle count ($a, $b)" [ "$a" -eq "$b" -a "$a" -gt 0 ]
fi
if [ -f "$T/cylinder_re200.tsv" ]; then
    # Disc of radius 0.1 m at dp 0.02: pi 0.1^2 / 0.02^2 = 78.5 nodes; at 5 dp of radius the
    # lattice count can differ by about half the perimeter over dp (16 nodes): 25 %.
    n=$(count "$T/cylinder_re200.tsv" fixed 1)
    check "cylinder_re200: cylinder particles near pi R^2/dp^2 = 78.5 ($n)" near "$n" 78.5 0.25
fi
