# pipelines/slamming.sh - the slamming force of a 2-D wedge's water entry against Wagner-type
# theory, shared by cases/wedge/check (free fall) and cases/wedge_entry2d/check (constant
# speed). Sourced after pipelines/vreslib.sh, never run.

# slamming_compare FORCES MOTION TANB HALFB RHO OUT: compare the fluid's vertical force on the
# wedge (FORCES: vres-forces output, time in column 1, fz in column 4) with the modified
# Logvinovich model at the wedge's own penetration history (MOTION: one row per force row,
# "t h hd hdd": penetration of the apex below the still-water level (m), its rate (m/s,
# positive down) and its second derivative (m/s^2)), by pipelines/slamming.awk, from the first
# contact until Wagner's wetted half-width reaches the chines (HALFB, m). Writes OUT (t, F,
# c, F_mlm, F_wagner, F_karman) and reports
#   impulse_Ns_m          the time integral of the computed force over that window (trapezoids)
#   impulse_mlm_Ns_m      the same of the modified Logvinovich model's force
#   karman_over_mlm, wagner_over_mlm   the bounds' impulses over the model's (von Karman's
#                         under-estimate, Wagner's over-estimate)
#   window_s              the window's end (the chines wetted, by Wagner's condition)
# and sets SLAM_RATIO (impulse over the model's) and SLAM_INSIDE (1 when the computed impulse
# lies between von Karman's and Wagner's). The impulse, the momentum the fluid took, averages
# out the acoustic ringing of the individual force samples (a sample at 0.25 ms can be 50%
# off; README of the cases).
slamming_compare() {
    local forces=$1 motion=$2 tanb=$3 halfb=$4 rho=$5 out=$6 line
    awk -v tanb="$tanb" -v rho="$rho" -v halfb="$halfb" -f "$VRES_ROOT/pipelines/slamming.awk" "$motion" >"$WORK/mlm.tsv" ||
        die "pipelines/slamming.awk failed"
    paste <(grep -v '^#' "$forces" | cut -f4) "$WORK/mlm.tsv" |
        awk -F'\t' -v OFS='\t' '{print $2, $1, $4, $5, $6, $7}' >"$out"
    line=$(awk -F'\t' '$4 == "-" {exit}
        NR > 1 {i += ($2 + f) / 2 * ($1 - t); m += ($4 + fm) / 2 * ($1 - t)
                w += ($5 + fw) / 2 * ($1 - t); k += ($6 + fk) / 2 * ($1 - t); n++}
        {t = $1; f = $2; fm = $4; fw = $5; fk = $6}
        END {if (n < 4 || m <= 0) exit 1; printf "%.6g %.6g %.6g %.6g %.6g %.6g\n", i, m, k / m, w / m, i / m, t}' "$out") ||
        die "$forces: fewer than four force samples before the chines are wetted"
    read -r SLAM_I SLAM_M SLAM_K SLAM_W SLAM_RATIO SLAM_END <<<"$line"
    report impulse_Ns_m "$SLAM_I"
    report impulse_mlm_Ns_m "$SLAM_M"
    report karman_over_mlm "$SLAM_K"
    report wagner_over_mlm "$SLAM_W"
    report window_s "$SLAM_END"
    SLAM_INSIDE=$(awk -v r="$SLAM_RATIO" -v k="$SLAM_K" -v w="$SLAM_W" 'BEGIN {print (r >= k && r <= w) ? 1 : 0}')
    [ "$SLAM_INSIDE" = 1 ] || note "the computed impulse lies outside von Karman's and Wagner's"
}

# slamming_plot OUT PNG TITLE: the computed force and the three models' against time (gnuplot,
# when installed).
slamming_plot() {
    command -v gnuplot >/dev/null || { note "no gnuplot: no plot"; return 0; }
    gnuplot -e "set terminal pngcairo size 800,500; set output '$2'; set title '$3';
        set datafile missing '-'; set xlabel 't (s)'; set ylabel 'vertical force (N/m)'; set key top left;
        plot '$1' u 1:2 w lp pt 7 ps 0.5 t 'vres-run (vres-forces)', '' u 1:4 w l lw 2 t 'modified Logvinovich (Korobkin 2004)',
             '' u 1:5 w l dt 2 t 'Wagner (1932)', '' u 1:6 w l dt 3 t 'von Karman (1929)'" ||
        note "gnuplot failed: no plot"
}

# penetration_history: read "t z" rows (a snapshot's time and its body's centre height, in
# time order) on stdin; print "t h hd hdd": the penetration h = z(0) - z(t) (the apex starts on
# the still-water level), its rate and its second derivative by central differences on the
# uneven times (one-sided at the ends). Fails on fewer than three rows.
penetration_history() {
    awk -F'\t' -v OFS='\t' '{t[n] = $1; h[n] = (n ? z0 - $2 : 0); if (!n) z0 = $2; n++}
        END { if (n < 3) exit 1
              for (i = 0; i < n; i++) {
                  a = (i == 0 ? 1 : (i == n - 1 ? n - 2 : i))       # centre of the 3-point stencil
                  d1 = (h[a] - h[a - 1]) / (t[a] - t[a - 1]); d2 = (h[a + 1] - h[a]) / (t[a + 1] - t[a])
                  acc = 2 * (d2 - d1) / (t[a + 1] - t[a - 1])
                  # the derivative of the parabola through the stencil, at t[i]
                  v = d1 + acc * (t[i] - (t[a - 1] + t[a]) / 2)
                  printf "%.9g\t%.9g\t%.9g\t%.9g\n", t[i], h[i], v, acc } }'
}
