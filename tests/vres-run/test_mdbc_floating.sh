#!/usr/bin/env bash
# Floating bodies with mDBC walls (Boundary=2). mDBC sets a wall's density from the fluid beside
# it, so a body's particles must push the fluid as much as a fixed wall's do: they carry the
# mass of the fluid they stand in for (rho0 dp^2), not their share of the body's mass (which
# DualSPHysics 5.4 uses, and with which a box of density 500 held in still water let 122 fluid
# particles into itself in 0.3 s). Checked here:
#   * cases/floating_box2d's box held by its degrees of freedom (translationDOF 0) leaves the
#     fluid exactly as the same box drawn as a fixed wall does (h5diff of every fluid particle's
#     position, velocity and density after 0.2 s): the same pair terms, the same masses;
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
    expect 0 "run the $v box 0.2 s" "$BIN/vres-run" --threads 1 --tout 0.1 "$T/$v.h5" -o "$T/$v"
    cp "$ERR" "$T/$v.err"
done
check "the held box's run warns that mDBC gives a body no contact with the other walls" \
    grep -q 'mDBC) with floating bodies: .*no contact with the other walls' "$T/held.err"
check "the fixed wall's run does not" sh -c "! grep -q 'no contact' '$T/wall.err'"
# the fluid: the same ids in the same order? compare sorted by id
fluid() { paste <(values /Domains/D0/Id "$1") <(values /Domains/D0/Type "$1") \
                <(values /Domains/D0/Position "$1" | paste - - -) <(values /Domains/D0/Velocity "$1" | paste - - -) \
                <(values /Domains/D0/Density "$1") | awk '$2 == 0' | sort -n; }
fluid "$T/held/snap_00002.h5" >"$T/fh"
fluid "$T/wall/snap_00002.h5" >"$T/fw"
n=$(wc -l <"$T/fh")
check "0.2 s run in both (snap_00002.h5 with $n fluid particles)" [ "$n" -gt 500 -a -s "$T/fw" ]
check "the fluid beside the held floating box is the fluid beside the fixed box, bit for bit ($n particles)" \
    cmp -s "$T/fh" "$T/fw"
inside=$(paste <(values /Domains/D0/Type "$T/held/snap_00002.h5") \
               <(values /Domains/D0/Position "$T/held/snap_00002.h5" | paste - - -) |
         awk '{t[NR] = $1; x[NR] = $2; z[NR] = $4}
              $1 == 4 { if (!nb++ || $2 < xl) xl = $2; if (nb == 1 || $2 > xh) xh = $2
                        if (nb == 1 || $4 < zl) zl = $4; if (nb == 1 || $4 > zh) zh = $4 }
              END { for (i = 1; i <= NR; i++) if (t[i] == 0 && x[i] > xl && x[i] < xh && z[i] > zl && z[i] < zh) n++
                    print n + 0 }')
check "no fluid inside the held box ($inside particles)" [ "$inside" -eq 0 ]
mass=$(paste <(values /Domains/D0/Type "$T/held/snap_00002.h5") <(values /Domains/D0/Mass "$T/held/snap_00002.h5") |
       awk '$1 == 4 {n++; e = $2 / (1000 * 0.025 * 0.025) - 1; if (e > 1e-12 || e < -1e-12) bad++} END {print n + 0, bad + 0}')
set -- $mass
check "the box's $1 particles carry rho0 dp^2 = 0.625 kg each ($2 do not)" [ "$1" -gt 0 -a "$2" -eq 0 ]
bm=$(h5dump -a /Bodies/B0/mass "$T/held/snap_00002.h5" | awk '/\(0\)/ {print $2}')
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
