#!/usr/bin/env bash
# vres-run with mDBC walls (Boundary=2, SlipMode=1) on still water: cases/hydrostatic2d (a 2-D
# tank 1 m wide, H = 0.5 m deep, dp 0.02 m, walls drawn as faces with 3 layers, so every wall
# particle has a GenCase-style normal). Reference: hydrostatics, p = rho0 g (H - z).
#  * The wall particles take the density extrapolated from their ghost nodes, so the first
#    wall row (z = -dp/2) carries the pressure of the bottom fluid row (z = dp/2) plus
#    rho0 g dp = 196 Pa; under DBC it carries whatever the continuity equation left
#    (measured: 670 to 880 Pa more than the fluid). Tolerance 25% of 196 Pa: the ghost's
#    first-order estimate is exact for the linear hydrostatic profile, and what is left is
#    the Tait equation's curvature and the ringing of the column (measured 195 to 201 Pa).
#  * No fluid particle ever goes below its starting row z = dp/2 by more than 1% of dp: mDBC
#    holds the fluid where the ghost nodes put the wall (measured: 0.05%; DBC lets the water
#    settle 1.4% of dp into the wall gap at this dp).
#  * The bottom pressure, averaged over the fluid's bottom row and the snapshots in (0.1, 0.3] s,
#    within 3% of rho0 g (H - dp/2): the column starts 1 dp short of its hydrostatic density
#    (GenCase's profile starts at the top particle) and rings at about +-3% for a period of some
#    0.24 s, of which this window holds one (measured +1.2%).
source "$(dirname "$0")/../harness.sh"
H=0.5 G=9.81 RHO0=1000 DP=0.02

expect 0 "gencase the tank with Boundary=2" "$BIN/vres-gencase" --set Boundary=2 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5"
expect 0 "run 0.3 s of still water with mDBC" "$BIN/vres-run" --threads 1 --tmax 0.3 --tout 0.008 "$T/tank.h5" -o "$T/run"
check "modules name mDBC with every wall normal" grep -q 'mdbc-walls(slip=vel0, 390 with normals' "$ERR"
TSV=$T/run/run.tsv
check "fluid mass conserved" awk -F'\t' 'NR == 2 {m = $6} !/^#/ && $6 != m {exit 1}' "$TSV"
: >"$T/rows"
for k in $(awk -F'\t' '!/^#/ {print NR - 2}' "$TSV"); do
    f=$(printf '%s/run/snap_%05d.h5' "$T" "$k")
    t=$(awk -v k="$k" '!/^#/ && n++ == k {print $1}' "$TSV")
    paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | paste - - -) \
          <(values /Domains/D0/Pressure "$f") |
        awk -v t="$t" -v dp=$DP '$1 == 0 && (zmin == "" || $4 < zmin) {zmin = $4}
            $1 == 0 && $4 < dp {pf += $5; nf++}
            $1 != 0 && $4 < 0 && $4 > -dp && $2 > 0 && $2 < 1 {pw += $5; nw++}
            END {print t, zmin, pf / nf, pw / nw}' >>"$T/rows"
done
read zmin pbot dwall < <(awk '{if (z == "" || $2 < z) z = $2} $1 > 0.1 {p += $3; w += $4 - $3; n++}
                             END {print z, p / n, w / n}' "$T/rows")
pref=$(awk -v r=$RHO0 -v g=$G -v h=$H -v dp=$DP 'BEGIN {print r * g * (h - dp / 2)}')
err=$(awk -v p="$pbot" -v q="$pref" 'BEGIN {e = (p - q) / q; printf "%.4f", e < 0 ? -e : e}')
echo "# lowest fluid z $zmin m; wall row minus fluid row $dwall Pa (rho0 g dp = 196.2); bottom pressure $pbot Pa against $pref Pa: error $err"
check "first wall row carries rho0 g dp more than the bottom fluid row ($dwall Pa)" \
    awk -v d="$dwall" 'BEGIN {exit !(d > 0.75 * 196.2 && d < 1.25 * 196.2)}'
check "no fluid sinks into the wall (lowest z $zmin m)" awk -v z="$zmin" -v dp=$DP 'BEGIN {exit !(z > 0.49 * dp)}'
check "bottom pressure within 3% of hydrostatic (error $err)" awk -v e="$err" 'BEGIN {exit !(e < 0.03)}'
