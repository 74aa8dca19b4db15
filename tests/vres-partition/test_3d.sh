#!/usr/bin/env bash
# vres-partition in 3D: the small tank of cases/tank_vres3d (0.4 x 0.4 m, 0.2 m of water at dp
# 0.02, cell-centred) with a box in the middle crossing the free surface (dpratio 2). Counts by
# hand (cases/tank_vres3d/README.md): h = sqrt(3) dp, so each buffer band is 4 layers thick.
source "$(dirname "$0")/../harness.sh"
C3D=$CASES/tank_vres3d/tank_vres3d_Def.xml

expect 0 "the 3D tank generates" "$BIN/vres-gencase" -q "$C3D" -o "$T/t.h5"
expect 0 "and partitions" "$ASAN/vres-partition" "$T/t.h5" -o "$T/p.h5"
run "$BIN/vres-info" -t "$T/p.h5"
count() { awk -F'\t' -v d="$1" -v t="$2" '$1 == d && $2 == t {s += $4} END {print s + 0}' "$OUT"; }
check "D0: 3300 fluid (4000 less the 10 x 10 x 7 in the box)" [ "$(count 0 fluid)" -eq 3300 ]
check "D0: 692 buffer (700 in the box less the 2 x 2 x 2 inside its inner box)" [ "$(count 0 buffer)" -eq 692 ]
check "D0: all 6736 walls" [ "$(count 0 fixed)" -eq 6736 ]
check "D1: 5600 fluid (20 x 20 x 14 at dp 0.01)" [ "$(count 1 fluid)" -eq 5600 ]
check "D1: 8512 buffer (28 x 28 x 18 less the fluid)" [ "$(count 1 buffer)" -eq 8512 ]
check "D1: 1156 walls (the floor's top layer under the band, 34 x 34)" [ "$(count 1 fixed)" -eq 1156 ]
values /Interfaces/I0/Position "$T/p.h5" | paste - - - >"$T/i0"
values /Interfaces/I0/Normal "$T/p.h5" | paste - - - >"$T/n0"
check "I0: 6 faces x 28 x 28 = 4704 patches (face areas / dp_child^2)" [ "$(wc -l <"$T/i0")" -eq 4704 ]
check "I0: patch area dp_child^2" [ "$(values /Interfaces/I0/Area "$T/p.h5" | sort -u | awk '{printf "%.12g\n", $1}')" = 0.0001 ]
check "I0: normals out of the box" \
    [ "$(paste "$T/i0" "$T/n0" | awk '($1 - 0.2) * $4 + ($2 - 0.2) * $5 + ($3 - 0.16) * $6 <= 0' | wc -l)" -eq 0 ]
check "I0: 784 patches per face direction" [ "$(awk '{print $1, $2, $3}' "$T/n0" | sort | uniq -c | awk '{print $1}' | sort -u)" = 784 ]
check "I1: the root's inner box, 0.04 m a side: 6 x 2 x 2 = 24 patches" \
    [ "$(values /Interfaces/I1/Area "$T/p.h5" | wc -l)" -eq 24 ]
expect 0 "vres-info shows the 3D tree" "$BIN/vres-info" -q "$T/p.h5"
check "tree: 4728 segments" grep -q "tree        2 domains, 2 interfaces, 4728 segments" "$OUT"
