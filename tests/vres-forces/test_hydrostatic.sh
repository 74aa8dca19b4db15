#!/usr/bin/env bash
# vres-forces on still water: the shipped 2-D tank (cases/hydrostatic2d: 1 m wide, water
# H = 0.5 m deep, DBC walls of 3 layers) with its walls split into three mkbounds (bottom 0,
# left 1, right 2), generated at dp 0.025 m and run for 0.3 s. Reference: hydrostatics, per
# metre of width (L = 1 m): the water's weight W = rho0 g H L = 4905 N/m rests on the bottom,
# and each side wall takes S = rho0 g H^2 / 2 = 1226.25 N/m acting H/3 above the bottom.
#
# Why time means: the walls start at rho0 (no pressure), so the column drops onto them and rings
# acoustically (about +-13% of W at 20 Hz, barely damped); the forces are means over the 50
# snapshots in (0.1, 0.3] s, four periods. The mean of a sinusoid of amplitude A over a window
# that is not a whole number of its periods differs from its centre by up to A/(pi n) for n
# periods: 13%/(4 pi) = 1%. Tolerance on each force: 1% (measured at dp 0.025 m: total vertical
# -0.07%, side walls +0.02%; at dp 0.02 m over (0.1, 0.6] s: -0.12% and -0.15%).
source "$(dirname "$0")/../harness.sh"
FORCES=$BIN/vres-forces
H=0.5 L=1 G=9.81 RHO0=1000 DP=0.025

# the shipped case with the wall drawbox drawn three times: bottom (mk 0), left (1), right (2)
awk '/<setmkbound mk="0" \/>/ {grab = 1}
     grab {block = block $0 "\n"
           if (/<\/drawbox>/) {
               grab = 0; n = split("bottom left right", face, " ")
               for (k = 1; k <= n; k++) {
                   b = block; sub(/mk="0"/, "mk=\"" k - 1 "\"", b)
                   sub(/<boxfill>[^<]*</, "<boxfill>" face[k] "<", b); printf "%s", b
               }
           }
           next}
     {print}' "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" >"$T/tank3_Def.xml"
expect 0 "gencase the tank with three wall mkbounds at dp $DP" "$BIN/vres-gencase" -q --dp $DP "$T/tank3_Def.xml" -o "$T/tank.h5"
"$BIN/vres-info" -t "$T/tank.h5" >"$T/counts.tsv"
check "the tank has fluid and walls of mkbound 0, 1 and 2" \
    [ "$(awk '$2 == "fixed" {printf "%s,", $3}' "$T/counts.tsv")" = "0,1,2," ]
# one thread: the physics does not depend on it, and it keeps the run to a few seconds on a
# machine loaded by other work (OpenMP threads waiting on each other there)
expect 0 "run 0.3 s" "$BIN/vres-run" -q --threads 1 --tmax 0.3 --tout 0.004 "$T/tank.h5" -o "$T/run"

# three calls cover the options: the bottom with the spectrum of its load, the left wall with
# coefficients and their spectrum, the right wall plain to stdout
expect 0 "forces on the bottom, --spectrum fz from 0.1 s" "$FORCES" --mk 0 --spectrum fz --from 0.1 "$T/run" -o "$T/bottom.tsv"
check "nothing on stdout with -o" [ ! -s "$OUT" ]
check "spectrum on stderr" grep -q 'fz: dominant frequency [0-9.]* Hz' "$ERR"
expect 0 "forces on the left wall about (0,0,0), --coef, --spectrum cl" \
    "$FORCES" --mk 1 --centre 0,0,0 --coef 2,0.5,1000 --spectrum cl --from 0.1 "$T/run" -o "$T/left.tsv"
expect 0 "forces on the right wall about (1,0,0), to stdout" "$FORCES" --mk 2 --centre 1,0,0 "$T/run"
cp "$OUT" "$T/right.tsv"

