#!/usr/bin/env bash
# cases/poiseuille_inout2d, reduced: plane Poiseuille flow between an inlet zone (the parabola
# imposed, density extrapolated) and an outlet zone (velocity extrapolated, rho0 imposed), no-slip
# mDBC walls, at dp 0.04 m (L/dp = 10) to the case's 4 s: its check must pass (the developed
# profile within its tolerance at this resolution, the pressure gradient, the flow rate, a steady
# mass and balanced books; README.md there). About 11 s of CPU.
source "$(dirname "$0")/../harness.sh"
expect 0 "poiseuille_inout2d/check --dp 0.04 passes" "$CASES/poiseuille_inout2d/check" --dp 0.04 --threads 1 -o "$T/run"
check "its verdict is pass" grep -q -P '^verdict\tpass$' "$OUT"
err=$(awk -F'\t' '$1 == "error" {print $2}' "$OUT")
check "it measured an error ($err) over some particles" \
    awk -v e="$err" -v n="$(awk -F'\t' '$1 == "particles_measured" {print $2}' "$OUT")" 'BEGIN {exit !(e > 0 && n > 100)}'
