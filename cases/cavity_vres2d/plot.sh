#!/usr/bin/env bash
# cases/cavity_vres2d/plot.sh - two figures of the three runs of pipelines/vres_compare.sh
# cavity_vres2d (RUNS=DIR as vres_compare.sh), into OUTDIR (default
# pipelines/reports/cavity_vres2d):
#   centrelines.png  u on the vertical centreline (left) and w on the horizontal one (right)
#                    against Ghia et al. (1982), Re = 100: each run probed by vres-probe at 79
#                    points a line (s = 0.0125 to 0.9875 of L), averaged over the snapshots of its
#                    last 3 s as ./check does (each run's RUNDIR/centrelines.tsv: line, s, v/U),
#                    the stretches of each line in the vres run's boxes shaded
#   flow.png         the owned fluid's velocity (pipelines/vreslib.sh owned_fluid: each piece
#                    once, from the domain whose region holds it) of snapshots 2, 8 and 20 (t = 1,
#                    4 and 10 s), vectors coloured by domain: the vres run above, the fine single
#                    one below
set -eu
VRES_ME=cavity_vres2d/plot.sh
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../../pipelines/vreslib.sh"
RUNS=${RUNS:-$VRES_ROOT/build/runs/vres_compare/cavity_vres2d}
OUTDIR=${OUTDIR:-$VRES_ROOT/pipelines/reports/cavity_vres2d}
mkdir -p "$OUTDIR"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- centrelines.png ---
REF=$HERE/../cavity_re100
for v in single_coarse single_fine vres; do
    d=$RUNS/$v
    run_complete "$d" || die "$d: no complete run"
    first=$(snapshots "$d" | head -1)
    dp=$(attr /Domains/D0/dp "$first") || die "$first: no dp"
    read -r x0 z0 L < <(particles "$first" | awk -v dp="$dp" '$1 == 0 || $1 == 1 {
            if (!n++ || $2 < a) a = $2; if ($2 > b) b = $2; if (n == 1 || $4 < c) c = $4 }
        END {printf "%.15g %.15g %.15g\n", a - dp / 2, c - dp / 2, b - a + dp}')
    tend=$(tsv_last "$d" time_s)
    pts=$(mktemp) probe=$(mktemp)
    awk -v x0="$x0" -v z0="$z0" -v L="$L" 'BEGIN { for (i = 1; i < 80; i++) print x0 + L / 2, 0, z0 + i * L / 80
                                                  for (i = 1; i < 80; i++) print x0 + i * L / 80, 0, z0 + L / 2 }' >"$pts"
    "$VRES_BIN/vres-probe" -q --points "$pts" --vars vx,vz "$d" -o "$probe" || die "vres-probe failed on $d"
    awk -F'\t' -v te="$tend" '!/^#/ && $1 >= te - 3 - 1e-9 { k = $2 + 0; v = k < 79 ? $6 : $7
                                                          if (v == v + 0) { s[k] += v; n[k]++ } }
        END { print "# line\ts (z/L for u, x/L for w)\tv/U (mean of the last 3 s)"
              for (k = 0; k < 158; k++) { if (k == 79) printf "\n\n"; if (n[k]) printf "%s\t%.4f\t%.6f\n", k < 79 ? "u" : "w", (k % 79 + 1) / 80, s[k] / n[k] } }' \
        "$probe" >"$d/centrelines.tsv"
    rm -f "$pts" "$probe"
