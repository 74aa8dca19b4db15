#!/usr/bin/env bash
# vres-run with the cubic spline kernel (Kernel=1, with DualSPHysics' tensile correction) on
# two single-resolution cases, each run with the Wendland kernel too (Kernel=2, the same store
# otherwise):
#   * still water (cases/hydrostatic2d, dp 0.02 m, 0.6 s): the run stays stable and at rest,
#     keeps its mass, and its bottom pressure is hydrostatic within 3% and within 2% of the
#     Wendland run's;
#   * the dam break (cases/dsph_dambreak2d at dp 0.025 m, 0.3 s): no particle lost, the surge
#     front has left the column and lies within 5% of the Wendland run's (both kernels resolve
#     the same flow at this dp; the front moves about 1.5 m by then, so 5% is about 3 dp).
# The two kernels must also give different states (the run used the kernel it was given).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
H=0.5 G=9.81 RHO0=1000 DP=0.02

# bottom_pressure RUNDIR: the mean pressure of the bottom fluid row (z < dp) over the snapshots
# after 0.2 s (as test_hydrostatic.sh: the DBC start rings, the time mean leaves ~1% of it)
bottom_pressure() {
    local psum=0 nsnap=0 k f p
    for k in $(awk -F'\t' '!/^#/ {if ($1 > 0.2) print NR - 2}' "$1/run.tsv"); do
        f=$(printf '%s/snap_%05d.h5' "$1" "$k")
        p=$(paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | awk 'NR % 3 == 0') \
                  <(values /Domains/D0/Pressure "$f") | awk -v dp=$DP '$1 == 0 && $2 < dp {s += $3; n++} END {if (n) print s / n}')
        [ -n "$p" ] || continue
        psum=$(awk -v a="$psum" -v b="$p" 'BEGIN {print a + b}'); nsnap=$((nsnap + 1))
    done
    awk -v s="$psum" -v n=$nsnap 'BEGIN {if (n >= 10) print s / n; else print "none"}'
}

# front SNAP: the largest x of the fluid particles (m)
front() {
    paste <(values /Domains/D0/Type "$1") <(values /Domains/D0/Position "$1" | awk 'NR % 3 == 1') |
        awk '$1 == 0 {n++; if ($2 > x) x = $2} END {if (n) print x; else print "none"}'
}

# ---- still water
for k in 1 2; do
    expect 0 "gencase the still-water tank, Kernel=$k" "$BIN/vres-gencase" -q --set Kernel=$k \
        "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank$k.h5"
    expect 0 "run 0.6 s of still water, Kernel=$k" "$RUN" --threads 1 --tmax 0.6 --tout 0.008 "$T/tank$k.h5" -o "$T/run$k"
    cp "$ERR" "$T/err$k"
done
check "the cubic run names its kernel" grep -q -E 'modules: wcsph-2d cubic-spline\(tensile\) ' "$T/err1"
check "the Wendland run names its kernel" grep -q -E 'modules: wcsph-2d wendland-c2 ' "$T/err2"
TSV=$T/run1/run.tsv
mass0=$(paste <(values /Domains/D0/Type "$T/tank1.h5") <(values /Domains/D0/Mass "$T/tank1.h5") |
        awk '$1 == 0 {m += $2} END {printf "%.9g", m}')