check "header names the columns and units" grep -q '^# time_s	fx_N	fy_N	fz_N	mx_Nm	my_Nm	mz_Nm$' "$T/bottom.tsv"
check "header says 2D forces are per unit width" grep -q '^# 2D case (x-z plane): forces per unit width in N/m' "$T/bottom.tsv"
check "header names the body" grep -q '^# vres-forces: .*mkbound 0 (fixed walls' "$T/bottom.tsv"
nsnap=$(ls "$T/run"/snap_*.h5 | wc -l)
check "one row per snapshot ($nsnap)" [ "$(grep -vc '^#' "$T/bottom.tsv")" -eq "$nsnap" ]
check "rows carry the snapshots' times, in order" \
    diff <(awk '!/^#/ {printf "%.6g\n", $1}' "$T/run/run.tsv") <(awk '!/^#/ {printf "%.6g\n", $1}' "$T/bottom.tsv")
check "2D: fy, mx and mz are zero" awk '!/^#/ && ($3 != 0 || $5 != 0 || $7 != 0) {exit 1}' "$T/bottom.tsv"

# means over (0.1, 0.3] s: column COL of FILE
mean() { awk -v c="$2" '!/^#/ && $1 > 0.1 {s += $c; n++} END {printf "%.6g", s / n}' "$1"; }
W=$(awk -v r=$RHO0 -v g=$G -v h=$H -v l=$L 'BEGIN {print r * g * h * l}')
S=$(awk -v r=$RHO0 -v g=$G -v h=$H 'BEGIN {print 0.5 * r * g * h * h}')
relerr() { awk -v a="$1" -v b="$2" 'BEGIN {e = (a - b) / b; printf "%.4f", e}'; }
within() { awk -v e="$1" -v t="$2" 'BEGIN {exit !(e < t && e > -t)}'; }

bz=$(mean "$T/bottom.tsv" 4) lz=$(mean "$T/left.tsv" 4) rz=$(mean "$T/right.tsv" 4)
lx=$(mean "$T/left.tsv" 2) rx=$(mean "$T/right.tsv" 2)
total=$(awk -v a="$bz" -v b="$lz" -v c="$rz" 'BEGIN {print -(a + b + c)}')
e=$(relerr "$total" "$W")
echo "# vertical force on all walls $total N/m against the weight $W N/m: relative error $e"
# Momentum: the mean force on all walls is the weight less the change of the water's momentum
# over the window, which the 1% time-mean tolerance above covers.
check "all walls carry the water's weight within 1% (error $e)" within "$e" 0.01
e=$(relerr "$(awk -v a="$bz" 'BEGIN {print -a}')" "$W")
echo "# bottom: $bz N/m (side walls: $lz, $rz N/m): relative error $e"
# The side walls are drawn down through the bottom's layers, so they own the corner blocks,
# which hold up the water next to the corners: measured 28.3 N/m each at this dp, 1.15% of W
# together, a share that scales with dp (0.23 dp rho0 g H per corner at dp 0.05, 0.025 and
# 0.02 m). Tolerance: 1% for the time mean + 1% for the corners (measured: -1.23%).
check "the bottom carries the weight within 2% (error $e)" within "$e" 0.02
check "the corners press down on the side walls, not up" awk -v a="$lz" -v b="$rz" 'BEGIN {exit !(a < 0 && b < 0)}'
el=$(relerr "$(awk -v a="$lx" 'BEGIN {print -a}')" "$S") er=$(relerr "$rx" "$S")
echo "# side walls: fx $lx and $rx N/m against -+$S N/m: relative errors $el, $er"
check "left wall pushed towards -x by rho0 g H^2/2 within 1% (error $el)" within "$el" 0.01
check "right wall pushed towards +x by rho0 g H^2/2 within 1% (error $er)" within "$er" 0.01
# Centre of pressure: for a linear pressure profile the resultant on a side wall acts H/3
# above the bottom, so my about the wall's foot is fx H/3 on both sides. The
# profile is linear in the particles' positions; the fluid's first row is dp/2 above the bottom
# face like its top row is dp/2 below the surface, so the lattice does not move the line of
# action. Tolerance 1% of H/3 (0.07 dp) for the time mean; measured +0.06%.
for side in left right; do
    arm=$(awk '!/^#/ && $1 > 0.1 {m += $6; f += $2} END {printf "%.6g", m / f}' "$T/$side.tsv")
    e=$(relerr "$arm" "$(awk -v h=$H 'BEGIN {print h / 3}')")
    check "$side wall: force acts H/3 above the bottom (arm $arm m, error $e)" within "$e" 0.01
