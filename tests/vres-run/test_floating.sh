#!/usr/bin/env bash
# vres-run with floating bodies (<floatings>): in a 2-D tank of still water,
#   body 1, a 0.04 m square of rhopbody 500 well above the water, released turning at 3 rad/s
#     about y: it falls freely and turns uniformly until it nears the water, so after 0.1 s its
#     centre has dropped by g t^2/2 and turned by 0.3 rad, its particles kept rigidly about it
#     (the Symplectic scheme is exact for a constant force, so to 1e-9 m);
#   body 2, a 0.04 x 0.02 m block held in the water by its degrees of freedom (all fixed): it
#     stays where it is, and the fluid pushes it up (buoyancy, with DBC's noise);
#   body 3, the same block with translation along x only: it stays at its height.
# Then cases/floating_box2d at dp 0.04, turning at 1 rad/s, restarts from a snapshot bit for
# bit (particles and /Bodies), the module list names the floating bodies, and what vres-run
# does not run with them (mDBC, Verlet restarts aside) is refused with nothing written.
source "$(dirname "$0")/../harness.sh"
# the constants and the start of both cases below
consts() {
    cat <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<case>
    <casedef>
        <constantsdef>
            <gravity x="0" y="0" z="-9.81" /> <rhop0 value="1000" /> <gamma value="7" />
            <hswl value="0" auto="true" /> <speedsystem value="0" auto="true" />
            <coefsound value="20" /> <speedsound value="0" auto="true" />
            <coefh value="1.0" /> <cflnumber value="0.2" />
        </constantsdef>
        <mkconfig boundcount="240" fluidcount="9" />
XML
}
{ consts; cat <<'XML'
        <geometry>
            <definition dp="0.01">
                <pointref x="0.005" y="0" z="0.005" />
                <pointmin x="-0.1" y="0" z="-0.1" /> <pointmax x="0.5" y="0" z="0.5" />
            </definition>
            <commands>
                <mainlist>
                    <setdrawmode mode="solid" />
                    <setmkfluid mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="0" /> <size x="0.4" y="0" z="0.1" /> </drawbox>
                    <setmkbound mk="0" />
                    <setnormalinvert invert="true" />
                    <drawbox> <boxfill>bottom | left | right</boxfill> <layers vdp="0.5,1.5,2.5" />
                        <point x="0" y="0" z="0" /> <size x="0.4" y="0" z="0.35" /> </drawbox>
                    <setnormalinvert invert="false" />
                    <setmkbound mk="1" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.08" y="0" z="0.2" /> <size x="0.04" y="0" z="0.04" /> </drawbox>
                    <setmkbound mk="2" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.2" y="0" z="0.04" /> <size x="0.04" y="0" z="0.02" /> </drawbox>
                    <setmkbound mk="3" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.3" y="0" z="0.04" /> <size x="0.04" y="0" z="0.02" /> </drawbox>
                </mainlist>
            </commands>
        </geometry>
        <floatings>
            <floating mkbound="1" rhopbody="500"> <angularvelini x="0" y="3" z="0" /> </floating>
            <floating mkbound="2" rhopbody="500">
                <translationDOF x="0" y="0" z="0" /> <rotationDOF x="0" y="0" z="0" />
            </floating>
            <floating mkbound="3" rhopbody="500"> <translationDOF x="1" y="0" z="0" /> <rotationDOF x="0" y="0" z="0" /> </floating>
        </floatings>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Visco" value="0.01" />
            <parameter key="DensityDT" value="2" />
            <parameter key="TimeMax" value="0.1" /> <parameter key="TimeOut" value="0.05" />
        </parameters>
    </execution>
</case>
XML
} >"$T/fl_Def.xml"
# near A B TOL: |A - B| <= TOL
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN {d = a - b; if (d < 0) d = -d; exit !(d <= t)}'; }

