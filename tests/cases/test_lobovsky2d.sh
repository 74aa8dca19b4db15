#!/usr/bin/env bash
# cases/dambreak_lobovsky2d: the case generates the Lobovsky et al. (2014) tank as its README
# says, at any dp dividing 0.01 m, and its check script handles its arguments. (The physics
# check itself needs a run of minutes: `make validate`, `make sweep`.)
# Expectations from the experiment's geometry: column 0.6 m x 0.3 m, downstream wall face at
# x = 1.61 m; the case's convention (cases/README.md): cell-centred lattice, wall layers 0.5,
# 1.5, 2.5 dp behind the faces.
source "$(dirname "$0")/../harness.sh"
DIR=$CASES/dambreak_lobovsky2d
XML=$DIR/dambreak_lobovsky2d_Def.xml

expect 0 "vres-gencase --check accepts the case" "$BIN/vres-gencase" -q --check "$XML"
for dp in 0.01 0.005; do
    expect 0 "generate it at dp $dp" "$BIN/vres-gencase" -q --dp "$dp" "$XML" -o "$T/c.h5"
    paste <(values /Domains/D0/Type "$T/c.h5") <(values /Domains/D0/Position "$T/c.h5" | paste - - -) >"$T/p"
    want=$(awk -v d="$dp" 'BEGIN {printf "%d", (0.6 / d) * (0.3 / d) + 0.5}')
    got=$(awk '$1 == 0' "$T/p" | wc -l)
    check "dp $dp: the column holds (0.6/dp)(0.3/dp) = $want fluid particles ($got)" [ "$got" -eq "$want" ]
    got=$(awk '$1 == 0 {if (!n++ || $2 > x) x = $2; if (n == 1 || $4 > z) z = $4} END {printf "%.9g %.9g", x, z}' "$T/p")
    check "dp $dp: column faces at x = 0.6, z = 0.3 m (last particles at $got)" \
        awk -v g="$got" -v d="$dp" 'BEGIN {split(g, v, " "); exit !((v[1] + d / 2 - 0.6) ^ 2 < 1e-18 && (v[2] + d / 2 - 0.3) ^ 2 < 1e-18)}'
    got=$(awk '$1 != 0 && $2 > 1 && $4 > 0 {if (!n++ || $2 < x) x = $2} END {printf "%.9g", x}' "$T/p")
    check "dp $dp: downstream wall's first layer dp/2 behind x = 1.61 m ($got)" \
        awk -v x="$got" -v d="$dp" 'BEGIN {exit !((x - d / 2 - 1.61) ^ 2 < 1e-18)}'
done
expect 0 "check --help" "$DIR/check" --help
expect_err 2 "usage" "check: an unknown option is a usage error" "$DIR/check" --bogus
mkdir -p "$T/empty"
expect_err 1 "not a vres-run directory" "check: a directory without a run is refused" "$DIR/check" "$T/empty"
