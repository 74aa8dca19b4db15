#!/usr/bin/env bash
# pipelines/slamming.awk and slamming.sh's penetration_history (the references of
# cases/wedge and cases/wedge_entry2d's checks) against closed forms:
#   - a 30-degree wedge at constant speed V: von Karman's force pi cot^2(beta) rho V^3 t and
#     Wagner's (pi^3/4) cot^2(beta) rho V^3 t exactly (1e-8 relative: printed to 9 digits);
#   - the modified Logvinovich model's F / (rho V^3 t) against its integral in closed form at
#     constant speed: with a = (pi/2) cot(beta), k = cos^2(beta), the pressure's zero at
#     x* = c sqrt(1 - w^2), w the smaller root of (1 - k) w^2 - 2 a w + k = 0, and
#     F / (rho V^2 c) = 2 [a asin(x*/c) - x*/(2c) - k (atanh(x*/c) - x*/c) / 2] (the script
#     integrates numerically: Simpson on 2000 intervals, bisection; 1e-6 relative);
#   - the deceleration term: rho hdd times the integral of sqrt(c^2 - x^2) + f - h lowers F;
#   - after the chines (c > B/2) no force is given ("-");
#   - penetration_history on z(t) = 1 - 6 t + 40 t^2 at uneven times: h, dh/dt and d2h/dt2 of
#     the parabola exactly (a three-point stencil is exact for it).
source "$(dirname "$0")/../harness.sh"
source "$ROOT/pipelines/vreslib.sh"
source "$ROOT/pipelines/slamming.sh"
TANB=0.577350269189626
rel() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN {d = (a - b) / b; if (d < 0) d = -d; exit !(d <= t)}'; }
out=$(printf '0.01\t0.0615\t6.15\t0\n0.01\t0.0615\t6.15\t-200\n0.03\t0.1845\t6.15\t0\n' |
      awk -v tanb=$TANB -v rho=1000 -v halfb=0.25 -f "$ROOT/pipelines/slamming.awk")
check "slamming.awk: one row out per row in" [ "$(wc -l <<<"$out")" -eq 3 ]
read -r _ _ c f_mlm f_wag f_kar <<<"$(sed -n 1p <<<"$out")"
q=$(awk 'BEGIN {printf "%.17g", 1000 * 6.15 ^ 3 * 0.01}')
pi=$(awk 'BEGIN {printf "%.17g", atan2(0, -1)}')
check "Wagner's c = (pi/2) V t cot(beta) ($c m)" rel "$c" "$(awk -v p="$pi" -v t=$TANB 'BEGIN {printf "%.17g", p / 2 * 0.0615 / t}')" 1e-8
check "von Karman: F = pi cot^2 rho V^3 t ($f_kar N/m)" rel "$f_kar" "$(awk -v p="$pi" -v q="$q" 'BEGIN {printf "%.17g", p * 3 * q / 0.577350269189626 ^ 2 / 3}')" 1e-8
check "Wagner: F = (pi^3/4) cot^2 rho V^3 t ($f_wag N/m)" rel "$f_wag" "$(awk -v p="$pi" -v q="$q" 'BEGIN {printf "%.17g", p ^ 3 / 4 * q / 0.577350269189626 ^ 2}')" 1e-8
closed=$(awk -v p="$pi" -v t=$TANB 'BEGIN {
    a = p / 2 / t; k = 1 / (1 + t * t)
    w = (2 * a - sqrt(4 * a * a - 4 * (1 - k) * k)) / (2 * (1 - k)); x = sqrt(1 - w * w)
    atanh = 0.5 * log((1 + x) / (1 - x)); asin = atan2(x, w)
    print 2 * (a * asin - x / 2 - k * (atanh - x) / 2) * a }')
echo "# modified Logvinovich at 30 degrees: closed form $closed rho V^3 t, slamming.awk $(awk -v f="$f_mlm" -v q="$q" 'BEGIN {print f / q}')"
check "modified Logvinovich: F / (rho V^3 t) = the closed form $closed (1e-6)" \
    rel "$(awk -v f="$f_mlm" -v q="$q" 'BEGIN {print f / q}')" "$closed" 1e-6
check "between von Karman's and Wagner's" awk -v m="$f_mlm" -v k="$f_kar" -v w="$f_wag" 'BEGIN {exit !(m > k && m < w)}'
read -r _ _ _ f_dec _ _ <<<"$(sed -n 2p <<<"$out")"
check "a deceleration lowers it ($f_dec < $f_mlm)" awk -v a="$f_dec" -v b="$f_mlm" 'BEGIN {exit !(a < b)}'
check "no force after the chines are wetted" [ "$(sed -n 3p <<<"$out" | cut -f4-6)" = "-	-	-" ]
ph=$(printf '0\t1\n0.001\t0.99404\n0.0025\t0.98525\n0.004\t0.97664\n' | penetration_history)
bad=$(awk -F'\t' '{t = $1; h = 6 * t - 40 * t * t; v = 6 - 80 * t
    if (($2 - h) ^ 2 > 1e-20 || ($3 - v) ^ 2 > 1e-16 || ($4 + 80) ^ 2 > 1e-10) n++} END {print n + 0 "/" NR}' <<<"$ph")
check "penetration_history: h, dh/dt, d2h/dt2 of a parabola at uneven times ($bad rows off)" [ "$bad" = "0/4" ]

# cases/wedge_entry2d/check end to end at a coarse single resolution (dp 0.02, B/dp = 25, about
# 400 steps): the check reads the prescribed motion back through vres-forces' moving-body
# columns (entry speed 6.15 m/s to 1e-4: centres printed to 8 digits, differenced over 0.25 ms), ends the window when Wagner's c reaches B/2, at
# t = (B/2) tan(beta) (2/pi) / V = 14.94 ms, the last snapshot before it (0.25 ms apart), and
# the computed impulse lies between von Karman's and Wagner's; its tables are written.
if ! "$ROOT/cases/wedge_entry2d/check" --single --dp 0.02 --threads 2 -o "$T/we" >"$T/we.out" 2>"$T/we.err"; then
    check "the coarse wedge entry ran (its check may fail on the error only)" grep -q '^verdict	FAIL' "$T/we.out"
fi
get() { awk -F'\t' -v k="$1" '$1 == k {print $2}' "$T/we.out"; }
check "entry speed read back: $(get entry_speed_m_s) m/s" rel "$(get entry_speed_m_s)" 6.15 1e-4
check "window ends within a snapshot of 14.94 ms ($(get window_s) s)" \
    awk -v w="$(get window_s)" 'BEGIN {t = 0.25 * 0.577350269189626 * 2 / atan2(0, -1) / 6.15; exit !(w <= t && w > t - 0.0003)}'
check "impulse between von Karman's and Wagner's (ratio to the model $(get impulse_Ns_m) / $(get impulse_mlm_Ns_m))" \
    awk -v i="$(get impulse_Ns_m)" -v m="$(get impulse_mlm_Ns_m)" -v k="$(get karman_over_mlm)" -v w="$(get wagner_over_mlm)" \
    'BEGIN {r = i / m; exit !(m > 0 && r >= k && r <= w)}'
check "the error is |impulse / model - 1| ($(get error))" \
    awk -v i="$(get impulse_Ns_m)" -v m="$(get impulse_mlm_Ns_m)" -v e="$(get error)" 'BEGIN {d = i / m - 1; if (d < 0) d = -d; d -= e; exit !(d < 1e-5 && d > -1e-5)}'
check "slamming.tsv and profile.tsv written" [ -s "$T/we/slamming.tsv" -a -s "$T/we/profile.tsv" ]
