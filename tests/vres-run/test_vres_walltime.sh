#!/usr/bin/env bash
# vres-run's last stderr line with several domains (vres-run(1), the end of a run): "coupling of
# the N domains: X s, Y% of the time loop (interpolation a%, flux b%, classification and
# creation c%, sorts and compaction d%)". Each part is timed inside the total, so the parts are
# present, not negative, and add up to at most the total (to the 0.1% of the printing); they
# also cover most of it, so that no part of the coupling goes untimed. A single-domain run has
# no such line. The case is cases/hydrostatic_vres2d under a sideways gravity of 3 m/s^2, as in
# test_vres_restart.sh, so that water crosses the interface (a few hundred steps, seconds).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
tilted_tank
"$BIN/vres-partition" -q --single "$T/tilt.h5" -o "$T/single.h5" || notok "partition --single the tilted tank"

expect 0 "coupled run to 0.03 s" "$RUN" --device cpu --tmax 0.03 --tout 0.03 "$T/parts.h5" -o "$T/run"
line=$(grep 'coupling of the 2 domains: ' "$ERR")
check "one coupling line ($line)" [ "$(grep -c 'coupling of the ' "$ERR")" -eq 1 ]
# parts LINE: "total interpolation flux creation compaction" (percent), or nothing when a name
# or a number is missing
parts() {
    sed -n -E 's/.*coupling of the [0-9]+ domains: [0-9.e+-]+ s, ([0-9.]+)% of the time loop \(interpolation ([0-9.]+)%, flux ([0-9.]+)%, classification and creation ([0-9.]+)%, sorts and compaction ([0-9.]+)%\)$/\1 \2 \3 \4 \5/p' <<<"$1"
}
p=$(parts "$line")
check "the line names the four parts, each with a percentage ($p)" [ "$(wc -w <<<"$p")" -eq 5 ]
check "total ($(cut -d' ' -f1 <<<"$p")%) above 0 and at most 100%" \
    awk -v p="$p" 'BEGIN {split(p, v, " "); exit !(v[1] > 0 && v[1] <= 100)}'
check "the parts add up to at most the total (0.2% for the printing's rounding)" \
    awk -v p="$p" 'BEGIN {split(p, v, " "); s = v[2] + v[3] + v[4] + v[5]; exit !(s <= v[1] + 0.2)}'
check "the parts cover at least half the total" \
    awk -v p="$p" 'BEGIN {split(p, v, " "); s = v[2] + v[3] + v[4] + v[5]; exit !(s >= 0.5 * v[1])}'

expect 0 "single-domain run to 0.01 s" "$RUN" --device cpu --tmax 0.01 --tout 0.01 "$T/single.h5" -o "$T/one"
check "no coupling line with one domain" sh -c "! grep -q 'coupling of the ' '$ERR'"