done
dpc=$(attr /Domains/D0/dp "$(snapshots "$RUNS/single_coarse" | head -1)")
dpf=$(attr /Domains/D0/dp "$(snapshots "$RUNS/single_fine" | head -1)")
# the refined stretches of each centreline, from the vres run's boxes (in units of L, clipped to
# the cavity: x0, z0, L are the vres run's, the loop's last): grey rectangles behind the u panel
# (z ranges on x = L/2) and the w panel (x ranges on z = L/2)
boxes=$(domain_boxes "$(snapshots "$RUNS/vres" | head -1)" | awk '$1 > 0 {print $4, $6, $7, $9}')
objs() { # AXIS (u or w): gnuplot "set object" commands for that panel
    awk -v a="$1" -v x0="$x0" -v z0="$z0" -v L="$L" 'function c(v) { return v < 0 ? 0 : v > 1 ? 1 : v }
        { xl = c(($1 - x0) / L); zl = c(($2 - z0) / L); xh = c(($3 - x0) / L); zh = c(($4 - z0) / L)
          if (a == "u" && xl <= 0.5 && xh >= 0.5) r = sprintf("graph 0, first %g to graph 1, first %g", zl, zh)
          else if (a == "w" && zl <= 0.5 && zh >= 0.5) r = sprintf("first %g, graph 0 to first %g, graph 1", xl, xh)
          else next
          printf "set object %d rect from %s fc rgb \"#e8e8e8\" fs solid noborder behind; ", ++n, r }' <<<"$boxes"
}
uobj=$(objs u) wobj=$(objs w)
ghia=$tmp
for t in u_vertical w_horizontal; do awk -F, '!/^#/ && $1 == $1 + 0 {print $1, $2}' "$REF/ghia_$t.csv" >"$ghia/$t"; done
gnuplot -e "set terminal pngcairo size 1100,560 noenhanced font ',11'; set output '$OUTDIR/centrelines.png';
    set multiplot layout 1,2 title 'cavity_vres2d, Re = 100: centreline velocities (mean of the last 3 s) against Ghia et al. 1982; shaded: refined boxes (dp $dpf)';
    set grid; set key bottom right;
    $uobj
    set xlabel 'u / U on x = L/2'; set ylabel 'z / L'; set yrange [0:1];
    plot '$ghia/u_vertical' using 2:1 with points pt 7 ps 1.2 lc rgb 'black' title 'Ghia et al. 1982',
         '$RUNS/single_coarse/centrelines.tsv' index 0 using 3:2 with lines lw 2 dt 2 title 'single, dp $dpc',
         '$RUNS/single_fine/centrelines.tsv' index 0 using 3:2 with lines lw 2 title 'single, dp $dpf',
         '$RUNS/vres/centrelines.tsv' index 0 using 3:2 with lines lw 2 title 'variable, dp $dpc / $dpf';
    unset object; set yrange [*:*];
    $wobj
    set xlabel 'x / L'; set ylabel 'w / U on z = L/2'; set xrange [0:1]; set yrange [-0.3:0.25]; set key top right;
    plot '$ghia/w_horizontal' using 1:2 with points pt 7 ps 1.2 lc rgb 'black' title 'Ghia et al. 1982',
         '$RUNS/single_coarse/centrelines.tsv' index 1 using 2:3 with lines lw 2 dt 2 title 'single, dp $dpc',
         '$RUNS/single_fine/centrelines.tsv' index 1 using 2:3 with lines lw 2 title 'single, dp $dpf',
         '$RUNS/vres/centrelines.tsv' index 1 using 2:3 with lines lw 2 title 'variable, dp $dpc / $dpf';
    unset multiplot"
echo "plot.sh: $OUTDIR/centrelines.png"

# --- flow.png ---
SNAPS="00002 00008 00020"
for v in vres single_fine; do
    for s in $SNAPS; do
        f=$RUNS/$v/snap_$s.h5
        [ -f "$f" ] || die "$f: no such snapshot"
        owned_fluid "$f" >"$tmp/${v}_$s"
        printf '%s' "$(attr /time "$f")" >"$tmp/${v}_$s.t"
    done
done
cmd="set terminal pngcairo size 1500,1000 noenhanced font ',10'; set output '$OUTDIR/flow.png';
    set multiplot layout 2,3 title 'owned fluid velocity (vectors: 0.1 s of travel; colour: domain), variable resolution (top) and single dp fine (bottom)';
    set size ratio -1; set xrange [-0.02:1.02]; set yrange [-0.02:1.02]; set xlabel 'x (m)'; set ylabel 'z (m)';"
for v in vres single_fine; do
    for s in $SNAPS; do
        cmd="$cmd set title '$v, t = $(cat "$tmp/${v}_$s.t") s'; plot '$tmp/${v}_$s' using 2:4:(\$5*0.1):(\$7*0.1):(\$10+1) with vectors lc variable notitle;"
    done
done
gnuplot -e "$cmd unset multiplot"
echo "plot.sh: $OUTDIR/flow.png"
