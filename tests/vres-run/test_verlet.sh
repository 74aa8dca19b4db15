#!/usr/bin/env bash
# vres-run with the Verlet scheme (StepAlgorithm=1, VerletSteps=40) on still water
# (cases/hydrostatic2d, DBC walls, dp 0.02 m), 0.3 s. Reference: hydrostatics, as
# test_hydrostatic.sh checks the Symplectic scheme: the run stays finite and nearly at rest
# (max speed below 5% of sqrt(g H): a wrong leapfrog factor, or Euler steps that never come,
# makes the column blow up or ring at sqrt(g dp) and more), keeps the fluid mass, and the bottom
# pressure averaged over the bottom row and the snapshots in (0.1, 0.3] s lies within 3% of
# rho0 g (H - dp/2) (the reasoning of test_hydrostatic.sh: ringing of +-15% that the average
# leaves at about 1%, and the DBC gap's 2%; measured 0.3%, 2026-11).
source "$(dirname "$0")/../harness.sh"
H=0.5 G=9.81 RHO0=1000 DP=0.02
expect 0 "gencase the tank with StepAlgorithm=1" "$BIN/vres-gencase" --set StepAlgorithm=1 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5"
expect 0 "run 0.3 s with Verlet" "$BIN/vres-run" --threads 1 --tmax 0.3 --tout 0.008 "$T/tank.h5" -o "$T/run"
check "modules name Verlet" grep -q 'verlet(euler every 40)' "$ERR"
TSV=$T/run/run.tsv
check "fluid mass conserved" awk -F'\t' '!/^#/ {if (!n++) m = $6; else if ($6 != m) bad = 1} END {exit bad || !n}' "$TSV"
vmax=$(awk -F'\t' '!/^#/ {n++; if ($7 > v) v = $7} END {if (n) print v + 0; else print "none"}' "$TSV") # none: no row read
check "max speed $vmax m/s < 0.05 sqrt(g H)" awk -v v="$vmax" -v g=$G -v h=$H 'BEGIN {exit !(v != "none" && v < 0.05 * sqrt(g * h))}'
psum=0; nsnap=0
for k in $(awk -F'\t' '!/^#/ {if ($1 > 0.1) print NR - 2}' "$TSV"); do
    f=$(printf '%s/run/snap_%05d.h5' "$T" "$k")
    p=$(paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | awk 'NR % 3 == 0') \
              <(values /Domains/D0/Pressure "$f") | awk -v dp=$DP '$1 == 0 && $2 < dp {s += $3; n++} END {print s / n}')
    psum=$(awk -v a="$psum" -v b="$p" 'BEGIN {print a + b}'); nsnap=$((nsnap + 1))
done
pbot=$(awk -v s="$psum" -v n=$nsnap 'BEGIN {print s / n}')
pref=$(awk -v r=$RHO0 -v g=$G -v h=$H -v dp=$DP 'BEGIN {print r * g * (h - dp / 2)}')
err=$(awk -v p="$pbot" -v q="$pref" 'BEGIN {e = (p - q) / q; printf "%.4f", e < 0 ? -e : e}')
echo "# Verlet: max speed $vmax m/s; bottom pressure over $nsnap snapshots $pbot Pa against $pref Pa: error $err"
check "bottom pressure within 3% of hydrostatic (error $err)" awk -v e="$err" 'BEGIN {exit !(e < 0.03)}'