"$BIN/vres-gencase" -q "$T/fl_Def.xml" -o "$T/fl.h5" || notok "gencase the three bodies"
expect 0 "run 0.1 s" "$BIN/vres-run" --threads 1 "$T/fl.h5" -o "$T/r"
check "modules name the floating bodies" grep -q 'floating-bodies(32 particles)' "$ERR"
S0=$T/r/snap_00000.h5 S2=$T/r/snap_00002.h5
t=$(attr /time "$S2")
read -r cx0 _ cz0 <<<"$(attr /Bodies/B0/center "$S0" | tr '\n' ' ')"
read -r cx _ cz <<<"$(attr /Bodies/B0/center "$S2" | tr '\n' ' ')"
zf=$(awk -v z="$cz0" -v t="$t" 'BEGIN {printf "%.12f", z - 9.81 * t * t / 2}')
check "body 1 falls freely: centre z $cz = z0 - g t^2/2 = $zf at t = $t" near "$cz" "$zf" 1e-9
check "body 1 keeps its x ($cx)" near "$cx" "$cx0" 1e-12
read -r qw _ qy _ <<<"$(attr /Bodies/B0/quat "$S2" | tr '\n' ' ')"
ang=$(awk -v w="$qw" -v y="$qy" 'BEGIN {printf "%.12f", 2 * atan2(y, w)}')
check "body 1 turned by 3 rad/s * t ($ang rad)" near "$ang" "$(awk -v t="$t" 'BEGIN {printf "%.12f", 3 * t}')" 1e-9
# its particles: each one's offset from the centre is its first offset turned by the angle
paste <(values /Domains/D0/Id "$S0") <(values /Domains/D0/Mk "$S0") <(values /Domains/D0/Position "$S0" | paste - - -) \
    | awk '$2 == 1' | sort -n >"$T/p0"
paste <(values /Domains/D0/Id "$S2") <(values /Domains/D0/Mk "$S2") <(values /Domains/D0/Position "$S2" | paste - - -) \
    | awk '$2 == 1' | sort -n >"$T/p2"
