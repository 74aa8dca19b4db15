#!/usr/bin/env bash
# The stability verdict (pipelines/stability.sh, used by cases/stiff_*/check; DESIGN section
# 7): a stiff run passes when it completes with finite fields, its fluid mass and no particle
# faster than sound, or when it stops with exit 3, a diagnosis naming the particle and a
# readable snap_last_good.h5; anything else fails. Quick runs here: the high-speed impact
# (cases/stiff_impact2d) at dp 0.05 m through its first impact on the far wall (0.4 s), and a
# dam break stopped on purpose (RhopOutMax 1003 kg/m^3, crossed at once). Then the verdict on
# doctored copies, which it must reject: a NaN in run.tsv, exit 3 without snap_last_good.h5,
# exit 3 with a diagnosis that names no particle, an exit status of 1, a run stopped early.
source "$(dirname "$0")/../harness.sh"
VRES_ME=test_stability
source "$ROOT/pipelines/vreslib.sh"
source "$ROOT/pipelines/stability.sh"
# verdict_of RUNDIR STATUS LOG: the verdict line of stability_verdict (it exits, so a subshell)
verdict_of() { (stability_verdict "$@" 2>/dev/null) | awk -F'\t' '$1 == "verdict" {print $2}'; }

expect 0 "stiff_impact2d: check passes at dp 0.05 to 0.4 s" \
    "$CASES/stiff_impact2d/check" --threads 1 --dp 0.05 --tmax 0.4 -o "$T/imp"
cp "$OUT" "$T/imp.result"
check "the run completed" grep -q -P '^outcome\tcompleted$' "$T/imp.result"
check "no fluid mass lost (fluid_mass_change 0)" grep -q -P '^fluid_mass_change\t0$' "$T/imp.result"
# the error is the largest speed over c0 (a number below its tolerance 1), the density deviation reported
check "the error is the Mach number, below 1" awk -F'\t' '$1 == "error" {e = $2; n++} END {exit !(n == 1 && e > 0 && e < 1)}' "$T/imp.result"
check "the largest density deviation is reported, above 0" awk -F'\t' '$1 == "max_density_deviation" {e = $2; n++} END {exit !(n == 1 && e > 0 && e < 0.3)}' "$T/imp.result"
check "no non-finite value in the last snapshot" grep -q -P '^nonfinite_values\t0$' "$T/imp.result"
# the front has hit the far wall by 0.4 s: Ritter's 2 sqrt(g H) = 10.8 m/s bounds the speed
# of a collapsing column from above; the impact's jet reaches several m/s
vmax=$(awk -F'\t' '$1 == "max_speed_m_s" {print $2}' "$T/imp.result")
check "impact speeds of several m/s reached ($vmax m/s, 3 to 15)" awk -v v="$vmax" 'BEGIN {exit !(v > 3 && v < 15)}'

"$BIN/vres-gencase" -q --dp 0.04 --set RhopOutMax=1003 "$CASES/dambreak_front2d/dambreak_front2d_Def.xml" -o "$T/db.h5" ||
    notok "gencase the dam break"
"$BIN/vres-run" -q --threads 1 --tout 0.05 "$T/db.h5" -o "$T/stop" 2>"$T/stop.log"
check "a density limit stops the dam break with exit 3" [ $? -eq 3 ]
check "verdict on the stopped run: pass" [ "$(verdict_of "$T/stop" 3 "$T/stop.log")" = pass ]

cp -r "$T/imp" "$T/nan"; sed -i '$ s/\t[0-9.e+-]*$/\tnan/' "$T/nan/run.tsv"
check "verdict with a NaN in run.tsv: FAIL" [ "$(verdict_of "$T/nan" 0 /dev/null)" = FAIL ]
cp -r "$T/imp" "$T/norows"; sed -i '/^[^#]/d' "$T/norows/run.tsv"
check "verdict on a run.tsv without rows: FAIL" [ "$(verdict_of "$T/norows" 0 /dev/null)" = FAIL ]
cp -r "$T/stop" "$T/nolast"; rm "$T/nolast/snap_last_good.h5"
check "verdict on exit 3 without snap_last_good.h5: FAIL" [ "$(verdict_of "$T/nolast" 3 "$T/stop.log")" = FAIL ]
echo "vres-run: unstable at step 12, t = 0.001 s: something went wrong" >"$T/vague.log"
check "verdict on exit 3 with a diagnosis naming no particle: FAIL" [ "$(verdict_of "$T/stop" 3 "$T/vague.log")" = FAIL ]
check "verdict on exit 1: FAIL" [ "$(verdict_of "$T/imp" 1 /dev/null)" = FAIL ]
cp -r "$T/imp" "$T/short"; rm "$(ls "$T/short"/snap_[0-9]*.h5 | tail -1)"
check "verdict on a run that stopped before TimeMax with exit 0: FAIL" [ "$(verdict_of "$T/short" 0 /dev/null)" = FAIL ]
