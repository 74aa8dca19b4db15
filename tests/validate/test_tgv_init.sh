#!/usr/bin/env bash
# pipelines/tgv_init.py writes the Taylor-Green vortex into a store made by vres-gencase
# (cases/taylor_green2d): at a particle, u = -U cos(2 pi x/L) sin(2 pi z/L),
# w = U sin(2 pi x/L) cos(2 pi z/L), p = -(rho0 U^2/4)(cos 4 pi x/L + cos 4 pi z/L) and rho
# from p by the inverse Tait equation (refdata/taylor_green_2d_analytical.csv); the history
# gains a line; vres-run accepts the store. It refuses a store that is not a vres store.
# In 3-D (cases/bench_tgv3d, the periodic cube of make bench's scaling table) it sets the
# vortex of Taylor and Green (1937): u = U sin kx cos ky cos kz, v = -U cos kx sin ky cos kz,
# w = 0, p = (rho0 U^2/16)(cos 2kx + cos 2ky)(cos 2kz + 2), k = 2 pi/L.
# Needs python3 with h5py and numpy (the check of cases/taylor_green2d does too; Debian's
# /usr/bin/python3 when the first python3 on the PATH lacks them, as vreslib's need_h5py).
source "$(dirname "$0")/../harness.sh"
source "$ROOT/pipelines/vreslib.sh"
if ! need_h5py; then
    ok "# SKIP python3 with h5py and numpy not found"; exit 0
fi
expect 0 "gencase the vortex at dp 0.05 (20 x 20)" "$BIN/vres-gencase" -q --dp 0.05 "$CASES/taylor_green2d/taylor_green2d_Def.xml" -o "$T/tgv.h5"
expect 0 "tgv_init.py sets the fields" python3 "$ROOT/pipelines/tgv_init.py" "$T/tgv.h5" --U 2
# every particle against the formulas (L = 1 m, U = 2 m/s, rho0 = 1000, c0 = 10 m/s, gamma 7)
bad=$(particles "$T/tgv.h5" | awk 'BEGIN {PI = atan2(0, -1); B = 100 * 1000 / 7}
    { kx = 2 * PI * $2; kz = 2 * PI * $4
      u = -2 * cos(kx) * sin(kz); w = 2 * sin(kx) * cos(kz); p = -(1000 * 4 / 4) * (cos(2 * kx) + cos(2 * kz))
      r = 1000 * (1 + p / B) ^ (1 / 7)
      if ((($5 - u) ^ 2 + ($7 - w) ^ 2) > 1e-10 || ($9 - p) ^ 2 > 1e-4 || ($8 - r) ^ 2 > 1e-6) n++ }
    END {print n + 0}')
check "400 particles carry the vortex's u, w, p and rho ($bad differ)" [ "$bad" -eq 0 ]
check "the largest speed is U = 2 m/s on the lattice (sin = 0.988 at the nearest node)" \
    awk -v v="$(particles "$T/tgv.h5" | awk '{s = sqrt($5 * $5 + $7 * $7); if (s > m) m = s} END {print m}')" 'BEGIN {exit !(v > 1.95 && v <= 2)}'
expect 0 "vres-info reads the store" "$BIN/vres-info" "$T/tgv.h5"
top=$(grep -A1 -E '^history' "$OUT" | tail -1)
check "its history names tgv_init.py first ($top)" grep -q 'tgv_init.py' <<<"$top"
expect 0 "vres-run runs it a few steps" "$BIN/vres-run" -q --threads 1 --tmax 0.01 "$T/tgv.h5" -o "$T/run"
expect 1 "a file that is not a store is refused" python3 "$ROOT/pipelines/tgv_init.py" "$CASES/taylor_green2d/taylor_green2d_Def.xml"

# the 3-D vortex (L = 1 m, U = 2 m/s, rho0 = 1000, c0 = 10 m/s, gamma 7), every particle
expect 0 "gencase the periodic cube at dp 0.1 (10 x 10 x 10)" "$BIN/vres-gencase" -q --dp 0.1 "$CASES/bench_tgv3d/bench_tgv3d_Def.xml" -o "$T/tgv3.h5"
expect 0 "tgv_init.py sets the 3-D fields" python3 "$ROOT/pipelines/tgv_init.py" "$T/tgv3.h5" --U 2
read -r n bad < <(particles "$T/tgv3.h5" | awk 'BEGIN {PI = atan2(0, -1); B = 100 * 1000 / 7}
    { kx = 2 * PI * $2; ky = 2 * PI * $3; kz = 2 * PI * $4
      u = 2 * sin(kx) * cos(ky) * cos(kz); v = -2 * cos(kx) * sin(ky) * cos(kz)
      p = (1000 * 4 / 16) * (cos(2 * kx) + cos(2 * ky)) * (cos(2 * kz) + 2)
      r = 1000 * (1 + p / B) ^ (1 / 7)
      if ((($5 - u) ^ 2 + ($6 - v) ^ 2 + $7 ^ 2) > 1e-10 || ($9 - p) ^ 2 > 1e-4 || ($8 - r) ^ 2 > 1e-6) m++ }
    END {print NR, m + 0}')
check "1000 particles read ($n)" [ "$n" -eq 1000 ]
check "every one carries the 3-D vortex's u, v, w, p and rho ($bad differ)" [ "$bad" -eq 0 ]
check "the fields vary: the largest |u| is near U (sin and cos of the nodes at 0.05 + 0.1 i m)" \
    awk -v v="$(particles "$T/tgv3.h5" | awk '{s = $5 < 0 ? -$5 : $5; if (s > m) m = s} END {print m}')" 'BEGIN {exit !(v > 1.6 && v <= 2)}'
expect 0 "vres-run runs the cube a few steps (periodic along x, y and z)" "$BIN/vres-run" -q --threads 1 --tmax 0.01 "$T/tgv3.h5" -o "$T/run3"
