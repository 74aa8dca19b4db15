#!/usr/bin/env bash
# vres-partition on the 2D still-water tank with a box crossing the free surface and the right
# wall (cases/hydrostatic_vres2d) and on the dam break refined at its impact wall
# (cases/dambreak2d): the domains, their counts per type, the interface segments, read back
# with h5dump. The counts follow by hand from the lattices (cases/hydrostatic_vres2d/README.md).
source "$(dirname "$0")/../harness.sh"
H2D=$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml

expect 0 "the tank generates" "$BIN/vres-gencase" -q "$H2D" -o "$T/h.h5"
expect 0 "and partitions" "$BIN/vres-partition" "$T/h.h5" -o "$T/p.h5"
check "it says what it built" grep -q "hydrostatic_vres2d: 2 domains, 196 interface segments" "$ERR"
# counts per domain and type (vres-info -t), by hand
run "$BIN/vres-info" -t "$T/p.h5"
count() { awk -F'\t' -v d="$1" -v t="$2" '$1 == d && $2 == t {s += $4} END {print s + 0}' "$OUT"; }
check "D0: 1050 fluid (1250 less the 200 of the box)" [ "$(count 0 fluid)" -eq 1050 ]
check "D0: 81 buffer (the root's 3-layer band inside the box, under the surface)" [ "$(count 0 buffer)" -eq 81 ]
check "D0: all 390 walls" [ "$(count 0 fixed)" -eq 390 ]
check "D1: 800 fluid (40 x 20 at dp 0.01)" [ "$(count 1 fluid)" -eq 800 ]
check "D1: 189 buffer (3 columns x 23 rows + 3 rows x 40)" [ "$(count 1 buffer)" -eq 189 ]
check "D1: 144 walls (the right wall's 3 layers near the box)" [ "$(count 1 fixed)" -eq 144 ]

# the domain tree's attributes and the interfaces, read with h5dump
attr() { h5dump -m '%.17g' -a "$1" "$2" | awk '/\([0-9]+\):/ {sub(/.*\([0-9]+\): */, ""); gsub(/,/, ""); printf "%s%s", n++ ? " " : "", $0} END {print ""}'; }
check "D1's parent is D0" [ "$(attr /Domains/D1/parent "$T/p.h5")" = 0 ]
check "D1's dp is 0.01" [ "$(attr /Domains/D1/dp "$T/p.h5")" = 0.01 ]
# same A B: two lists of numbers equal to 1e-9
same() { awk -v a="$1" -v b="$2" 'BEGIN {n = split(a, x, " "); if (n != split(b, y, " ")) exit 1;
    for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d > 1e-9 || d < -1e-9) exit 1 } }'; }
check "D1's fluid box is the box cut to the domain" same "$(attr /Domains/D1/box_max "$T/p.h5")" "1.05 0 0.7"
check "D1's buffer band reaches 3 layers out" same "$(attr /Domains/D1/buffer_min "$T/p.h5")" "0.57 0 0.27"
check "D1's hole in D0: the root's cells in the box" same "$(attr /Domains/D1/hole_max "$T/p.h5")" "1.06 0 0.7"
check "D1's inner box: 3 root layers in, none on the right" same "$(attr /Domains/D1/inner_max "$T/p.h5")" "1.06 0 0.64"
check "I0: D1 receives from D0" [ "$(attr /Interfaces/I0/receiving "$T/p.h5") $(attr /Interfaces/I0/donor "$T/p.h5")" = "1 0" ]
check "I1: D0 receives from D1" [ "$(attr /Interfaces/I1/receiving "$T/p.h5") $(attr /Interfaces/I1/donor "$T/p.h5")" = "0 1" ]
values /Interfaces/I0/Position "$T/p.h5" | paste - - - >"$T/i0"
values /Interfaces/I0/Normal "$T/p.h5" | paste - - - >"$T/n0"
values /Interfaces/I1/Position "$T/p.h5" | paste - - - >"$T/i1"
values /Interfaces/I1/Normal "$T/p.h5" | paste - - - >"$T/n1"
# the child's band: perimeter 2 (0.51 + 0.46) / 0.01 = 194, less the right edge beyond the
# domain (x = 1.08 > 1.05: 46) and the 3 + 3 of the top and bottom edges past x = 1.05
check "I0: 142 segments" [ "$(wc -l <"$T/i0")" -eq 142 ]
check "I0: none outside the domain" [ "$(awk '$1 > 1.05 + 1e-9' "$T/i0" | wc -l)" -eq 0 ]
check "I0: normals point out of the child's box" \
    [ "$(paste "$T/i0" "$T/n0" | awk '($1 - 0.825) * $4 + ($3 - 0.5) * $6 <= 0' | wc -l)" -eq 0 ]
