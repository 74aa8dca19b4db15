#!/usr/bin/env bash
# vres-run on still water (cases/hydrostatic2d: a 2-D tank 1 m wide, water H = 0.5 m deep,
# dp 0.02 m, DBC walls of 3 layers): the run keeps the fluid mass exactly, stays finite, keeps
# the water nearly at rest, and the pressure at the bottom matches the hydrostatic
# p = rho0 g (H - z) (the analytical solution at rest).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
H=0.5 G=9.81 RHO0=1000 DP=0.02


expect 0 "gencase the still-water tank" "$BIN/vres-gencase" "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5"
mass0=$(paste <(values /Domains/D0/Type "$T/tank.h5") <(values /Domains/D0/Mass "$T/tank.h5") |
        awk '$1 == 0 {m += $2} END {printf "%.9g", m}')

# 0.6 s is 13 periods of the slowest acoustic mode 4H/c0 = 0.046 s (c0 = 43.4 m/s)
expect 0 "run 0.6 s of still water" "$RUN" -q --tmax 0.6 --tout 0.008 "$T/tank.h5" -o "$T/run"
TSV=$T/run/run.tsv
check "run.tsv header names the columns" grep -q '^# time_s	step	dt_s	n_fluid	n_wall	mass_fluid_kg	max_speed_m_s' "$TSV"
nl=$(grep -vc '^#' "$TSV")
check "one run.tsv line per snapshot ($nl lines)" [ "$nl" -eq "$(ls "$T/run"/snap_*.h5 | wc -l)" ]
check "snapshot 0 is at t = 0" [ "$(awk 'NR == 2 {print $1}' "$TSV")" = 0 ]
last=$(awk 'END {print $1}' "$TSV")
check "the run reaches 0.6 s (last line $last)" awk -v t="$last" 'BEGIN {exit !(t >= 0.6)}'
# no particle is ever removed, so the fluid mass is the store's, to the last digit printed
check "fluid mass conserved exactly ($mass0 kg)" awk -F'\t' -v m="$mass0" '!/^#/ {n++; if ($6 != m) bad = 1} END {exit bad || !n}' "$TSV"
check "no NaN or Inf in run.tsv" bash -c "! grep -qiE 'nan|inf' '$TSV'"
values /Domains/D0/Density "$(ls "$T/run"/snap_*.h5 | tail -1)" >"$T/rho.txt"
check "last snapshot's densities all finite" [ "$(grep -c -E '^[0-9.eE+-]+$' "$T/rho.txt")" -eq "$(values /Domains/D0/Type "$T/tank.h5" | wc -l)" ]
# At rest the reference speed is 0; an unstable or leaking tank moves at sqrt(g dp) = 0.44 m/s
# or more, so bound the spurious currents (from the DBC start, where the walls begin at rho0)
# at 5% of the long-wave speed sqrt(g H) = 2.21 m/s: 0.11 m/s.
vmax=$(awk -F'\t' '!/^#/ {n++; if ($7 > v) v = $7} END {if (n) print v + 0; else print "none"}' "$TSV") # none: no row read
check "max speed $vmax m/s < 0.05 sqrt(g H)" awk -v v="$vmax" -v g=$G -v h=$H 'BEGIN {exit !(v != "none" && v < 0.05 * sqrt(g * h))}'

# Bottom pressure: the mean over the bottom fluid row (z = dp/2) and over the snapshots in
# (0.2, 0.6] s. The walls start at rho0 (zero pressure), so the column drops onto them and
# rings: an acoustic oscillation of about +-15% that alpha = 0.01 hardly damps; the time mean
# over 50 snapshots and about 9 periods leaves about 1% of it. DBC holds the fluid a wall gap
# off the wall, which moves the bottom row by a fraction of dp: rho0 g dp/2 = 2% of the
# bottom pressure. Tolerance: 3%.
psum=0; nsnap=0
for k in $(awk -F'\t' '!/^#/ {if ($1 > 0.2) print NR - 2}' "$TSV"); do
    f=$(printf '%s/run/snap_%05d.h5' "$T" "$k")
    p=$(paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | awk 'NR % 3 == 0') \
              <(values /Domains/D0/Pressure "$f") | awk -v dp=$DP '$1 == 0 && $2 < dp {s += $3; n++} END {print s / n}')
    psum=$(awk -v a="$psum" -v b="$p" 'BEGIN {print a + b}'); nsnap=$((nsnap + 1))
done
pbot=$(awk -v s="$psum" -v n=$nsnap 'BEGIN {print s / n}')
pref=$(awk -v r=$RHO0 -v g=$G -v h=$H -v dp=$DP 'BEGIN {print r * g * (h - dp / 2)}')
err=$(awk -v p="$pbot" -v q="$pref" 'BEGIN {e = (p - q) / q; printf "%.4f", e < 0 ? -e : e}')
echo "# bottom pressure over $nsnap snapshots: $pbot Pa against rho0 g (H - dp/2) = $pref Pa: relative error $err"
check "bottom pressure within 3% of hydrostatic (error $err)" awk -v e="$err" 'BEGIN {exit !(e < 0.03)}'
