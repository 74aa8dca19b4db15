#!/usr/bin/env bash
# cases/ritter2d: the case generates the reservoir its README describes (h0 = 1 m deep, 5 h0
# long, dam face at x = 0) at any dp dividing h0, its copy of Ritter's profile is Ritter's
# (2 - xi)^2 / 9, and its check script handles its arguments. (The physics check needs runs of
# a minute or more: `make validate`, `make sweep`.)
source "$(dirname "$0")/../harness.sh"
DIR=$CASES/ritter2d
XML=$DIR/ritter2d_Def.xml

expect 0 "vres-gencase --check accepts the case" "$BIN/vres-gencase" -q --check "$XML"
for dp in 0.05 0.025; do
    expect 0 "generate it at dp $dp" "$BIN/vres-gencase" -q --dp "$dp" "$XML" -o "$T/c.h5"
    paste <(values /Domains/D0/Type "$T/c.h5") <(values /Domains/D0/Position "$T/c.h5" | paste - - -) >"$T/p"
    want=$(awk -v d="$dp" 'BEGIN {printf "%d", (5 / d) * (1 / d) + 0.5}')
    got=$(awk '$1 == 0' "$T/p" | wc -l)
    check "dp $dp: the reservoir holds (5/dp)(1/dp) = $want fluid particles ($got)" [ "$got" -eq "$want" ]
    got=$(awk '$1 == 0 {if (!n++ || $2 > x) x = $2; if (n == 1 || $2 < a) a = $2; if (n == 1 || $4 > z) z = $4}
               END {printf "%.9g %.9g %.9g", a, x, z}' "$T/p")
    check "dp $dp: reservoir faces at x = -5, 0 and z = 1 m (extreme particles at $got)" \
        awk -v g="$got" -v d="$dp" 'BEGIN {split(g, v, " ")
            exit !((v[1] - d / 2 + 5) ^ 2 < 1e-18 && (v[2] + d / 2) ^ 2 < 1e-18 && (v[3] + d / 2 - 1) ^ 2 < 1e-18)}'
done
# Ritter: h/h0 = 1 for xi <= -1, (2 - xi)^2 / 9 up to xi = 2, 0 beyond (its file's header)
dev=$(awk -F, '!/^#/ && $1 + 0 == $1 { x = $1 + 0; r = (x < -1) ? 1 : (x > 2) ? 0 : (2 - x) ^ 2 / 9
                                       d = $2 - r; if (d * d > m) m = d * d; n++ }
               END {printf "%d %.3g", n, sqrt(m)}' "$DIR/ritter_profile.csv")
check "ritter_profile.csv: (2 - xi)^2/9 to 1e-4 over -1.5 <= xi <= 2.4 (points, max deviation: $dev)" \
    awk -v d="$dev" 'BEGIN {split(d, v, " "); exit !(v[1] >= 30 && v[2] < 1e-4)}'
expect 0 "check --help" "$DIR/check" --help
expect_err 2 "usage" "check: an unknown option is a usage error" "$DIR/check" --bogus
mkdir -p "$T/empty"
expect_err 1 "not a vres-run directory" "check: a directory without a run is refused" "$DIR/check" "$T/empty"
