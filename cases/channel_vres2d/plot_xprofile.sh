#!/usr/bin/env bash
# cases/channel_vres2d/plot_xprofile.sh CASE - the x profiles across the box's faces of the
# three runs of pipelines/vres_compare.sh CASE (their RUNDIR/xprofile.tsv, channel_analyse.py:
# (u - u_ex)/U and (rho - rho0)/rho0 of the owned fluid in bins dp_root wide, time-averaged
# over t > t_end/2) into pipelines/reports/CASE/vres_xprofile.png, the box's faces x = 1 and
# 2 m marked. RUNS=DIR as vres_compare.sh.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CASE=${1:?usage: plot_xprofile.sh CASE}
RUNS=${RUNS:-$ROOT/build/runs/vres_compare/$CASE}
REP=$ROOT/pipelines/reports/$CASE
for v in single_coarse single_fine vres; do [ -f "$RUNS/$v/xprofile.tsv" ] || { echo "plot_xprofile.sh: no $RUNS/$v/xprofile.tsv" >&2; exit 1; }; done
gnuplot -e "set terminal pngcairo size 900,800 noenhanced font ',11'; set output '$REP/vres_xprofile.png';
    set multiplot layout 2,1 title '$CASE: profiles along the channel (owned fluid, time average over t > t_end/2)';
    set grid; set arrow 1 from 1, graph 0 to 1, graph 1 nohead dt 2; set arrow 2 from 2, graph 0 to 2, graph 1 nohead dt 2;
    set ylabel '(u - u_ex) / U'; set key outside right;
    plot '$RUNS/single_coarse/xprofile.tsv' using 1:2 with linespoints pt 6 title 'single coarse',
         '$RUNS/single_fine/xprofile.tsv' using 1:2 with linespoints pt 4 title 'single fine',
         '$RUNS/vres/xprofile.tsv' using 1:2 with linespoints pt 7 title 'variable';
    set xlabel 'x (m)'; set ylabel '(rho - rho0) / rho0';
    plot '$RUNS/single_coarse/xprofile.tsv' using 1:3 with linespoints pt 6 title 'single coarse',
         '$RUNS/single_fine/xprofile.tsv' using 1:3 with linespoints pt 4 title 'single fine',
         '$RUNS/vres/xprofile.tsv' using 1:3 with linespoints pt 7 title 'variable';
    unset multiplot"
echo "plot_xprofile.sh: $REP/vres_xprofile.png"
