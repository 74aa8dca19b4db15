#!/usr/bin/env bash
# cases/cavity_vres2d/field_diff.sh RUNDIR REFRUN [SNAP...] - how far a run's velocity field is
# from a reference run's (the fine single-resolution one), snapshot by snapshot: the owned fluid
# of each (pipelines/vreslib.sh owned_fluid) averaged in 0.1 m x 0.1 m cells of the cavity
# [0, 1]^2 m, and per snapshot (default snap_00001, 00002 and 00004: t = 0.5, 1, 2 s) one line:
#   time_s  rms_U (RMS over the cells of |mean v - mean v_ref|, m/s over U = 1 m/s)
#   max_U x_cell z_cell du dw (the cell with the largest difference, its lower-left corner, m)
set -eu
VRES_ME=cavity_vres2d/field_diff.sh
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../../pipelines/vreslib.sh"
[ $# -ge 2 ] || { echo "usage: field_diff.sh RUNDIR REFRUN [SNAP...]" >&2; exit 2; }
run=$1 ref=$2; shift 2
[ $# -gt 0 ] || set -- 00001 00002 00004
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '# time_s\trms_U\tmax_U\tx_cell_m\tz_cell_m\tdu_U\tdw_U\n'
for s in "$@"; do
    for d in "$run" "$ref"; do [ -f "$d/snap_$s.h5" ] || die "$d/snap_$s.h5: no such snapshot"; done
    owned_fluid "$run/snap_$s.h5" >"$tmp/a"
    owned_fluid "$ref/snap_$s.h5" >"$tmp/b"
    awk -v t="$(attr /time "$run/snap_$s.h5")" 'FNR == 1 { f++ }
        { i = int($2 * 10); j = int($4 * 10); i = i > 9 ? 9 : i < 0 ? 0 : i; j = j > 9 ? 9 : j < 0 ? 0 : j; k = i " " j
          n[f, k]++; u[f, k] += $5; w[f, k] += $7; cell[k] = 1 }
        END { for (k in cell) { if (!n[1, k] || !n[2, k]) continue
                  du = u[1, k] / n[1, k] - u[2, k] / n[2, k]; dw = w[1, k] / n[1, k] - w[2, k] / n[2, k]
                  d = sqrt(du * du + dw * dw); s += d * d; c++; if (d > m) { m = d; mk = k; mu = du; mw = dw } }
              if (!c) exit 1
              split(mk, q, " "); printf "%.4f\t%.4f\t%.4f\t%.1f\t%.1f\t%+.4f\t%+.4f\n", t, sqrt(s / c), m, q[1] / 10, q[2] / 10, mu, mw }' \
        "$tmp/a" "$tmp/b" || die "snap_$s: no cell holds fluid of both runs"
done