check "body 1 has its 16 particles" [ "$(wc -l <"$T/p2")" -eq 16 ]
err=$(paste "$T/p0" "$T/p2" | awk -v a="$ang" -v cx0="$cx0" -v cz0="$cz0" -v cx="$cx" -v cz="$cz" '
    {rx = $3 - cx0; rz = $5 - cz0; c = cos(a); s = sin(a);
     ex = cx + c * rx + s * rz - $8; ez = cz - s * rx + c * rz - $10; e = sqrt(ex * ex + ez * ez); if (e > m) m = e}
    END {printf "%g", m}')
check "body 1's particles turned rigidly about its centre (largest error $err m)" near "$err" 0 1e-9
# FtPause (DualSPHysics' warm-up): held for the first 0.05 s, body 1 has not moved at 0.05 s
# (centre and orientation exactly its start), then falls from rest and turns at its initial
# 3 rad/s from the first step that starts at or after 0.05 s, so by 0.1 s it has dropped
# g (t - tp)^2 / 2 and turned 3 (t - tp) with tp within a step (1.5e-4 s here) of 0.05 s
"$BIN/vres-gencase" -q --set FtPause=0.05 "$T/fl_Def.xml" -o "$T/fp.h5" || notok "gencase with FtPause 0.05"
expect 0 "FtPause 0.05: run 0.1 s" "$BIN/vres-run" --threads 1 "$T/fp.h5" -o "$T/fp"
P1=$T/fp/snap_00001.h5 P2=$T/fp/snap_00002.h5
check "FtPause: body 1 where it started at t = $(attr /time "$P1") s" \
    [ "$(attr /Bodies/B0/center "$P1" | tr '\n' ' ')" = "$(attr /Bodies/B0/center "$T/fp/snap_00000.h5" | tr '\n' ' ')" -a \
      "$(attr /Bodies/B0/quat "$P1" | tr '\n' ' ')" = "1 0 0 0 " ]
t2=$(attr /time "$P2")
read -r _ _ pz <<<"$(attr /Bodies/B0/center "$P2" | tr '\n' ' ')"
read -r pw _ py _ <<<"$(attr /Bodies/B0/quat "$P2" | tr '\n' ' ')"
check "FtPause: then it falls from rest (drop $(awk -v a="$cz0" -v b="$pz" 'BEGIN {print a - b}') m, g (t - 0.05)^2/2 = $(awk -v t="$t2" 'BEGIN {print 9.81 * (t - 0.05)^2 / 2}') m)" \
    awk -v d="$(awk -v a="$cz0" -v b="$pz" 'BEGIN {print a - b}')" -v t="$t2" \
    'BEGIN {lo = 9.81 * (t - 0.05 - 1.5e-4)^2 / 2; hi = 9.81 * (t - 0.05)^2 / 2; exit !(d >= lo - 1e-9 && d <= hi + 1e-9)}'
check "FtPause: and turns at 3 rad/s ($(awk -v w="$pw" -v y="$py" 'BEGIN {print 2 * atan2(y, w)}') rad)" \
    awk -v a="$(awk -v w="$pw" -v y="$py" 'BEGIN {print 2 * atan2(y, w)}')" -v t="$t2" \
    'BEGIN {lo = 3 * (t - 0.05 - 1.5e-4); hi = 3 * (t - 0.05); exit !(a >= lo - 1e-9 && a <= hi + 1e-9)}'
check "body 2 (every freedom fixed) has not moved" [ "$(attr /Bodies/B1/center "$S2")" = "$(attr /Bodies/B1/center "$S0")" ]
fz=$(attr /Bodies/B1/force "$S2" | sed -n 3p)
check "body 2 is pushed up by the water (force z $fz N/m > 0)" awk -v f="$fz" 'BEGIN {exit !(f > 0)}'
check "body 3 (x free only) stays at its height" [ "$(attr /Bodies/B2/center "$S2" | sed -n 3p)" = "$(attr /Bodies/B2/center "$S0" | sed -n 3p)" ]
# Verlet (StepAlgorithm=1): DualSPHysics' leapfrog starts with v^-1 = v^0, so its velocities
# lead the exact fall by up to g dt (dt about 1.5e-4 s): after t the centre is within g dt t
sed 's/<parameter key="StepAlgorithm" value="2" \/>/<parameter key="StepAlgorithm" value="1" \/>/' "$T/fl_Def.xml" >"$T/flv.xml"
"$BIN/vres-gencase" -q "$T/flv.xml" -o "$T/flv.h5" || notok "gencase for Verlet"
expect 0 "Verlet run 0.1 s" "$BIN/vres-run" --threads 1 "$T/flv.h5" -o "$T/v"
check "it runs Verlet" grep -q 'modules: .*floating-bodies.* verlet' "$ERR"
czv=$(attr /Bodies/B0/center "$T/v/snap_00002.h5" | sed -n 3p)
tv=$(attr /time "$T/v/snap_00002.h5")
zv=$(awk -v z="$cz0" -v t="$tv" 'BEGIN {printf "%.12f", z - 9.81 * t * t / 2}')
check "Verlet: body 1's centre z $czv within g dt t = 1.5e-4 m of z0 - g t^2/2 = $zv" near "$czv" "$zv" 1.5e-4

# 3D: a 0.1 x 0.06 x 0.04 m block (unequal principal moments) in the air above a small tank,
# released spinning at (1, 2, 3) rad/s, off its principal axes: w precesses, but with no torque
# its angular momentum L = R I0 R^T w is conserved (to the scheme's O(dt^2) per step: 1e-3 over
# 0.1 s, where leaving out the gyroscopic term w x I w would change L at the rate of |w x I w|,
# several percent over 0.1 s), and its centre falls freely
{ consts; cat <<'XML'
        <geometry>
            <definition dp="0.02">
                <pointref x="0.01" y="0.01" z="0.01" />
                <pointmin x="-0.1" y="-0.1" z="-0.1" /> <pointmax x="0.4" y="0.4" z="0.5" />
            </definition>
            <commands>
                <mainlist>
                    <setdrawmode mode="solid" />
                    <setmkfluid mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="0" /> <size x="0.3" y="0.3" z="0.1" /> </drawbox>
                    <setmkbound mk="0" />
                    <drawbox> <boxfill>bottom | left | right | front | back</boxfill> <layers vdp="0.5,1.5" />
                        <point x="0" y="0" z="0" /> <size x="0.3" y="0.3" z="0.4" /> </drawbox>
                    <setmkbound mk="1" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.1" y="0.12" z="0.28" /> <size x="0.1" y="0.06" z="0.04" /> </drawbox>
                </mainlist>
            </commands>
        </geometry>
        <floatings>
            <floating mkbound="1" rhopbody="700"> <angularvelini x="1" y="2" z="3" /> </floating>
        </floatings>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Visco" value="0.01" />
            <parameter key="TimeMax" value="0.1" /> <parameter key="TimeOut" value="0.1" />
        </parameters>
    </execution>
</case>
XML
} >"$T/fl3_Def.xml"
"$BIN/vres-gencase" -q "$T/fl3_Def.xml" -o "$T/fl3.h5" || notok "gencase the 3D block"
expect 0 "3D run 0.1 s" "$BIN/vres-run" -q --threads 1 "$T/fl3.h5" -o "$T/r3"
# L = R I0 R^T w from a snapshot's /Bodies (quat, inertia, omega)
angmom() {
    cat <(attr /Bodies/B0/quat "$1") <(attr /Bodies/B0/inertia "$1") <(attr /Bodies/B0/omega "$1") | paste -s -d ' ' |
        awk 'NF == 16 {
        w = $1; x = $2; y = $3; z = $4; for (i = 0; i < 9; i++) I[i] = $(5 + i); for (i = 0; i < 3; i++) o[i] = $(14 + i)
        R[0] = 1 - 2 * (y * y + z * z); R[1] = 2 * (x * y - z * w); R[2] = 2 * (x * z + y * w)
        R[3] = 2 * (x * y + z * w); R[4] = 1 - 2 * (x * x + z * z); R[5] = 2 * (y * z - x * w)
        R[6] = 2 * (x * z - y * w); R[7] = 2 * (y * z + x * w); R[8] = 1 - 2 * (x * x + y * y)
        for (i = 0; i < 3; i++) { b[i] = 0; for (j = 0; j < 3; j++) b[i] += R[3 * j + i] * o[j] }   # R^T w
        for (i = 0; i < 3; i++) { c[i] = 0; for (j = 0; j < 3; j++) c[i] += I[3 * i + j] * b[j] }  # I0 R^T w
        for (i = 0; i < 3; i++) { L = 0; for (j = 0; j < 3; j++) L += R[3 * i + j] * c[j]; printf "%.12g ", L }
        printf "%.12g %.12g %.12g\n", o[0], o[1], o[2] }'
}
read -r l0x l0y l0z w0x w0y w0z <<<"$(angmom "$T/r3/snap_00000.h5")"
read -r l1x l1y l1z w1x w1y w1z <<<"$(angmom "$T/r3/snap_00001.h5")"
dl=$(awk -v a="$l0x" -v b="$l0y" -v c="$l0z" -v d="$l1x" -v e="$l1y" -v f="$l1z" \
    'BEGIN {printf "%.3g", sqrt((a - d) ^ 2 + (b - e) ^ 2 + (c - f) ^ 2) / sqrt(a * a + b * b + c * c)}')
