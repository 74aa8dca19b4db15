#!/usr/bin/env bash
# A small 3D case in the vocabulary of DualSPHysics' CaseFloating (written here, not copied):
# body-centred cubic walls (<lattice bound="2">), <mkorientfluid>, <setshapemode>dp | real |
# bound</setshapemode>, a cmt comment, a face-drawn tank open on the left and top (boxfill
# "bottom | right | front | back"), a solid piston moving with <mvrectsinu>, a floating box of
# given <massbody> (and relativeweight, refused beside rhopbody or at 0), the water a <fillbox> of void, RigidAlgorithm, FtPause and a simulation
# domain "default + 20%". vres-gencase reads it whole, with the particle counts worked out by
# hand below; vres-run runs it for 0.1 s. The body, 40 kg, floats up: its particles span
# z 0.4..0.8 and the water's reach 0.6, so with DBC's half-dp gaps 0.3 m of its 0.5 m are
# immersed, 75 kg of water on a 0.5 m square: 343 N upward at most, 4.3 cm in 0.1 s at most.
source "$(dirname "$0")/../harness.sh"
cat >"$T/fl_Def.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<case>
    <casedef>
        <constantsdef>
            <lattice bound="2" fluid="1" />
            <gravity x="0" y="0" z="-9.81" /> <rhop0 value="1000" /> <gamma value="7" />
            <hswl value="0" auto="true" /> <speedsystem value="0" auto="true" />
            <coefsound value="20" /> <speedsound value="0" auto="true" />
            <coefh value="1.0" /> <cflnumber value="0.2" />
        </constantsdef>
        <mkconfig boundcount="230" fluidcount="9">
            <mkorientfluid mk="0" orient="Xyz" />
        </mkconfig>
        <geometry>
            <definition dp="0.1">
                <pointmin x="-0.5" y="-0.5" z="-0.5" /> <pointmax x="2.5" y="1.5" z="1.5" />
            </definition>
            <commands>
                <mainlist>
                    <setshapemode>dp | real | bound</setshapemode>
                    <setdrawmode mode="full" />
                    <setmkbound mk="10" />
                    <drawbox cmt="Piston"> <boxfill>solid</boxfill>
                        <point x="0.2" y="0" z="0" /> <size x="0.1" y="1" z="0.8" /> </drawbox>
                    <setdrawmode mode="face" />
                    <setmkbound mk="20" />
                    <drawbox> <boxfill>bottom | right | front | back</boxfill>
                        <point x="0" y="0" z="0" /> <size x="2" y="1" z="1" /> </drawbox>
                    <setdrawmode mode="full" />
                    <setmkbound mk="50" />
                    <drawbox> <boxfill>solid</boxfill>
                        <point x="1.2" y="0.3" z="0.4" /> <size x="0.4" y="0.4" z="0.4" /> </drawbox>
                    <setmkfluid mk="0" />
                    <fillbox x="1" y="0.5" z="0.2"> <modefill>void</modefill>
                        <point x="0" y="0" z="0" /> <size x="2" y="1" z="0.6" /> </fillbox>
                    <shapeout file="" reset="true" />
                </mainlist>
            </commands>
        </geometry>
        <motion>
            <objreal ref="10">
                <begin mov="1" start="0" finish="100" />
                <mvrectsinu id="1" duration="50"> <freq x="0.5" y="0" z="0" /> <ampl x="0.1" y="0" z="0" /> </mvrectsinu>
            </objreal>
        </motion>
        <floatings>
            <floating mkbound="50"> <massbody value="40" /> </floating>
        </floatings>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Kernel" value="2" />
            <parameter key="ViscoTreatment" value="1" /> <parameter key="Visco" value="0.05" />
            <parameter key="DensityDT" value="2" /> <parameter key="RigidAlgorithm" value="1" />
            <parameter key="FtPause" value="0.0" />
            <parameter key="TimeMax" value="0.1" /> <parameter key="TimeOut" value="0.05" />
            <simulationdomain>
                <posmin x="default" y="default" z="default" />
                <posmax x="default" y="default" z="default + 20%" />
            </simulationdomain>
        </parameters>
    </execution>