check "I0: segment length dp_child" [ "$(values /Interfaces/I0/Area "$T/p.h5" | sort -u)" = 0.01 ]
check "I0: accumulated mass 0" [ "$(values /Interfaces/I0/Mass "$T/p.h5" | sort -u)" = 0 ]
# the root's band: the inner box 0.66..1.06 x 0.36..0.64, open on the right where the box
# reaches the domain's edge: 14 + 2 x 20 segments, dp_root apart, normals into the box
check "I1: 54 segments (left edge 14, top and bottom 20 each)" [ "$(wc -l <"$T/i1")" -eq 54 ]
check "I1: normals point into the box" \
    [ "$(paste "$T/i1" "$T/n1" | awk '($1 - 0.86) * $4 + ($3 - 0.5) * $6 >= 0' | wc -l)" -eq 0 ]
check "I1: segment length dp_root" [ "$(values /Interfaces/I1/Area "$T/p.h5" | sort -u)" = 0.02 ]
# ids unique across domains, next_id after them
ids=$( (values /Domains/D0/Id "$T/p.h5"; values /Domains/D1/Id "$T/p.h5") | sort -n)
check "ids are unique across domains" [ "$(uniq -d <<<"$ids" | wc -l)" -eq 0 ]
check "next_id is one past the largest id" [ "$(attr /next_id "$T/p.h5")" -eq $(( $(tail -1 <<<"$ids") + 1 )) ]
check "the root keeps its ids" [ "$(values /Domains/D0/Id "$T/p.h5" | head -1)" -eq 0 ]
# one equation of state (the root's B, rho0): equal depth below the column's top, equal pressure
p_root=$(paste <(values /Domains/D0/Position "$T/p.h5" | paste - - -) <(values /Domains/D0/Pressure "$T/p.h5") |
    awk '$1 > 0.56 && $1 < 0.6 && $3 > 0.3 && $3 < 0.32 {print $4; exit}')
p_child=$(paste <(values /Domains/D1/Position "$T/p.h5" | paste - - -) <(values /Domains/D1/Pressure "$T/p.h5") |
    awk '$1 > 0.6 && $1 < 0.61 && $3 > 0.31 && $3 < 0.32 {print $4; exit}')
check "the root at z = 0.31 and the child at 0.315, both 0.18 m below their column's top particle, have one pressure ($p_root, $p_child)" \
    awk -v a="$p_root" -v b="$p_child" 'BEGIN {d = a - b; exit !(a > 1700 && d < 1e-3 && d > -1e-3)}'

# vres-info shows the tree
expect 0 "vres-info reads the parts" "$BIN/vres-info" "$T/p.h5"
check "tree line" grep -q "tree        2 domains, 2 interfaces, 196 segments, next id 2773" "$OUT"
check "D1's line: parent, dp, h, box, counts, segments" grep -q \
    "D1 (in D0): 1133 particles, dp 0.01 m, h 0.0141421 m, box (0.6, 0, 0.3) to (1.05, 0, 0.7) m: 800 fluid, 189 buffer, 144 walls, 142 segments" "$OUT"
