#!/usr/bin/env bash
# cases/cavity_re1000: the case generates the cavity its README describes at any dp dividing
# L = 1 m (an (L/dp)^2 fluid square, nu = 0.001 m^2/s for Re = U L / nu = 1000), its lid is
# long enough to cover the cavity until TimeMax (the lid slides at U, so its left end must
# start at least U TimeMax + 2h left of the cavity, or the fluid near x = 0 loses its lid
# before the end), its copies of Ghia et al.'s tables are the Re = 1000 columns of the shared
# reference data, and its check script handles its arguments. (The physics check needs runs of
# many minutes: `make validate`, `make sweep`.)
source "$(dirname "$0")/../harness.sh"
source "$ROOT/pipelines/vreslib.sh"
DIR=$CASES/cavity_re1000
XML=$DIR/cavity_re1000_Def.xml
REF=$ROOT/../shared/refdata

expect 0 "vres-gencase --check accepts the case" "$BIN/vres-gencase" -q --check "$XML"
for dp in 0.05 0.04; do
    expect 0 "generate it at dp $dp" "$BIN/vres-gencase" -q --dp "$dp" "$XML" -o "$T/c.h5"
    particles "$T/c.h5" >"$T/p"
    want=$(awk -v d="$dp" 'BEGIN {printf "%d", (1 / d) ^ 2 + 0.5}')
    got=$(awk '$1 == 0' "$T/p" | wc -l)
    check "dp $dp: (L/dp)^2 = $want fluid particles ($got)" [ "$got" -eq "$want" ]
    re=$(awk -v nu="$(param Visco "$T/c.h5")" 'BEGIN {printf "%.6g", 1 * 1 / nu}')
    check "dp $dp: Re = U L / nu = 1000 ($re)" [ "$re" = 1000 ]
    tmax=$(param TimeMax "$T/c.h5")
    h=$(attr /Domains/D0/h "$T/c.h5")
    left=$(awk '$1 == 3 {if (!n++ || $2 < a) a = $2} END {printf "%.9g", a}' "$T/p")
    check "dp $dp: the lid starts at x = $left m, at least U TimeMax + 2h = $tmax + 2 x $h m left of x = 0" \
        awk -v a="$left" -v t="$tmax" -v h="$h" 'BEGIN {exit !(a <= -(t + 2 * h))}'
done
for f in u_vertical:ghia1982_u_vertical_centerline.csv v_horizontal:ghia1982_v_horizontal_centerline.csv; do
    mine=${f%%:*}; [ "$mine" = v_horizontal ] && mine=w_horizontal
    if [ -f "$REF/${f#*:}" ]; then
        d=$(paste -d, <(awk -F, '!/^#/ && $1 + 0 == $1 {print $1, $2}' "$DIR/ghia_$mine.csv") \
                      <(awk -F, '!/^#/ && $1 + 0 == $1 {print $2, $5}' "$REF/${f#*:}") |
            awk -F, '{split($1, a, " "); split($2, b, " "); n++; if (a[1] != b[1] || a[2] != b[2]) bad++}
                     END {printf "%d %d", n, bad}')
        check "ghia_$mine.csv is the Re = 1000 column of ${f#*:} (rows, differing: $d)" \
            awk -v d="$d" 'BEGIN {split(d, v, " "); exit !(v[1] >= 17 && v[2] == 0)}'
    else
        ok "# SKIP ${f#*:} not found in $REF"
    fi
done
expect 0 "check --help" "$DIR/check" --help
expect_err 2 "usage" "check: an unknown option is a usage error" "$DIR/check" --bogus
mkdir -p "$T/empty"
expect_err 1 "not a vres-run directory" "check: a directory without a run is refused" "$DIR/check" "$T/empty"
