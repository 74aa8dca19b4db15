#!/usr/bin/env bash
# Fluid that leaves the simulation domain is excluded with a record, never dropped silently
# (issue 3 item 9; DualSPHysics excludes such particles too): the still-water tank with
# gravity turned upwards (+9.81 m/s^2) throws its water out through the open top, where the
# domain ends 0.075 m above the 0.7 m walls. Each exclusion is a line of excluded.tsv; run.tsv
# counts them and its fluid mass falls by one particle mass each; when no fluid is left the run
# stops with exit 3 and a last good snapshot. MinFluidStop stops it earlier.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
TANK=$CASES/hydrostatic2d/hydrostatic2d_Def.xml

"$BIN/vres-gencase" -q --dp 0.05 --set 'gravity=0,0,9.81' "$TANK" -o "$T/up.h5" || notok "gencase the upside-down tank"
expect_err 3 'unstable at step [0-9]+, t = [0-9.e-]+ s: 0 fluid particles left' \
    "all the water thrown out: exit 3 when none is left" "$RUN" --threads 2 --tmax 1 --tout 0.1 "$T/up.h5" -o "$T/run"
check "one message per step with exclusions, naming ids" \
    grep -q -E 'fluid particles? left the simulation domain and (is|are) excluded \(id [0-9]+' "$ERR"
n=$(grep -c -v '^#' "$T/run/excluded.tsv")
check "excluded.tsv: one line per fluid particle (200, got $n)" [ "$n" -eq 200 ]
check "each line: time, step, id, fluid, above the domain top 0.775 m, the reason" \
    awk -F'\t' '!/^#/ && !($4 == "fluid" && $8 > 0.775 && $13 == "left the simulation domain") {exit 1}' "$T/run/excluded.tsv"
check "no id twice" [ "$(grep -v '^#' "$T/run/excluded.tsv" | cut -f3 | sort -u | wc -l)" -eq 200 ]
# run.tsv: n_excluded (col 12) grows, n_fluid (col 4) + n_excluded stays 200, mass = 2.5 kg per particle
check "run.tsv: fluid + excluded = 200 and mass = 2.5 kg x fluid on every line" \
    awk -F'\t' '!/^#/ { if ($4 + $12 != 200 || ($6 - 2.5 * $4)^2 > 1e-9) exit 1 }' "$T/run/run.tsv"
check "run.tsv: some line between none and all excluded" \
    awk -F'\t' '!/^#/ && $12 > 0 && $12 < 200 {f = 1} END {exit !f}' "$T/run/run.tsv"
expect 0 "snap_last_good.h5 is readable" "$BIN/vres-info" "$T/run/snap_last_good.h5"

"$BIN/vres-gencase" -q --dp 0.05 --set 'gravity=0,0,9.81' --set MinFluidStop=0.5 "$TANK" -o "$T/half.h5" ||
    notok "gencase with MinFluidStop 0.5"
expect_err 3 'fluid particles left, below MinFluidStop=0.5 of the 200 at the start' \
    "MinFluidStop=0.5: stops when fewer than 100 are left" "$RUN" --tmax 1 --tout 0.1 "$T/half.h5" -o "$T/half"
left=$(values /Domains/D0/Type "$T/half/snap_last_good.h5" | awk '$1 == 0' | wc -l)
check "its last good state holds the fluid left (under 100, got $left)" [ "$left" -lt 100 -a "$left" -gt 0 ]

# a restart in the same directory trims excluded.tsv to its steps and appends after them: one
# header, each of the 200 particles once
expect_err 3 '0 fluid particles left' "restart from snap_00003.h5 excludes the rest again" \
    "$RUN" --threads 2 --restart "$T/run/snap_00003.h5"
check "excluded.tsv after the restart: one header line" [ "$(grep -c '^#' "$T/run/excluded.tsv")" -eq 1 ]
check "excluded.tsv after the restart: 200 distinct ids" \
    [ "$(grep -v '^#' "$T/run/excluded.tsv" | cut -f3 | sort -u | wc -l)" -eq 200 -a "$(grep -c -v '^#' "$T/run/excluded.tsv")" -eq 200 ]