</case>
XML
expect 0 "CaseFloating's vocabulary passes --check" "$BIN/vres-gencase" --check "$T/fl_Def.xml"
check "with no warning" [ "$(grep -c -E 'warning|error' "$ERR")" -eq 0 ]
expect 0 "and generates" "$BIN/vres-gencase" -q "$T/fl_Def.xml" -o "$T/fl.h5"

# count TYPE MK: particles of that type and mk (vres-info's table)
count() { "$BIN/vres-info" -t "$T/fl.h5" | awk -F'\t' -v t="$1" -v m="$2" '$2 == t && $3 == m {print $4}'; }
# Lattice nodes: the tank's faces at x=2, y=0, y=1, z=0 (231 + 110 + 200 + 200), the piston's
# 2 x 11 x 9 less the 22 + 32 the tank's faces drew over, the body's 5^3; the fluid fills
# x 0.4..1.9, y 0.1..0.9, z 0.1..0.6 (16 x 9 x 6) less the body's 75 nodes there.
# Cell centres: the tank's half a dp outside its faces (264 + 132 + 231 + 231), the piston's
# and the body's inside them (1 x 10 x 8 and 4^3).
check "fixed walls: 741 nodes + 858 centres" [ "$(count fixed 20)" = 1599 ]
check "piston: 144 nodes + 80 centres" [ "$(count moving 10)" = 224 ]
check "floating box: 125 nodes + 64 centres" [ "$(count floating 50)" = 189 ]
check "fluid: 789 on the cubic lattice" [ "$(count fluid 0)" = 789 ]
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN {d = a - b; if (d < 0) d = -d; exit !(d <= t)}'; }
check "the body's mass is its massbody" near "$(attr /Bodies/B0/mass "$T/fl.h5")" 40 1e-9
check "shared by its 189 particles" near "$(values /Domains/D0/Mass "$T/fl.h5" | sed -n "$((1599 + 224 + 1))p")" "$(awk 'BEGIN {print 40 / 189}')" 1e-6
check "walls weigh rho0 dp^3, centres too" [ "$(values /Domains/D0/Mass "$T/fl.h5" | head -1599 | sort -u | awk '{printf "%.9g\n", $1}')" = 1 ]
# the walls' box: the tank's centres at z -0.05 up to its faces' top 1.05; 20% of 1.1 above
check "domain top: default + 20%" near "$(attr /Parameters/domain_max "$T/fl.h5" | sed -n 3p)" 1.27 1e-9

# DualSPHysics' examples give a body's density as relativeweight, its ratio to rhop0
# (examples/main/11_Floating: relativeweight="1.20"): the same body as rhopbody 500
sed 's|<floating mkbound="50"> <massbody value="40" /> </floating>|<floating mkbound="50" relativeweight="0.5" />|' \
    "$T/fl_Def.xml" >"$T/rw_Def.xml"
sed 's|<floating mkbound="50"> <massbody value="40" /> </floating>|<floating mkbound="50" rhopbody="500" />|' \
    "$T/fl_Def.xml" >"$T/rb_Def.xml"
expect 0 "relativeweight 0.5: generates" "$BIN/vres-gencase" -q "$T/rw_Def.xml" -o "$T/rw.h5"
expect 0 "rhopbody 500: generates" "$BIN/vres-gencase" -q "$T/rb_Def.xml" -o "$T/rb.h5"
mrw=$(attr /Bodies/B0/mass "$T/rw.h5") mrb=$(attr /Bodies/B0/mass "$T/rb.h5")
check "relativeweight 0.5 weighs what rhopbody 500 does ($mrw and $mrb kg; 189 x 500 x 0.1^3 / 2 = 47.25)" \
    sh -c "[ '$mrw' = '$mrb' ] && awk -v m='$mrw' 'BEGIN {d = m - 47.25; exit !(d < 1e-9 && d > -1e-9)}'"
