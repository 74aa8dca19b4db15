#!/usr/bin/env bash
# vres-run with moving walls: a 2-D tank of still water with two bodies above it, a plate
# (mkbound 1) moving at 0.1 m/s along x for 0.2 s and then waiting, and a bar (mkbound 2)
# turning at 90 degrees/s about the y axis through its centre (0.2, 0.2) m, for ever. After
# 0.25 s the plate must be 0.02 m along x from where it started and at rest, and the bar's
# particles at their old distances from the axis, turned by pi/2 * 0.25 rad, moving at
# omega r. Reference: those closed forms (DualSPHysics' <mvrect>, <wait>, <mvrot>). Positions
# are double precision and set from the motion's closed form each half step, so they must
# match to 1e-9 m; velocities are stored in single precision (1e-6 relative).
source "$(dirname "$0")/../harness.sh"
cat >"$T/mv_Def.xml" <<'XML'
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
        <geometry>
            <definition dp="0.01">
                <pointref x="0.005" y="0" z="0.005" />
                <pointmin x="-0.1" y="0" z="-0.1" /> <pointmax x="0.5" y="0" z="0.5" />
            </definition>
            <commands>
                <mainlist>
                    <setdrawmode mode="solid" />
                    <setmkfluid mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="0" /> <size x="0.3" y="0" z="0.1" /> </drawbox>
                    <setmkbound mk="0" />
                    <setnormalinvert invert="true" />
                    <drawbox> <boxfill>bottom | left | right</boxfill> <layers vdp="0.5,1.5,2.5" />
                        <point x="0" y="0" z="0" /> <size x="0.3" y="0" z="0.3" /> </drawbox>
                    <setnormalinvert invert="false" />
                    <setmkbound mk="1" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.05" y="0" z="0.2" /> <size x="0.05" y="0" z="0.02" /> </drawbox>
                    <setmkbound mk="2" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0.17" y="0" z="0.19" /> <size x="0.06" y="0" z="0.02" /> </drawbox>
                </mainlist>
            </commands>
        </geometry>
        <motion>
            <objreal ref="1">
                <begin mov="1" start="0" />
                <mvrect id="1" duration="0.2" next="2"> <vel x="0.1" y="0" z="0" /> </mvrect>
                <wait id="2" duration="-1" />
            </objreal>
            <objreal ref="2">
                <begin mov="1" start="0" />
                <mvrot id="1" duration="-1"> <vel ang="90" /> <axisp1 x="0.2" y="-1" z="0.2" /> <axisp2 x="0.2" y="1" z="0.2" /> </mvrot>
            </objreal>
        </motion>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Visco" value="0.01" />
            <parameter key="DensityDT" value="2" />
            <parameter key="TimeMax" value="0.25" /> <parameter key="TimeOut" value="0.25" />
        </parameters>
    </execution>
</case>
XML
expect 0 "gencase the tank with moving bodies" "$BIN/vres-gencase" "$T/mv_Def.xml" -o "$T/mv.h5"
expect 0 "run 0.25 s" "$BIN/vres-run" "$T/mv.h5" -o "$T/run"
check "modules name the moving walls" grep -q 'moving-walls(' "$ERR"
t=$(awk 'END {print $1}' "$T/run/run.tsv")
table() { paste <(values /Domains/D0/Id "$1") <(values /Domains/D0/Mk "$1") <(values /Domains/D0/Type "$1") \
                <(values /Domains/D0/Position "$1" | paste - - -) <(values /Domains/D0/Velocity "$1" | paste - - -) | sort -n; }
table "$T/mv.h5" >"$T/a"
table "$T/run/snap_00001.h5" >"$T/b"
# joined: id mk type x y z vx vy vz | mk type x y z vx vy vz
res=$(join "$T/a" "$T/b" | awk -v t="$t" '
    $3 == 3 && $2 == 1 { n1++; e = $12 - ($4 + 0.02); e = e < 0 ? -e : e; f = $14 - $6; f = f < 0 ? -f : f
                         if (e > p1) p1 = e; if (f > p1) p1 = f; if ($15 != 0 || $17 != 0) v1++ }
    $3 == 3 && $2 == 2 { n2++; th = 0.5 * atan2(0, -1) * t
                         x0 = $4 - 0.2; z0 = $6 - 0.2; x1 = $12 - 0.2; z1 = $14 - 0.2
                         ex = x0 * cos(th) + z0 * sin(th); ez = -x0 * sin(th) + z0 * cos(th)
                         e = sqrt((x1 - ex)^2 + (z1 - ez)^2); if (e > p2) p2 = e
                         r = sqrt(x1 * x1 + z1 * z1); sp = sqrt($15 * $15 + $17 * $17); w = 0.5 * atan2(0, -1)
                         dv = sp - w * r; dv = dv < 0 ? -dv : dv; if (dv > v2) v2 = dv }
    END { printf "%d %d %.3g %d %.3g %.3g", n1, n2, p1, v1, p2, v2 }')
set -- $res
echo "# t = $t s: plate $1 particles, position error $3 m, $4 moving; bar $2 particles, position error $5 m, speed error $6 m/s"
check "the plate and the bar have particles ($1, $2)" [ "$1" -gt 0 ] && [ "$2" -gt 0 ]
check "plate 0.02 m along x (error $3 m)" awk -v e="$3" 'BEGIN {exit !(e < 1e-9)}'
check "plate at rest after its 0.2 s ($4 particles moving)" [ "$4" -eq 0 ]
check "bar turned by omega t about its axis (error $5 m)" awk -v e="$5" 'BEGIN {exit !(e < 1e-9)}'
check "bar particles move at omega r (error $6 m/s)" awk -v e="$6" 'BEGIN {exit !(e < 1e-6)}'
check "fluid mass kept" awk -F'\t' 'NR == 2 {m = $6} !/^#/ && $6 != m {exit 1}' "$T/run/run.tsv"

# A restart from a snapshot places the moving walls bit for bit as the uninterrupted run: the
# time loop anchors them (their positions as the reference, the motion counted from then) at
# every snapshot, so both runs take them from the same numbers. Outputs every 0.05 s; restart
# from snap_00002.h5 (t = 0.1 s: the plate still moving, the bar turning), compared at 0.25 s.
expect 0 "run 0.25 s with outputs every 0.05 s" "$BIN/vres-run" -q --threads 1 --tout 0.05 "$T/mv.h5" -o "$T/r5"
cp -r "$T/r5" "$T/r5b"
expect 0 "restart from snap_00002.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/r5b/snap_00002.h5"
bad=
for ds in Position Velocity Density Type Id; do
    h5diff -q "$T/r5/snap_00005.h5" "$T/r5b/snap_00005.h5" "/Domains/D0/$ds" "/Domains/D0/$ds" >/dev/null || bad="$bad $ds"
done
check "snap_00005.h5 after the restart equals the uninterrupted run's bit for bit${bad:+ (differs in$bad)}" \
    [ -z "$bad" -a -f "$T/r5b/snap_00005.h5" ]
