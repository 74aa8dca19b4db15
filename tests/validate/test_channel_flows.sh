#!/usr/bin/env bash
# Quick versions of the Poiseuille and Couette start-up validations (cases/poiseuille2d and
# cases/couette2d; full runs to 1 s in `make validate` and `make sweep`): each channel at its
# validation dp 5e-5 m (L/dp = 20) to t = 0.3 s, compared by its check with the series
# solutions of Morris, Fox & Zhu (1997) (refdata/poiseuille_couette_transient.csv) at every
# snapshot. The checks' tolerances (0.25 and 0.10) come from the DBC walls' no-slip plane about
# dp/2 behind the faces (cases/*/README.md); the early profiles must also be in the right
# place: at t = 0.0225 s the Couette flow has entered only the top part of the channel.
source "$(dirname "$0")/../harness.sh"

for c in poiseuille2d couette2d; do
    expect 0 "$c: check passes at dp 5e-5 to 0.3 s" "$CASES/$c/check" --threads 1 --dp 5e-5 --tmax 0.3 -o "$T/$c"
    cp "$OUT" "$T/$c.result"
    grep -E '^error' "$T/$c.result" | tr '\n' ' ' | sed 's/^/# /'; echo
done
get() { awk -F'\t' -v k="$1" '$1 == k {print $2}' "$T/$2.result"; }
check "poiseuille2d: 400 fluid + 120 wall particles ($(get particles poiseuille2d))" [ "$(get particles poiseuille2d)" = 520 ]
check "couette2d: wall speed read as V0 = 2.5e-5 m/s ($(get wall_speed_m_s couette2d))" \
    awk -v v="$(get wall_speed_m_s couette2d)" 'BEGIN {exit !(v > 2.49e-5 && v < 2.51e-5)}'
# Couette at t = 0.0225 s: the diffusion length sqrt(nu t) = 0.15 L, so the bottom 30% of the
# channel is nearly at rest (the series gives at most 0.06% of V0 there, about erfc(0.7 L /
# (2 sqrt(nu t)))); bound: 1% of V0. The top row (z = 0.975 L) moves at a good part of V0
# (series: 0.91 V0; the DBC wall a fraction of dp behind the face gives the SPH top row 0.8 V0).
f=$(ls "$T/couette2d"/snap_00001.h5)
source "$ROOT/pipelines/vreslib.sh"
read -r ubot utop < <(particles "$f" | awk '$1 == 0 { if ($4 < 3e-4 && ($5 > a || -$5 > a)) a = ($5 < 0 ? -$5 : $5); if ($4 > 9.5e-4 && $5 > b) b = $5 } END {print a + 0, b + 0}')
check "couette2d at t = 0.0225 s: bottom 30% at rest (|u| $ubot < 2.5e-7)" awk -v u="$ubot" 'BEGIN {exit !(u < 2.5e-7)}'
check "couette2d at t = 0.0225 s: top row moving (u $utop > 0.5 V0)" awk -v u="$utop" 'BEGIN {exit !(u > 1.25e-5)}'
