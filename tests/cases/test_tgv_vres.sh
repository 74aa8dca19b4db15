#!/usr/bin/env bash
# cases/taylor_green_vres2d: the Taylor-Green vortex with a refined centre box through the coupled
# pipeline vres-gencase | vres-partition | tgv_init.py | vres-run, at a coarse dp (0.04, box at
# 0.02) over the first 0.2 s (about 360 steps, 2 s of run). The partition of the periodic square
# has two domains with the box [0.24, 0.76]^2 m; tgv_init.py puts the analytical vortex on the
# fluid AND buffer particles of both domains (checked here against the formula with awk); the
# coupled run starts and its kinetic energy (owned fluid, each piece once) follows the
# single-resolution run's: E/E_exact of the two within 3% of each other at every output
# (measured: 1.0% at most, at t = 0.15 s; the box's own energy differs by up to 4.6% because
# particles cross its edge one by one at this dp, so the whole square's is compared).
# Needs python3 with h5py and numpy (tgv_init.py).
source "$(dirname "$0")/../harness.sh"
if ! python3 -c 'import h5py, numpy' 2>/dev/null; then
    ok "# SKIP python3 with h5py and numpy not found"; exit 0
fi
DIR=$CASES/taylor_green_vres2d
XML=$DIR/taylor_green_vres2d_Def.xml

expect 0 "vres-gencase at dp 0.04" "$BIN/vres-gencase" -q --dp 0.04 "$XML" -o "$T/c.h5"
expect 0 "vres-partition of the periodic square" "$BIN/vres-partition" -q "$T/c.h5" -o "$T/p.h5"
check "two domains" [ "$(h5ls "$T/p.h5/Domains" | wc -l)" -eq 2 ]
box=$(for a in box_min box_max; do h5dump -a "/Domains/D1/$a" "$T/p.h5" | awk '/\(0\):/ {sub(/.*\(0\): */, ""); print}'; done | paste -s -d ' ')
check "D1's box is the case's [0.24, 0.76]^2 ($box)" [ "$box" = "0.24, 0, 0.24 0.76, 0, 0.76" ]
expect 0 "tgv_init.py sets the vortex after the partition" python3 "$ROOT/pipelines/tgv_init.py" "$T/p.h5"
# the velocity of every fluid and buffer particle of both domains against u = -cos(2 pi x) sin(2 pi z),
# w = sin(2 pi x) cos(2 pi z) (L = 1 m, origin 0); the largest deviation, and the buffers counted
dev() {
    paste <(values "/Domains/D$1/Type" "$T/p.h5") <(values "/Domains/D$1/Position" "$T/p.h5" | paste - - -) \
          <(values "/Domains/D$1/Velocity" "$T/p.h5" | paste - - -) |
        awk 'BEGIN {P = 2 * atan2(0, -1)} $1 == 0 || $1 == 1 {u = -cos(P * $2) * sin(P * $4); w = sin(P * $2) * cos(P * $4)
             d = ($5 - u) ^ 2 + ($7 - w) ^ 2; if (d > m) m = d; nb += $1 == 1} END {printf "%.3g %d\n", sqrt(m), nb}'
}
read -r d0 b0 < <(dev 0)
read -r d1 b1 < <(dev 1)
check "the vortex on D0's fluid and its $b0 buffer particles (largest deviation $d0 m/s)" \
    awk -v d="$d0" -v n="$b0" 'BEGIN {exit !(n > 0 && d < 1e-6)}'
check "the vortex on D1's fluid and its $b1 buffer particles (largest deviation $d1 m/s)" \
    awk -v d="$d1" -v n="$b1" 'BEGIN {exit !(n > 0 && d < 1e-6)}'

# the coupled and the single-resolution runs, 0.2 s each
expect 0 "check --vres at dp 0.04 to t = 0.2 s: the coupled run completes" \
    "$DIR/check" --threads 1 --dp 0.04 --tmax 0.2 --vres -o "$T/vres"
check "it ran two domains" grep -q -x 'domains	2' "$OUT"
expect 0 "check --single at dp 0.04 to t = 0.2 s" "$DIR/check" --threads 1 --dp 0.04 --tmax 0.2 --single -o "$T/single"
check "it ran one domain" grep -q -x 'domains	1' "$OUT"
# profile.tsv: t, E_box/E0, exp(2 b t), E_all/E0; compare E_all/exp(2 b t) output by output
worst=$(paste "$T/vres/profile.tsv" "$T/single/profile.tsv" |
    awk 'NF == 8 {n++; r = ($4 / $3) / ($8 / $7) - 1; if (r < 0) r = -r; if (r > m) m = r} END {if (n != 5) print "nan"; else printf "%.4f", m}')
check "the whole square's E/E_exact of the coupled run within 3% of the single run's at the 5 outputs ($worst)" \
    awk -v w="$worst" 'BEGIN {exit !(w == w + 0 && w < 0.03)}'