dw=$(awk -v a="$w0x" -v b="$w0y" -v c="$w0z" -v d="$w1x" -v e="$w1y" -v f="$w1z" \
    'BEGIN {printf "%.3g", sqrt((a - d) ^ 2 + (b - e) ^ 2 + (c - f) ^ 2) / sqrt(a * a + b * b + c * c)}')
check "3D: the angular velocity precesses (relative change $dw > 1e-2)" awk -v d="$dw" 'BEGIN {exit !(d ~ /^[0-9.e+-]+$/ && d > 1e-2)}'
check "3D: the angular momentum is conserved (relative change $dl < 1e-3)" awk -v d="$dl" 'BEGIN {exit !(d ~ /^[0-9.e+-]+$/ && d < 1e-3)}'
t3=$(attr /time "$T/r3/snap_00001.h5")
cz3=$(attr /Bodies/B0/center "$T/r3/snap_00001.h5" | sed -n 3p)
c30=$(attr /Bodies/B0/center "$T/r3/snap_00000.h5" | sed -n 3p)
check "3D: the centre falls freely ($cz3)" near "$cz3" "$(awk -v z="$c30" -v t="$t3" 'BEGIN {printf "%.12f", z - 9.81 * t * t / 2}')" 1e-9

# restart bit for bit: the floating box, turning
sed 's|<rotationDOF x="0" y="0" z="0"|<angularvelini x="0" y="1" z="0" /> <rotationDOF x="0" y="1" z="0"|' \
    "$CASES/floating_box2d/floating_box2d_Def.xml" >"$T/box.xml"