check "D0's line" grep -q "D0 (root): 1521 particles, dp 0.02 m, .*: 1050 fluid, 81 buffer, 390 walls, 54 segments" "$OUT"

# pipes: gencase | partition | info
"$BIN/vres-gencase" -q "$H2D" | "$BIN/vres-partition" -q - | "$BIN/vres-info" -q - >"$T/pipe.txt" 2>"$T/pipe.err"
check "vres-gencase | vres-partition - | vres-info - works" grep -q "tree        2 domains" "$T/pipe.txt"
"$BIN/vres-partition" -q - <"$T/h.h5" >"$T/fromstdin.h5"
check "stdin to stdout gives the same particles" cmp -s <(values /Domains/D1/Position "$T/fromstdin.h5") \
    <(values /Domains/D1/Position "$T/p.h5")

# the dam break refined at its wall: before the front arrives the box holds walls only
expect 0 "the dam break partitions" "$BIN/vres-partition" "$(
    "$BIN/vres-gencase" -q "$CASES/dambreak2d/dambreak2d_Def.xml" -o "$T/db.h5"; echo "$T/db.h5")" -o "$T/dbp.h5"
check "dam break: 2 domains, 912 + 420 segments (perimeters 2.28 m / 0.0025, 2.1 m / 0.005)" \
    grep -q "dambreak2d: 2 domains, 1332 interface segments" "$ERR"
check "dam break: the column stays whole in D0" grep -q "D0: dp 0.005 m, 7200 fluid, 0 buffer" "$ERR"
check "dam break: D1 holds the wall at its dp" grep -q "D1: dp 0.0025 m, 0 fluid, 0 buffer, 1185 walls" "$ERR"
values /Domains/D1/Normal "$T/dbp.h5" | paste - - - >"$T/dbn"
check "dam break: every wall of D1 has its mDBC normal" [ "$(awk '$1 == 0 && $3 == 0' "$T/dbn" | wc -l)" -eq 0 ]

# the same dam break without its widened domain: the box is cut at the floor (z = -0.0125, the
# lowest wall layer), so no segment lies on the floor side: the child's band below the domain
# is dropped (its bottom edge and the 3 lowest segments of each side), and the root has no
# band on that side (its inner box reaches the cut face) nor segments there
sed 's|z="default - 0.05"|z="default"|' "$CASES/dambreak2d/dambreak2d_Def.xml" >"$T/floor.xml"
"$BIN/vres-gencase" -q "$T/floor.xml" -o "$T/floor.h5"
expect 0 "the dam break cut at the floor partitions" "$ASAN/vres-partition" "$T/floor.h5" -o "$T/floorp.h5"
values /Interfaces/I0/Position "$T/floorp.h5" | paste - - - >"$T/f0"
values /Interfaces/I0/Normal "$T/floorp.h5" | paste - - - >"$T/fn0"
values /Interfaces/I1/Normal "$T/floorp.h5" | paste - - - >"$T/fn1"
check "child's band: 170 top + 2 x (271 - 3) sides = 706 segments" [ "$(wc -l <"$T/f0")" -eq 706 ]
check "child's band: none below the domain" [ "$(awk '$3 < -0.0125 - 1e-9' "$T/f0" | wc -l)" -eq 0 ]
check "child's band: no bottom edge" [ "$(awk '$3 == -1' "$T/fn0" | wc -l)" -eq 0 ]
check "root's band: 2 x 130 sides + 76 top = 336 segments, none on the floor side" \
    [ "$(wc -l <"$T/fn1") $(awk '$3 == 1' "$T/fn1" | wc -l)" = "336 0" ]
check "root's inner box reaches the cut face" [ "$(attr /Domains/D1/inner_min "$T/floorp.h5" | cut -d' ' -f3)" = "$(attr /Domains/D1/hole_min "$T/floorp.h5" | cut -d' ' -f3)" ]
