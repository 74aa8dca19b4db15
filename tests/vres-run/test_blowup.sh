#!/usr/bin/env bash
# vres-run stops a run that goes bad with exit 3, one diagnosis line (which particle, where,
# which quantity and value, step and time) and a readable snap_last_good.h5 holding the state
# before it. Two ways to go bad: a density limit the dam break crosses at once (RhopOutMax
# 1003 kg/m^3, just above the column's initial hydrostatic 1002.5), and a DtMin above the
# second step's dt.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml


"$BIN/vres-gencase" -q --dp 0.04 --set RhopOutMax=1003 "$DB" -o "$T/db.h5" || notok "gencase the dam break"
expect_err 3 'unstable at step [0-9]+, t = [0-9.e-]+ s: fluid particle id [0-9]+ at \([-0-9.e]+, 0, [-0-9.e]+\) m: density [0-9.]+ kg/m\^3 outside RhopOutMin\.\.RhopOutMax = 700\.\.1003' \
    "density above RhopOutMax: exit 3 and the diagnosis" "$RUN" --tout 0.05 "$T/db.h5" -o "$T/run"
cp "$ERR" "$T/diag"
check "names the last good state" grep -q -E 'last good state \(step [0-9]+, t = [0-9.e-]+ s\) written to .*/snap_last_good\.h5' "$ERR"
check "snap_last_good.h5 exists" [ -f "$T/run/snap_last_good.h5" ]
expect 0 "vres-info reads snap_last_good.h5" "$BIN/vres-info" "$T/run/snap_last_good.h5"
# the step vres-info reports is the one before the bad step named in the diagnosis
bad=$(grep -o -E 'unstable at step [0-9]+' "$T/diag" | grep -o -E '[0-9]+$')
good=$(grep -o -E 'time +[0-9.e-]+ s, step [0-9]+' "$OUT" | grep -o -E '[0-9]+$')
check "last good step $good is bad step $bad - 1" [ "$good" -eq $((bad - 1)) ]
# in the last good state every fluid density lies within the limits
rmax=$(paste <(values /Domains/D0/Type "$T/run/snap_last_good.h5") <(values /Domains/D0/Density "$T/run/snap_last_good.h5") |
       awk '$1 == 0 && $2 > m {m = $2} END {print m}')
check "last good fluid densities <= 1003 (max $rmax)" awk -v r="$rmax" 'BEGIN {exit !(r <= 1003)}'
check "snap 0 and run.tsv written before the stop" [ -f "$T/run/snap_00000.h5" ] && grep -q '^0	0	' "$T/run/run.tsv"

# a DtMin no step can meet (1 s) is refused before any step (lib/preflight.c,
# tests/vres-run/test_unworkable.sh); one just below the longest step the run can take,
# cflnumber h/c0 = 0.2 x 0.0565685 / 87.6986 = 1.29007e-4 s, passes that and is met by the first
# step (the fluid at rest: no viscous term), not by the second (the column starts to move: the
# viscous rate shortens dt): stopped there, the state after the first step kept
"$BIN/vres-gencase" -q --dp 0.04 --set DtMin=1.29e-4 "$DB" -o "$T/dt.h5" || notok "gencase with DtMin 1.29e-4"
expect_err 3 'unstable at step 2, t = [0-9.e-]+ s: time step [0-9.e-]+ s below DtMin 0\.000129 s' "dt below DtMin: exit 3" \
    "$RUN" --tout 0.05 "$T/dt.h5" -o "$T/run2"
expect 0 "its snap_last_good.h5 is readable" "$BIN/vres-info" "$T/run2/snap_last_good.h5"
check "and holds step 1" grep -q -E 'time +[0-9.e-]+ s, step 1$' "$OUT"

# a coupled run (two domains: cases/stiff_vres_front2d, the dam break through a refinement box)
# stops the same way, and its snap_last_good.h5 is the step's start in every domain, which the
# coupling's exchange at the step's end (conversions, creation, deletion, the sort) must not
# have changed: restarted from it, the run meets the same particle at the same step. (Before
# the check ran ahead of the exchange, a blow-up found after it wrote the step-start copies
# over the exchanged particles: in cases/wedge_entry2d under mDBC, wall types on fluid
# positions.)
FRONT=$CASES/stiff_vres_front2d/stiff_vres_front2d_Def.xml
"$BIN/vres-gencase" -q --set RhopOutMax=1010 "$FRONT" | "$BIN/vres-partition" -q - -o "$T/front.h5" ||
    notok "gencase and partition the coupled dam break"
expect_err 3 'unstable at step [0-9]+, t = [0-9.e-]+ s: fluid particle id [0-9]+ at .* outside RhopOutMin\.\.RhopOutMax = 700\.\.1010' \
    "coupled: density above RhopOutMax, exit 3" "$RUN" --threads 1 --tout 0.05 "$T/front.h5" -o "$T/front"
diag=$(grep -o 'unstable at step .*' "$ERR" | head -1)
check "coupled: names the last good state" grep -q 'last good state .* written to .*/snap_last_good\.h5' "$ERR"
expect_err 3 'unstable at step' "coupled: restarted from snap_last_good.h5, it stops again" \
    "$RUN" --threads 1 --restart "$T/front/snap_last_good.h5" -o "$T/front"
check "coupled: at the same step, the same particle, the same value ($diag)" \
    [ "$(grep -o 'unstable at step .*' "$ERR" | head -1)" = "$diag" ]
