#!/usr/bin/env bash
# vres-run with fluid flowing in through an outlet (cases/stiff_inlet_reverse2d, shortened: the
# stream runs at -0.5 m/s, towards zone 1, which draws it out, until 0.2 s; zone 1's velocity
# then turns to +0.5 m/s by 1.2 s; run to 1.6 s at dp 0.05): handled, and said. The outlet
# (velocity extrapolated, rho0) sees fluid flowing in from the first step: its back creates
# particles from that inflow as an inlet's does, and vres-run says so on stderr, and again
# when the flow through a zone changes direction; the books balance. Without the notes the
# reverse flow would be silent (issue 8 item 5). Also: a parabolic inlet profile (<velocity3>)
# is what the inlet's particles carry.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
CASE=$CASES/stiff_inlet_reverse2d/stiff_inlet_reverse2d_Def.xml
sed 's|<timevalue time="2" v="-0.5" />|<timevalue time="0.2" v="-0.5" />|; s|<timevalue time="3" v="0.5" />|<timevalue time="1.2" v="0.5" />|' \
    "$CASE" >"$T/rev.xml"
check "the shortened case turns from 0.2 to 1.2 s" grep -q '<timevalue time="1.2" v="0.5" />' "$T/rev.xml"
expect 0 "vres-gencase stiff_inlet_reverse2d at dp 0.05" "$BIN/vres-gencase" -q --dp 0.05 "$T/rev.xml" -o "$T/case.h5"
expect 0 "run to 1.6 s" "$RUN" --threads 1 --tmax 1.6 --tout 0.2 "$T/case.h5" -o "$T/a"
check "said at the first step: fluid flows in through the outlet (zone 2)" \
    grep -q -E 'warning: inlet/outlet zone 2 \(case line [0-9]+\): from t = 0\.00[0-9]* s fluid flows in through it: its back creates particles' "$ERR"
check "said when the stream turned: fluid flows out through the outlet" \
    grep -q -E 'warning: inlet/outlet zone 2 \(case line [0-9]+\): from t = [0-9.e+-]+ s fluid flows out through it$' "$ERR"
check "said: fluid flows in through zone 1 once its velocity turned" \
    grep -q -E 'warning: inlet/outlet zone 1 \(case line [0-9]+\): from t = [0-9.e+-]+ s fluid flows in through it' "$ERR"
L=$T/a/ledger.tsv
zcol() { awk -F'\t' -v z="$1" -v c="$2" '$3 == z {v = $c} END {print v + 0}' "$L"; }
check "the outlet created particles after its fill of 4 x 8 ($(zcol Z2 8))" [ "$(zcol Z2 8)" -gt 32 ]
check "the outlet's particles became fluid ($(zcol Z2 10))" [ "$(zcol Z2 10)" -gt 0 ]
check "fluid entered zone 1 while it drew water out and was converted ($(zcol Z1 11))" [ "$(zcol Z1 11)" -gt 0 ]
check "zone 1 deleted particles past its back ($(zcol Z1 12))" [ "$(zcol Z1 12)" -gt 0 ]
drift=$(awk -F'\t' '!/^#/ {d = $20; if (d < 0) d = -d; if (d > D) D = d} END {print D + 0}' "$L")
check "the books balance (largest drift $drift)" awk -v d="$drift" 'BEGIN {exit !(d <= 1e-12)}'
u=$(paste <(values /Domains/D0/Type "$T/a/snap_00008.h5") <(values /Domains/D0/Position "$T/a/snap_00008.h5" | paste - - -) \
        <(values /Domains/D0/Velocity "$T/a/snap_00008.h5" | paste - - -) |
    awk '$1 == 0 && $2 >= 0 && $2 <= 2 {u += $5; n++} END {if (n) printf "%.4f\n", u / n; else print "nan"}')
check "the stream has turned by 1.6 s (mean u $u m/s > 0.3)" awk -v u="$u" 'BEGIN {exit !(u > 0.3)}'

# the inlet of cases/poiseuille_inout2d: <velocity3> puts the parabola on its particles
expect 0 "vres-gencase poiseuille_inout2d at dp 0.04" "$BIN/vres-gencase" -q --dp 0.04 \
    "$CASES/poiseuille_inout2d/poiseuille_inout2d_Def.xml" -o "$T/p.h5"
expect 0 "run 2 steps' worth (1e-3 s)" "$RUN" --threads 1 --tmax 0.001 --tout 0.001 "$T/p.h5" -o "$T/p"
last=$(ls "$T"/p/snap_*.h5 | tail -1)
paste <(values /Domains/D0/Type "$last") <(values /Domains/D0/Position "$last" | paste - - -) \
    <(values /Domains/D0/Velocity "$last" | paste - - -) >"$T/pv"
check "the inlet's particles (x < 0) carry u = 6 U (z/L)(1 - z/L) to 1e-5" \
    [ "$(awk '$1 == 5 && $2 < 0 {n++; z = $4 / 0.4; e = $5 - 6 * z * (1 - z); if (e < 0) e = -e; if (e > 1e-5 || $7 != 0) bad++} END {print n + 0, bad + 0}' "$T/pv")" = "40 0" ]