last=$(awk 'END {print $1}' "$TSV")
check "cubic: the run reaches 0.6 s (last line $last)" awk -v t="$last" 'BEGIN {exit !(t >= 0.6)}'
check "cubic: fluid mass conserved exactly ($mass0 kg)" awk -F'\t' -v m="$mass0" '!/^#/ {n++; if ($6 != m) bad = 1} END {exit bad || !n}' "$TSV"
check "cubic: no NaN or Inf in run.tsv" bash -c "! grep -qiE 'nan|inf' '$TSV'"
# At rest the reference speed is 0; an unstable or leaking tank moves at sqrt(g dp) = 0.44 m/s or
# more (test_hydrostatic.sh). The cubic spline rearranges the initial square lattice at this
# h/dp = 1.41 (nearest neighbours at q = 0.71, next to the largest |dW/dr| at q = 2/3): its bulk
# moves at up to 0.2 m/s around 0.2 s and settles (measured: 0.199 m/s at 0.22 s, 0.13 m/s at
# 0.6 s; the Wendland run 0.045 m/s), so the bound is half the instability's speed, 0.22 m/s,
# not test_hydrostatic.sh's 0.05 sqrt(g H) = 0.11 m/s, which the Wendland run is checked against.
vmax=$(awk -F'\t' '!/^#/ {n++; if ($7 > v) v = $7} END {if (n) print v + 0; else print "none"}' "$TSV")
vmax2=$(awk -F'\t' '!/^#/ {n++; if ($7 > v) v = $7} END {if (n) print v + 0; else print "none"}' "$T/run2/run.tsv")
echo "# max speed at rest: cubic $vmax m/s, Wendland $vmax2 m/s"
check "cubic: max speed $vmax m/s < 0.5 sqrt(g dp)" awk -v v="$vmax" -v g=$G -v dp=$DP 'BEGIN {exit !(v != "none" && v < 0.5 * sqrt(g * dp))}'
check "Wendland: max speed $vmax2 m/s < 0.05 sqrt(g H)" awk -v v="$vmax2" -v g=$G -v h=$H 'BEGIN {exit !(v != "none" && v < 0.05 * sqrt(g * h))}'
p1=$(bottom_pressure "$T/run1") p2=$(bottom_pressure "$T/run2")
pref=$(awk -v r=$RHO0 -v g=$G -v h=$H -v dp=$DP 'BEGIN {print r * g * (h - dp / 2)}')
echo "# bottom pressure: cubic $p1 Pa, Wendland $p2 Pa, rho0 g (H - dp/2) = $pref Pa"
check "cubic: bottom pressure within 3% of hydrostatic ($p1 Pa)" \
    awk -v p="$p1" -v q="$pref" 'BEGIN {exit !(p != "none" && (p - q) / q < 0.03 && (q - p) / q < 0.03)}'
check "cubic and Wendland bottom pressures within 2% ($p1, $p2 Pa)" \
    awk -v p="$p1" -v q="$p2" 'BEGIN {exit !(p != "none" && q != "none" && (p - q) / q < 0.02 && (q - p) / q < 0.02)}'
values /Domains/D0/Position "$(ls "$T/run1"/snap_*.h5 | tail -1)" >"$T/pos1"
values /Domains/D0/Position "$(ls "$T/run2"/snap_*.h5 | tail -1)" >"$T/pos2"
check "the kernels give different states" bash -c "[ -s '$T/pos1' ] && [ -s '$T/pos2' ] && ! cmp -s '$T/pos1' '$T/pos2'"

# ---- the dam break at a coarse dp
for k in 1 2; do
    expect 0 "gencase the dam break at dp 0.025, Kernel=$k" "$BIN/vres-gencase" -q --dp 0.025 --set Kernel=$k \
        "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" -o "$T/db$k.h5"
    expect 0 "run the dam break to 0.3 s, Kernel=$k" "$RUN" -q --threads 1 --tmax 0.3 --tout 0.1 "$T/db$k.h5" -o "$T/db$k"
done
n0=$(values /Domains/D0/Type "$T/db1.h5" | awk '$1 == 0 {n++} END {print n + 0}')
n1=$(awk -F'\t' '!/^#/ {n = $4} END {print n + 0}' "$T/db1/run.tsv")
check "cubic dam break: every fluid particle kept ($n1 of $n0)" [ "$n0" -gt 0 -a "$n1" -eq "$n0" ]
f1=$(front "$(ls "$T/db1"/snap_*.h5 | tail -1)") f2=$(front "$(ls "$T/db2"/snap_*.h5 | tail -1)")
echo "# surge front at 0.3 s: cubic $f1 m, Wendland $f2 m (column 1 m wide at t = 0)"
check "cubic dam break: the front has left the column ($f1 m > 1.5 m)" awk -v f="$f1" 'BEGIN {exit !(f != "none" && f > 1.5)}'
check "cubic and Wendland fronts within 5% ($f1, $f2 m)" \
    awk -v a="$f1" -v b="$f2" 'BEGIN {exit !(a != "none" && b != "none" && (a - b) / b < 0.05 && (b - a) / b < 0.05)}'
