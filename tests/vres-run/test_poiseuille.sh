#!/usr/bin/env bash
# vres-run with laminar viscosity and periodic boundaries: start-up plane Poiseuille flow
# (tests/vres-run/cases/poiseuille2d_Def.xml: walls 1 mm apart, nu = 1e-6 m^2/s, body force
# 2e-4 m/s^2 along x as gravity, periodic along x, dp = L/20, DBC walls). Reference: the series
# solution of Morris, Fox & Zhu (1997) as written in /work/shared/refdata/
# poiseuille_couette_transient.csv (checked here against that file's values), evaluated at
# each snapshot's own time.
source "$(dirname "$0")/../harness.sh"
REF=${VRES_REFDATA:-/work/shared/refdata}/poiseuille_couette_transient.csv
L=0.001 F=2e-4 NU=1e-6 DP=5e-5

# The series u(y, t) for walls at y = 0 and y = W (awk function text, 200 odd terms).
SERIES='function u(y, t, W,   s, n, m, pi) { pi = atan2(0, -1); s = F / (2 * nu) * y * (W - y)
  for (n = 0; n < 200; n++) { m = 2 * n + 1
    s -= 4 * F * W * W / (nu * pi^3 * m^3) * sin(m * pi * y / W) * exp(-m * m * pi * pi * nu * t / (W * W)) }
  return s }'

if [ -r "$REF" ]; then
    # the transcription of the series reproduces the reference file to 1e-3 of its largest value
    dev=$(awk -F, -v F=$F -v nu=$NU -v W=$L "$SERIES"'
          $1 == "poiseuille" && $2 + 0 > 0 { n++; d = u($3, $2, W) - $4; d = d < 0 ? -d : d; if (d > e) e = d }
          END { if (n) printf "%.3g", e / 2.5e-5; else printf "none" }' "$REF")
    check "series matches $REF (largest deviation $dev of u_max)" awk -v e="$dev" 'BEGIN {exit !(e != "none" && e < 1e-3)}'
else
    ok "# SKIP reference file $REF not readable: series checked only through the run below"
fi

expect 0 "gencase the Poiseuille channel" "$BIN/vres-gencase" "$(dirname "$0")/cases/poiseuille2d_Def.xml" -o "$T/ch.h5"
expect 0 "run 0.225 s of start-up flow" "$BIN/vres-run" "$T/ch.h5" -o "$T/run"
check "modules name laminar viscosity and periodic x" grep -q 'laminar-viscosity(nu=1e-06 m^2/s).*periodic(x)' "$ERR"
TSV=$T/run/run.tsv
# 11 rows (t = 0 and the 10 outputs), each with the fluid's mass and count: none read fails
check "fluid mass and count kept on 11 rows" awk -F'\t' '!/^#/ {n++; if ($6 != 0.0005 || $4 != 200) bad = 1} END {exit bad || n != 11}' "$TSV"

# Velocity profile at t = 0.0225, 0.045, 0.1125, 0.225 s (snapshots 1, 2, 5, 10): mean u_x of
# each fluid row against the series at that row and the snapshot's time. DBC walls hold the
# no-slip plane at their first particle row (0.5 dp behind each face), so the channel of the
# series is W = L + dp with y = z + dp/2. Tolerance 4% of the centreline speed: at dp = L/20 the
# SPH Laplacian on the lattice is 2% low (tests/lib/test_solver.c) and the DBC no-slip plane is
# placed to a fraction of dp (0.1 dp moves u by 1%); measured 1.6% to 2.4% (2026-11). Taking
# the faces as walls (W = L) is 9% off at 0.225 s, so the test tells the two apart.
for k in 1 2 5 10; do
    f=$(printf '%s/run/snap_%05d.h5' "$T" $k)
    t=$(awk -v k=$k '!/^#/ && n++ == k {print $1}' "$TSV")
    err=$(paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | paste - - -) \
                <(values /Domains/D0/Velocity "$f" | paste - - -) |
          awk -v t="$t" -v W=$(awk -v l=$L -v d=$DP 'BEGIN {print l + d}') -v F=$F -v nu=$NU -v dp=$DP "$SERIES"'
              $1 == 0 { r = int($4 / dp); sum[r] += $5; cnt[r]++; n++ }
              END { if (!n || t == "") { print "none"; exit }  # no fluid or no time read: fail below
                    uc = u(W / 2, t, W); e = 0
                    for (r in sum) { d = sum[r] / cnt[r] - u((r + 1) * dp, t, W); d = d < 0 ? -d : d; if (d > e) e = d }
                    printf "%.4f %.4e %.4e", e / uc, uc, (sum[9] / cnt[9] + sum[10] / cnt[10]) / 2 }')
    set -- $err none none
    echo "# t = $t s: centreline series $2 m/s, SPH (rows 10, 11) $3 m/s, largest row error $1 of it"
    check "profile at t = $t s within 4% of the series (error $1)" awk -v e="$1" 'BEGIN {exit !(e != "none" && e < 0.04)}'
done
