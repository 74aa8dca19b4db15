#!/usr/bin/env bash
# The coupled variable-resolution run in 3-D, end to end: cases/tank_vres3d (still water 0.2 m
# deep in a 0.4 m x 0.4 m tank, dp 0.02 m, a refinement box of dpratio 2 across the free
# surface; tests/vres-partition/test_3d.sh checks its partition) through
# vres-gencase | vres-partition - | vres-run - for about 30 steps, then vres-vtk. Both domains
# must step, stay finite, keep their counts and mass (nothing crosses the interface at rest in
# 4 ms), the segments accumulate mass, a restart continues bit for bit (h5diff, as
# test_vres_restart.sh does in 2-D), and the VTK holds both domains. About 40 steps of 28,800
# particles in all: 19 to 22 s on one thread of the loaded 2-core VM (fewer on two).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
CASE=$CASES/tank_vres3d/tank_vres3d_Def.xml

# ---- the pipe: three outputs about 10 steps apart (dt 1.3e-4 s, set by the box's h)
"$BIN/vres-gencase" -q "$CASE" | "$BIN/vres-partition" -q - | "$RUN" -q --tmax 0.0039 --tout 0.0013 - -o "$T/a" 2>"$ERR"
ps="${PIPESTATUS[*]}"
check "vres-gencase CASE | vres-partition - | vres-run - -o DIR: every stage exits 0 ($ps)" [ "$ps" = "0 0 0" ]
sed 's/^/#   /' "$ERR" | head -10
check "snapshots 0 to 3 written" [ -f "$T/a/snap_00003.h5" -a ! -e "$T/a/snap_00004.h5" ]
last=$T/a/snap_00003.h5
check "snap_00003.h5 holds domains D0 and D1 and two interfaces" \
    [ "$(h5ls "$last/Domains" | awk '{printf "%s ", $1}')" = "D0 D1 " -a "$(h5ls "$last/Interfaces" | wc -l)" -eq 2 ]
check "it is 3-D" [ "$(h5dump -a /dim "$last" | sed -n 's/^ *(0): //p')" = 3 ]
steps=$(grep -v '^#' "$T/a/run.tsv" | tail -1 | cut -f2)
check "about 30 steps ($steps)" [ "${steps:-0}" -ge 20 -a "${steps:-0}" -le 45 ]

