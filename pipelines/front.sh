#!/usr/bin/env bash
# pipelines/front.sh - extent of the fluid in each snapshot of a vres-run directory.
#
#   pipelines/front.sh [--dimensionless] RUNDIR
#
# Prints a TSV table, one row per snapshot snap_NNNNN.h5 in time order (the fluid of every
# domain of a variable-resolution run, each particle with its own domain's dp):
#   time_s      simulation time (s), the snapshot's root attribute time
#   x_left_m    smallest fluid particle x minus its dp/2 (m)
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
    t=$(attr /time "$f") && nd=$(domains "$f") || die "$f: unreadable"
    # every domain's fluid (a variable-resolution run's front lies in whichever domain holds
    # it), each particle with its own domain's dp as the fifth column
    for ((k = 0; k < nd; k++)); do
        dp=$(attr "/Domains/D$k/dp" "$f") || die "$f: no dp in D$k"
        paste <(values "/Domains/D$k/Type" "$f") <(values "/Domains/D$k/Position" "$f" | paste - - -) |
            awk -v dp="$dp" '{print $0 "\t" dp}'
    done |
        awk -v t="$t" -v f="$f" '
            $1 == 0 { n++; h = $5 / 2
                      if (n == 1 || $2 - h < x0) x0 = $2 - h; if (n == 1 || $2 + h > x1) x1 = $2 + h
                      if (n == 1 || $4 - h < z0) z0 = $4 - h; if (n == 1 || $4 + h > z1) z1 = $4 + h }
            END { if (!n) { print "front.sh: " f ": no fluid particles" > "/dev/stderr"; exit 1 }
                  printf "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n", t, x0, x1, z0, z1 }' ||
        exit 1
done
