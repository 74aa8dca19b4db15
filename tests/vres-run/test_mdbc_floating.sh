#!/usr/bin/env bash
# Floating bodies with mDBC walls (Boundary=2). mDBC sets a wall's density from the fluid beside
# it, so a body's particles must push the fluid as much as a fixed wall's do: they carry the
# mass of the fluid they stand in for (rho0 dp^2), not their share of the body's mass (which
# DualSPHysics 5.4 uses, and with which a box of density 500 held in still water let 122 fluid
# particles into itself in 0.3 s); their mDBC densities are kept at rho0 or above (a body must
# not draw the fluid in; kernels/mdbc.h). Checked here:
#   * cases/floating_box2d's box held by its degrees of freedom (translationDOF 0) keeps the
#     fluid out and feels the force the same box drawn as a fixed wall feels: the mean over 10
#     snapshots within 1% (the runs differ only where the fixed box's mDBC densities fall below
#     rho0, near the free surface: 0.13% apart at dp 0.01 over 0.6 s; with the body's mass
#     share the held box felt 45% less and let the fluid in);
#   * the snapshots keep the body's mass (/Bodies) and its particles' fluid mass;
#   * the box released: a restart from a snapshot continues bit for bit;
#   * the warning that mDBC gives a body no contact with the other walls.
# The draft and heave period of the released box at the case's dp: cases/floating_box2d/README.md.
source "$(dirname "$0")/../harness.sh"
XML=$CASES/floating_box2d/floating_box2d_Def.xml
sed -e 's|<rotationDOF x="0" y="0" z="0" comment="Heave and sway only: the box is unstable in roll" />|<rotationDOF x="0" y="0" z="0" /> <translationDOF x="0" y="0" z="0" />|' \
    -e 's|key="TimeMax" value="2.5"|key="TimeMax" value="0.2"|' "$XML" >"$T/held_Def.xml"
check "the held box's case has translationDOF 0" grep -q '<translationDOF x="0" y="0" z="0" />' "$T/held_Def.xml"
awk '/<floatings>/ {skip = 1} !skip {print} /<\/floatings>/ {skip = 0}' "$T/held_Def.xml" >"$T/wall_Def.xml"
check "the wall box's case has no <floatings>" [ "$(grep -c '<floating' "$T/wall_Def.xml")" -eq 0 ]
for v in held wall; do
    expect 0 "gencase the $v box with mDBC at dp 0.025" "$BIN/vres-gencase" --dp 0.025 --set Boundary=2 \
        "$T/${v}_Def.xml" -o "$T/$v.h5"
    expect 0 "run the $v box 0.2 s" "$BIN/vres-run" --threads 1 --tout 0.02 "$T/$v.h5" -o "$T/$v"
    cp "$ERR" "$T/$v.err"
done
check "the held box's run warns that mDBC gives a body no contact with the other walls" \
    grep -q 'mDBC) with floating bodies: .*no contact with the other walls' "$T/held.err"
check "the fixed wall's run does not" sh -c "! grep -q 'no contact' '$T/wall.err'"
n=$(ls "$T"/held/snap_*.h5 "$T"/wall/snap_*.h5 2>/dev/null | wc -l)
check "0.2 s run in both (22 snapshots: $n)" [ "$n" -eq 22 ]
mean_fz() { "$BIN/vres-forces" --mk 1 "$1" 2>/dev/null | awk -F'\t' '!/^#/ && $1 > 0 {s += $4; n++} END {if (n) printf "%.6g %d", s / n, n}'; }
read -r fh nh < <(mean_fz "$T/held")
read -r fw nw < <(mean_fz "$T/wall")
echo "# mean vertical force over $nh snapshots: held floating box $fh N/m, fixed box $fw N/m"
check "the held floating box feels the fixed box's force: means $fh and $fw N/m within 1%" \
    awk -v a="$fh" -v b="$fw" -v n="$nh" 'BEGIN {e = a / b - 1; exit !(n == 10 && b > 100 && e < 0.01 && e > -0.01)}'
inside=$(paste <(values /Domains/D0/Type "$T/held/snap_00010.h5") \
               <(values /Domains/D0/Position "$T/held/snap_00010.h5" | paste - - -) |
         awk '{t[NR] = $1; x[NR] = $2; z[NR] = $4}
              $1 == 4 { if (!nb++ || $2 < xl) xl = $2; if (nb == 1 || $2 > xh) xh = $2
                        if (nb == 1 || $4 < zl) zl = $4; if (nb == 1 || $4 > zh) zh = $4 }
              END { for (i = 1; i <= NR; i++) if (t[i] == 0 && x[i] > xl && x[i] < xh && z[i] > zl && z[i] < zh) n++
                    print n + 0 }')
check "no fluid inside the held box ($inside particles)" [ "$inside" -eq 0 ]
mass=$(paste <(values /Domains/D0/Type "$T/held/snap_00010.h5") <(values /Domains/D0/Mass "$T/held/snap_00010.h5") |
       awk '$1 == 4 {n++; e = $2 / (1000 * 0.025 * 0.025) - 1; if (e > 1e-12 || e < -1e-12) bad++} END {print n + 0, bad + 0}')
set -- $mass
check "the box's $1 particles carry rho0 dp^2 = 0.625 kg each ($2 do not)" [ "$1" -gt 0 -a "$2" -eq 0 ]
bm=$(h5dump -a /Bodies/B0/mass "$T/held/snap_00010.h5" | awk '/\(0\)/ {print $2}')
check "the body keeps its own mass in /Bodies ($bm kg = 500 kg/m^3 x $1 x dp^2)" \
    awk -v m="$bm" -v n="$1" 'BEGIN {e = m / (500 * n * 0.025 * 0.025) - 1; exit !(e < 1e-12 && e > -1e-12)}'

# the box released (the case's 0.06 m above its equilibrium): a restart continues bit for bit
sed 's|key="TimeMax" value="2.5"|key="TimeMax" value="0.3"|' "$XML" >"$T/free_Def.xml"
expect 0 "gencase the free box with mDBC" "$BIN/vres-gencase" --dp 0.025 --set Boundary=2 "$T/free_Def.xml" -o "$T/free.h5"
expect 0 "run the free box 0.3 s" "$BIN/vres-run" -q --threads 1 --tout 0.1 "$T/free.h5" -o "$T/free"
z0=$(h5dump -a /Bodies/B0/center "$T/free/snap_00000.h5" | awk '/\(0\)/ {print $4}')
z3=$(h5dump -a /Bodies/B0/center "$T/free/snap_00003.h5" | awk '/\(0\)/ {print $4}')
check "the released box sinks toward its equilibrium (centre z $z0 -> $z3 m)" \
    awk -v a="$z0" -v b="$z3" 'BEGIN {exit !(b < a - 0.01 && b > a - 0.2)}'
same_after_restart "free box, mDBC" "$T/free" 00001 00003
for a in center vel quat; do
    check "free box, mDBC: /Bodies/B0 $a after the restart equals the uninterrupted run's" \
        [ "$(h5dump -a /Bodies/B0/$a "$T/free/snap_00003.h5" | grep '(0)')" = \
          "$(h5dump -a /Bodies/B0/$a "$T/free.r/snap_00003.h5" | grep '(0)')" ]
done