done

# Coefficients: cd = fx / (0.5 rho U^2 L), cl = fz / (0.5 rho U^2 L); U = 2 m/s, L = 0.5 m,
# rho = 1000 kg/m^3 make the dynamic pressure times L 1000 N/m.
check "header adds cd and cl" grep -q '^# time_s	fx_N	fy_N	fz_N	mx_Nm	my_Nm	mz_Nm	cd	cl$' "$T/left.tsv"
check "header defines them" grep -q '^# cd = fx / (0.5 rho U^2 L), cl = fz / (0.5 rho U^2 L)' "$T/left.tsv"
check "cd = fx / 1000 N/m and cl = fz / 1000 N/m on every row" \
    awk '!/^#/ {if ($8 == 0 || (($8 * 1000 - $2) / $2) ^ 2 > 1e-12 || (($9 * 1000 - $4) / $4) ^ 2 > 1e-12) exit 1}' "$T/left.tsv"
check "strouhal = f L / U" awk '$2 == "frequency_Hz" {f = $3} $2 == "strouhal" {s = $3} END {exit !(f > 0 && (s - f * 0.5 / 2) ^ 2 < 1e-10)}' "$T/left.tsv"

# Spectrum: the column rings in its acoustic mode, a quarter wave over the depth: f = c0/(4 H')
# with H' between H (rigid bottom) and H + 3 dp (the DBC wall's three layers take part: their
# density follows the continuity equation like the water's).
f=$(awk '$1 == "#" && $2 == "frequency_Hz" {print $3}' "$T/bottom.tsv")
c0=$("$BIN/vres-info" "$T/tank.h5" | awk '$1 == "cs0" {print $2}')
echo "# acoustic mode: $f Hz; c0/(4H) = $(awk -v c="$c0" -v h=$H 'BEGIN {print c / (4 * h)}') Hz"
check "frequency $f Hz between c0/(4(H + 3 dp)) and c0/(4H)" \
    awk -v f="$f" -v c="$c0" -v h=$H -v dp=$DP 'BEGIN {exit !(f > c / (4 * (h + 3 * dp)) && f < c / (4 * h))}'
check "spectrum lines follow the rows" bash -c "tail -3 '$T/bottom.tsv' | grep -c '^#' | grep -qx 3"
check "the left wall's load rings at the bottom's frequency (within a bin)" \
    awk '$2 == "frequency_Hz" {f[n++] = $3} $0 ~ /bin width/ {match($0, /bin width [0-9.e+-]+/); b = substr($0, RSTART + 10, RLENGTH - 10)}
         END {d = f[0] - f[1]; exit !(n == 2 && d * d < b * b)}' "$T/bottom.tsv" "$T/left.tsv"

# a single store works too: the generated one, at t = 0
expect 0 "one store: one row" "$FORCES" --mk 0 "$T/tank.h5"
check "one row at t = 0" [ "$(grep -v '^#' "$OUT" | awk '{print $1}')" = 0 ]
expect 0 "a store on stdin" "$FORCES" --mk 0 - <"$T/tank.h5"
check "same row from stdin" [ "$(grep -v '^#' "$OUT" | awk '{print $1}')" = 0 ]
