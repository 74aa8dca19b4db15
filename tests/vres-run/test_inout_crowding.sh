#!/usr/bin/env bash
# vres-run's crowding watch on inlet/outlet zones (lib/solver_inout.c, vres_inout_watch): the
# velocity step of cases/stiff_inlet_step2d with its inlet's density fixed at rho0
# (imposerhop mode 0, which the case used until 2026-12-03) over-determines the inlet, and
# particles pile up in front of it (500 fluid particles before the step, 550 at 1 s, with the
# density 1% above rho0; cases/stiff_inlet_step2d/README.md): vres-run says so by 0.9 s,
# naming the zone, its line and why. The case as shipped (density extrapolated) runs to the
# same time without the warning. Each run is 1 s of the case at its dp (0.04 m), about 900
# steps of 1000 particles.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/stiff_inlet_step2d/stiff_inlet_step2d_Def.xml
sed '0,/<imposerhop mode="2"[^>]*>/s//<imposerhop mode="0" \/>/' "$CASE" >"$T/fixed.xml"
check "the variant fixes the inlet's density, and only the inlet's" \
    [ "$(grep -c '<imposerhop mode="0" />' "$T/fixed.xml") $(grep -c '<imposerhop mode="2"' "$T/fixed.xml")" = "1 1" ]
line=$(grep -n '<inoutzone' "$T/fixed.xml" | head -1 | cut -d: -f1)
expect 0 "vres-gencase the variant" "$BIN/vres-gencase" -q "$T/fixed.xml" -o "$T/fixed.h5"
expect 0 "run it to 1 s" "$BIN/vres-run" --threads 1 --tmax 1 --tout 0.1 "$T/fixed.h5" -o "$T/f"
check "said: fluid piles up in front of zone 1 (case line $line), the two imposed quantities named" \
    grep -q -E "warning: t = 0\.[0-9]+ s, step [0-9]+: inlet/outlet zone 1 \(case line $line\): the fluid within 0\.32 m of its face claims 1\.[2-9][0-9] times the room it has .*imposes both velocity and density.*imposerhop mode 2" "$ERR"
check "said once for that zone" [ "$(grep -c 'inlet/outlet zone 1 (case line [0-9]*): the fluid within' "$ERR")" -eq 1 ]
n=$(awk -F'\t' '!/^#/ {n = $4} END {print n + 0}' "$T/f/run.tsv")
check "the pile-up is real: $n fluid particles at 1 s, 500 before the step" [ "$n" -ge 530 ]
expect 0 "vres-gencase the case as shipped" "$BIN/vres-gencase" -q "$CASE" -o "$T/ok.h5"
expect 0 "run it to 1 s" "$BIN/vres-run" --threads 1 --tmax 1 --tout 0.1 "$T/ok.h5" -o "$T/o"
check "no crowding said with the density extrapolated" bash -c "! grep -q 'times the room it has' '$ERR'"