# ---- both domains stepped: every fluid and buffer particle of each domain moved (gravity and
# the start-up transient move them all), and each has its own dt in the ledger
L=$T/a/ledger.tsv
for k in 0 1; do
    # particles matched by id (the cell sort orders each cell by x, which moves with them)
    moved=$(paste <(paste <(values /Domains/D$k/Id "$T/a/snap_00000.h5") <(values /Domains/D$k/Type "$T/a/snap_00000.h5") \
                          <(values /Domains/D$k/Position "$T/a/snap_00000.h5" | paste - - -) | sort -n -k1,1) \
                  <(paste <(values /Domains/D$k/Id "$last") <(values /Domains/D$k/Position "$last" | paste - - -) |
                    sort -n -k1,1) |
        awk '$2 <= 1 {n++; if ($1 != $6) bad++; else if ($3 != $7 || $4 != $8 || $5 != $9) m++}
             END {print n + 0, m + 0, bad + 0}')
    read -r n m bad <<<"$moved"
    check "D$k stepped: all $n fluid and buffer particles moved ($m), the same ids ($bad differ)" \
        [ "$n" -gt 0 -a "$m" -eq "$n" -a "$bad" -eq 0 ]
    dto=$(awk -F'\t' -v k=$k '!/^#/ && $3 == k {d = $4} END {print d}' "$L")
    check "ledger: D$k's own dt at the end ($dto s) is positive" awk -v d="$dto" 'BEGIN {exit !(d > 0)}'
done
check "ledger: the box's own dt is half the root's (h halves; 2% for the speeds)" \
    awk -F'\t' '!/^#/ && $2 > 0 {d[$3] = $4} END {r = d[0] / d[1]; exit !(r > 1.96 && r < 2.04)}' "$L"
# (the ledger's own dt is each domain's estimate at the output, run.tsv's the last step's: 1%)
dtrun=$(grep -v '^#' "$T/a/run.tsv" | tail -1 | cut -f3)
check "run.tsv's dt ($dtrun s) is the box's, the minimum over domains, to 1%" \
    awk -F'\t' -v d="$dtrun" '!/^#/ && $2 > 0 {o[$3] = $4} END {m = o[0] < o[1] ? o[0] : o[1]; exit !(m == o[1] && d > 0.99 * m && d < 1.01 * m)}' "$L"

# ---- finite, counts and mass kept: the partition's counts (test_3d.sh) at every output
check "no NaN or inf in run.tsv and ledger.tsv" sh -c "! grep -v '^#' '$T/a/run.tsv' '$L' | grep -q -i 'nan\|inf'"
fin=1
for d in D0 D1; do for ds in Position Velocity Density Pressure; do
    h5dump -d "/Domains/$d/$ds" "$last" | grep -q -i 'nan\|inf' && fin=0
done; done
check "snap_00003.h5: finite positions, velocities, densities, pressures in both domains" [ $fin = 1 ]
check "ledger: D0 3300 fluid + 692 buffer, D1 5600 + 8512 at every output" \
    awk -F'\t' '!/^#/ && !(($3 == 0 && $5 == 3300 && $6 == 692) || ($3 == 1 && $5 == 5600 && $6 == 8512)) {exit 1}' "$L"
m0=$(grep -v '^#' "$L" | head -1 | cut -f19)
dr=$(grep -v '^#' "$L" | tail -1 | cut -f20)
# one fine particle (rho0 dp^3 = 0.001 kg) against the 32 kg of water: 3.1e-5
check "total fluid mass $m0 kg (3300 x 0.008 + 5600 x 0.001)" awk -v m="$m0" 'BEGIN {exit !(m > 31.9999 && m < 32.0001)}'
check "ledger's drift ($dr) finite and within one fine particle's mass (3.1e-5)" \
    awk -v d="$dr" 'BEGIN {exit !(d == d + 0 && d <= 3.1e-5 && d >= -3.1e-5)}'
# the segments' sums are signed (vres-run(1)): at rest they hold the interpolated noise, small
# and of either sign, which the restart below must carry over exactly
nz=$(values /Interfaces/I0/Mass "$last" | awk '$1 != 0 {n++} END {print n + 0}')
check "snap_00003.h5: the box's segments have accumulated ($nz of 4704 nonzero)" [ "$nz" -gt 0 ]
smax=$(values /Interfaces/I0/Mass "$last" | awk '{a = $1 < 0 ? -$1 : $1; if (a > m) m = a} END {print m + 0}')
check "every segment of I0 within one fine particle's mass, 0.001 kg (largest |m| $smax): nothing created" \
    awk -v s="$smax" 'BEGIN {exit !(s > 0 && s < 0.001)}'

# ---- restart from snap_00001.h5 (about 20 steps continued): bit for bit
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00001.h5" "$RUN" -q --restart "$T/b/snap_00001.h5"
bad=
for k in 2 3; do
    f=$(printf 'snap_%05d.h5' $k)
    for d in D0 D1; do for ds in Position Velocity Density Pressure Mass Type Mk Id; do
        h5diff -q "$T/a/$f" "$T/b/$f" "/Domains/$d/$ds" "/Domains/$d/$ds" >/dev/null || bad="$bad $f:$d/$ds"
    done; done
    for i in I0 I1; do
        h5diff -q "$T/a/$f" "$T/b/$f" "/Interfaces/$i/Mass" "/Interfaces/$i/Mass" >/dev/null || bad="$bad $f:$i/Mass"
    done
done
check "restart: snap_00002.h5 and snap_00003.h5 equal to the uninterrupted run's, both domains and interfaces${bad:+ (differ:$bad)}" [ -z "$bad" ]
check "restart: run.tsv's times, steps, counts, masses, speeds, densities the same" \
    diff <(grep -v '^#' "$T/a/run.tsv" | cut -f1-9) <(grep -v '^#' "$T/b/run.tsv" | cut -f1-9)
check "restart: ledger.tsv the same file" cmp -s "$T/a/ledger.tsv" "$T/b/ledger.tsv"

# ---- vres-vtk: both domains in one file (its Domain array), counted with VTK's own reader
expect 0 "vres-vtk --buffers on the run directory" "$BIN/vres-vtk" --buffers "$T/a" -o "$T/vtk"
vtu=$T/vtk/a_00003.vtu   # vres-vtk names the files after the run directory
check "a_00003.vtu has the Domain array" grep -a -q '<DataArray [^>]*Name="Domain"' "$vtu"
MAKER=$ROOT/$VRES_BUILD/tests/test_vtkio
if VRES_TEST_VTU_COUNT=$vtu "$MAKER" >"$T/vtu.txt" 2>/dev/null; then
    check "a_00003.vtu: domains 0 and 1" [ "$(cut -d' ' -f1 "$T/vtu.txt" | sort -u | tr '\n' ' ')" = "0 1 " ]
    check "a_00003.vtu: D0 3300 fluid + 692 buffer, D1 5600 + 8512" \
        [ "$(awk '$2 == "fluid" || $2 == "buffer" {printf "%s %s %s,", $1, $2, $3}' "$T/vtu.txt" | tr ',' '\n' | sort | tr '\n' ',')" \
          = "0 buffer 692,0 fluid 3300,1 buffer 8512,1 fluid 5600," ]
else notok "count the .vtu with $MAKER (build it: make $VRES_BUILD/tests/test_vtkio)"; fi
