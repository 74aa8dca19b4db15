#!/usr/bin/env bash
# pipelines/front.sh - extent of the fluid in each snapshot of a vres-run directory.
#
#   pipelines/front.sh [--dimensionless] RUNDIR
#
# Prints a TSV table, one row per snapshot snap_NNNNN.h5 in time order:
#   time_s      simulation time (s), the snapshot's root attribute time
#   x_left_m    smallest fluid particle x minus dp/2 (m)
#   x_front_m   largest fluid particle x plus dp/2 (m): the surge front of a dam break
#   z_bottom_m  smallest fluid particle z minus dp/2 (m)
#   z_top_m     largest fluid particle z plus dp/2 (m)
# Half a spacing is added on each side because a particle stands for the dp-wide cell around
# it: a column of n particles spans n dp, so the first row reproduces the drawn column. The
# stores are read with h5dump (vres-store(5)); nothing of vres runs here.
#
# --dimensionless: print instead the Martin & Moyce variables of a dam break, two columns
#   T   n t sqrt(g/a) = t sqrt(g H) / a
#   Z   (x_front - x_left(0)) / a
# with the column (width a, height H = n^2 a, left face x_left(0)) taken from the first
# snapshot and g = |gravity| of the store.
set -u
VRES_ME=front.sh
source "$(dirname "$0")/vreslib.sh"
dimless=0
[ "${1-}" = --dimensionless ] && { dimless=1; shift; }
[ $# -eq 1 ] || { echo "usage: pipelines/front.sh [--dimensionless] RUNDIR" >&2; exit 2; }
d=$1
if [ "$dimless" = 1 ]; then
    g=$(gravity_norm "$(snapshots "$d" | head -1)") || die "$d: no gravity"
    "$0" "$d" | awk -F'\t' -v g="$g" '!/^#/ { if (!n++) { x0 = $2; a = $3 - $2; H = $5 - $4; s = sqrt(g * H) / a; print "# T\tZ" }
                                              printf "%.6f\t%.6f\n", $1 * s, ($3 - x0) / a }'
    exit "${PIPESTATUS[0]}"
fi
[ -n "$(snapshots "$d")" ] || die "$d: no snapshots snap_NNNNN.h5"

printf '# time_s\tx_left_m\tx_front_m\tz_bottom_m\tz_top_m\n'
for f in $(snapshots "$d"); do
    t=$(attr /time "$f") && dp=$(attr /Domains/D0/dp "$f") || die "$f: unreadable"
    paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | paste - - -) |
        awk -v t="$t" -v dp="$dp" -v f="$f" '
            $1 == 0 { n++; if (n == 1 || $2 < x0) x0 = $2; if (n == 1 || $2 > x1) x1 = $2
                           if (n == 1 || $4 < z0) z0 = $4; if (n == 1 || $4 > z1) z1 = $4 }
            END { if (!n) { print "front.sh: " f ": no fluid particles" > "/dev/stderr"; exit 1 }
                  printf "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n", t, x0 - dp/2, x1 + dp/2, z0 - dp/2, z1 + dp/2 }' ||
        exit 1
done