sed 's|relativeweight="0.5"|relativeweight="0.5" rhopbody="500"|' "$T/rw_Def.xml" >"$T/rw2_Def.xml"
expect_err 1 'rw2_Def\.xml:[0-9]+: only one of rhopbody and relativeweight may be given' "relativeweight and rhopbody: refused" \
    "$BIN/vres-gencase" "$T/rw2_Def.xml" -o "$T/rw2.h5"
check "relativeweight and rhopbody: nothing written" [ ! -e "$T/rw2.h5" ]
sed 's|relativeweight="0.5"|relativeweight="0"|' "$T/rw_Def.xml" >"$T/rw0_Def.xml"
expect_err 1 'rw0_Def\.xml:[0-9]+: relativeweight must be greater than zero \(0\)' "relativeweight 0: refused" \
    "$BIN/vres-gencase" "$T/rw0_Def.xml" -o "$T/rw0.h5"

# a body of zero or negative mass: one message naming the element and its line, nothing written
for kv in 'massbody value="0":massbody must be greater than zero \(0\)' \
          'massbody value="-5":massbody must be greater than zero \(-5\)'; do
    sed "s|<massbody value=\"40\" />|<${kv%%:*} />|" "$T/fl_Def.xml" >"$T/m_Def.xml"
    expect_err 1 "m_Def\.xml:[0-9]+: ${kv#*:}" "${kv%%:*}: refused" "$BIN/vres-gencase" "$T/m_Def.xml" -o "$T/m.h5"
    check "${kv%%:*}: one message" [ "$(grep -c '^vres-gencase: ' "$ERR")" -eq 1 ]
    check "${kv%%:*}: nothing written" [ ! -e "$T/m.h5" ]
done
sed 's|<floating mkbound="50"> <massbody value="40" /> </floating>|<floating mkbound="50" rhopbody="-500" />|' \
    "$T/fl_Def.xml" >"$T/m_Def.xml"
expect_err 1 'm_Def\.xml:[0-9]+: rhopbody must be greater than zero \(-500\)' "rhopbody -500: refused" \
    "$BIN/vres-gencase" "$T/m_Def.xml" -o "$T/m.h5"
check "rhopbody -500: one message" [ "$(grep -c '^vres-gencase: ' "$ERR")" -eq 1 ]

expect 0 "vres-run runs it" "$BIN/vres-run" -q --threads 1 "$T/fl.h5" -o "$T/run"
"$BIN/vres-forces" --mk 50 "$T/run" >"$T/body.tsv" 2>"$ERR" || notok "vres-forces on the body"
# columns: time fx fy fz mx my mz cx cy cz vx vy vz angle
last=$(grep -v '^#' "$T/body.tsv" | tail -1)
check "the run reached 0.1 s" near "$(cut -f1 <<<"$last")" 0.1 0.002
check "the body rises, by less than 4.3 cm" awk -v z="$(cut -f10 <<<"$last")" 'BEGIN {d = z - 0.6; exit !(d > 0 && d < 0.043)}'
# the piston's push (0.31 m/s at the start) reaches it: it drifts and tilts a little (0.0067 rad)
check "pushed along +x by the piston" awk -v v="$(cut -f11 <<<"$last")" 'BEGIN {exit !(v > 0 && v < 0.31)}'
check "and tilts by less than 0.05 rad" awk -v a="$(cut -f14 <<<"$last")" 'BEGIN {exit !(a < 0.05 && a > -0.05)}'
check "no particle left the domain" [ "$(grep -v '^#' "$T/run/run.tsv" | tail -1 | cut -f12)" = 0 ]
exit 0