grep -q angularvelini "$T/box.xml" || notok "the box is given its spin"
"$BIN/vres-gencase" -q --dp 0.04 "$T/box.xml" -o "$T/box.h5" || notok "gencase the floating box"
expect 0 "uninterrupted run of the turning box to 0.1 s" "$BIN/vres-run" -q --threads 1 --tmax 0.1 --tout 0.01 "$T/box.h5" -o "$T/a"
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00004.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/b/snap_00004.h5"
for k in 00005 00010; do
    for ds in Position Velocity Density; do
        check "snap $k $ds equal to the uninterrupted run's" \
            h5diff -q "$T/a/snap_$k.h5" "$T/b/snap_$k.h5" /Domains/D0/$ds /Domains/D0/$ds
    done
    for at in center quat vel omega force torque; do
        check "snap $k body $at equal to the uninterrupted run's" \
            [ "$(attr /Bodies/B0/$at "$T/a/snap_$k.h5")" = "$(attr /Bodies/B0/$at "$T/b/snap_$k.h5")" ]
    done
done
check "the box has turned (quat y $(attr /Bodies/B0/quat "$T/a/snap_00010.h5" | sed -n 3p))" \
    awk -v y="$(attr /Bodies/B0/quat "$T/a/snap_00010.h5" | sed -n 3p)" 'BEGIN {exit !(y > 0.01)}'

# vres-forces reports the body's motion beside the force: the /Bodies values of each snapshot
expect 0 "vres-forces on the floating box" "$BIN/vres-forces" --mk 1 "$T/a" -o "$T/f.tsv"
check "motion columns in its header" grep -q -P '^# time_s\tfx_N.*\tmz_Nm\tcx_m\tcy_m\tcz_m\tvx_m_s\tvy_m_s\tvz_m_s\tangle_rad$' "$T/f.tsv"
read -r fcz fang < <(awk -F'\t' '!/^#/ {z = $10; a = $14} END {print z, a}' "$T/f.tsv")
check "its last cz ($fcz) is /Bodies' centre z" near "$fcz" "$(attr /Bodies/B0/center "$T/a/snap_00010.h5" | sed -n 3p)" 1e-7
check "its last angle ($fang rad) is 2 atan2(q_y, q_w)" near "$fang" "$(attr /Bodies/B0/quat "$T/a/snap_00010.h5" |
    paste -s -d ' ' | awk '{printf "%.12f", 2 * atan2($3, $1)}')" 1e-7
"$BIN/vres-forces" --mk 0 "$T/a" -o "$T/f0.tsv" 2>/dev/null
check "a fixed wall has no motion columns" sh -c "grep '^# time_s' '$T/f0.tsv' | grep -qv cz_m"

# (mDBC walls with floating bodies: tests/vres-run/test_mdbc_floating.sh)
for kv in "RigidAlgorithm=0:RigidAlgorithm=0 \(floating bodies without SPH contact\) is not implemented yet"; do
    "$BIN/vres-gencase" -q --dp 0.04 --set "${kv%%:*}" "$T/box.xml" -o "$T/k.h5" || notok "gencase with ${kv%%:*}"
    expect_err 1 "${kv#*:}" "${kv%%:*} with a floating body refused" "$ASAN/vres-run" "$T/k.h5" -o "$T/k"
    nothing_in "$T/k" "nothing written"
done

# a scene without floating bodies runs without their module (and the interaction without their terms)
"$BIN/vres-gencase" -q --dp 0.05 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/h.h5" || notok "gencase the tank"
expect 0 "a tank without bodies runs" "$BIN/vres-run" --threads 1 --tmax 0.001 "$T/h.h5" -o "$T/h"
check "its modules leave floating bodies out" sh -c "grep -q 'modules: .*dbc-walls' '$ERR' && ! grep -q floating '$ERR'"
