#!/usr/bin/env bash
# vres-run with motions read from tables (DualSPHysics' <mvrectfile> and <mvrotfile>): the tank
# of test_moving.sh, its plate (mkbound 1) moved along x by the table plate.csv (a header line,
# then time;unused;x with x = 0.4 t^2 at t = 0, 0.05, ..., 0.3 s: an accelerating plate whose
# table is followed piecewise linearly) and its bar (mkbound 2) turned about the y axis through
# (0.2, 0.2) m by bar.dat (a comment, then time and angle in degrees: 0 0, 2 180, i.e. 90
# degrees/s, as test_moving.sh's <mvrot>). Reference: the tables themselves, interpolated
# linearly in time, and the closed form of the turn; positions to 1e-9 m, velocities (single
# precision in the store) to 1e-6. The store keeps the tables (/Bodies/B<i>/Table<id>): the run
# and a restart need no file. Bad tables are refused naming the file and its line.
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
                <mvrectfile id="1" duration="-1"> <file name="plate.csv" fields="3" fieldtime="0" fieldx="2" /> </mvrectfile>
            </objreal>
            <objreal ref="2">
                <begin mov="1" start="0" />
                <mvrotfile id="1" duration="-1" anglesunits="degrees"> <file name="bar.dat" /> <axisp1 x="0.2" y="-1" z="0.2" /> <axisp2 x="0.2" y="1" z="0.2" /> </mvrotfile>
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
printf 'time;unused;x\n' >"$T/plate.csv"
for i in 0 1 2 3 4 5 6; do awk -v i=$i 'BEGIN {t = 0.05 * i; printf "%.2f;7;%.6f\n", t, 0.4 * t * t}' >>"$T/plate.csv"; done
printf '# t (s) angle (degrees)\n0 0\n2 180\n' >"$T/bar.dat"
expect 0 "gencase the tank with bodies moved by tables" "$BIN/vres-gencase" "$T/mv_Def.xml" -o "$T/mv.h5"
check "the store keeps both tables (7 and 2 rows of 4)" \
    [ "$(h5dump -H -d /Bodies/B0/Table1 -d /Bodies/B1/Table1 "$T/mv.h5" | grep -c -e 'SIMPLE { ( 7, 4 )' -e 'SIMPLE { ( 2, 4 )')" -eq 2 ]
expect 0 "vres-info shows the table segments" "$BIN/vres-info" -v "$T/mv.h5"
check "vres-info: rectfile, 7 rows, t 0 to 0.3 s" grep -q 'segment 1: rectfile, forever, 7 rows, t 0 to 0.3 s' "$OUT"
check "vres-info: rotfile, 2 rows" grep -q 'segment 1: rotfile, forever, 2 rows, t 0 to 2 s' "$OUT"
mkdir -p "$T/elsewhere" && cp "$T/mv.h5" "$T/elsewhere/" && rm "$T/plate.csv" "$T/bar.dat"
expect 0 "run 0.25 s from the store alone (the table files removed)" "$BIN/vres-run" -q --threads 1 --tout 0.05 "$T/elsewhere/mv.h5" -o "$T/run"
t=$(awk 'END {print $1}' "$T/run/run.tsv")
table() { paste <(values /Domains/D0/Id "$1") <(values /Domains/D0/Mk "$1") <(values /Domains/D0/Type "$1") \
                <(values /Domains/D0/Position "$1" | paste - - -) <(values /Domains/D0/Velocity "$1" | paste - - -) | sort -n; }
table "$T/mv.h5" >"$T/a"
table "$T/run/snap_00005.h5" >"$T/b"
# the plate's table at t: the row interval [0.05 i, 0.05 (i + 1)] holding t, x linear in it
res=$(join "$T/a" "$T/b" | awk -v t="$t" '
    BEGIN { i = int(t / 0.05); t0 = 0.05 * i; t1 = t0 + 0.05; x0 = 0.4 * t0 * t0; x1 = 0.4 * t1 * t1
            u = (x1 - x0) / 0.05; dx = x0 + (t - t0) * u }
    $3 == 3 && $2 == 1 { n1++; e = $12 - ($4 + dx); e = e < 0 ? -e : e; f = $14 - $6; f = f < 0 ? -f : f
                         if (e > p1) p1 = e; if (f > p1) p1 = f; g = $15 - u; g = g < 0 ? -g : g; if (g > v1) v1 = g }
    $3 == 3 && $2 == 2 { n2++; th = 0.5 * atan2(0, -1) * t
                         x0 = $4 - 0.2; z0 = $6 - 0.2; x1 = $12 - 0.2; z1 = $14 - 0.2
                         ex = x0 * cos(th) + z0 * sin(th); ez = -x0 * sin(th) + z0 * cos(th)
                         e = sqrt((x1 - ex)^2 + (z1 - ez)^2); if (e > p2) p2 = e
                         r = sqrt(x1 * x1 + z1 * z1); sp = sqrt($15 * $15 + $17 * $17); w = 0.5 * atan2(0, -1)
                         dv = sp - w * r; dv = dv < 0 ? -dv : dv; if (dv > v2) v2 = dv }
    END { printf "%d %d %.3g %.3g %.3g %.3g %.6f", n1, n2, p1, v1, p2, v2, dx }')
set -- $res
echo "# t = $t s: plate $1 particles moved $7 m, position error $3 m, speed error $4 m/s; bar $2 particles, position error $5 m, speed error $6 m/s"
check "the plate and the bar have particles ($1, $2)" [ "$1" -gt 0 -a "$2" -gt 0 ]
check "plate where its table says at t = $t s ($7 m along x, error $3 m)" awk -v e="$3" 'BEGIN {exit !(e < 1e-9)}'
check "plate moving at its table's slope there (error $4 m/s)" awk -v e="$4" 'BEGIN {exit !(e < 1e-6)}'
check "bar turned by its table's angle about its axis (error $5 m)" awk -v e="$5" 'BEGIN {exit !(e < 1e-9)}'
check "bar particles move at omega r (error $6 m/s)" awk -v e="$6" 'BEGIN {exit !(e < 1e-6)}'
cp -r "$T/run" "$T/runb"
expect 0 "restart from snap_00002.h5 (no table file anywhere)" "$BIN/vres-run" -q --threads 1 --restart "$T/runb/snap_00002.h5"
bad=
for ds in Position Velocity Density Type Id; do
    h5diff -q "$T/run/snap_00005.h5" "$T/runb/snap_00005.h5" "/Domains/D0/$ds" "/Domains/D0/$ds" >/dev/null || bad="$bad $ds"
done
check "snap_00005.h5 after the restart equals the uninterrupted run's bit for bit${bad:+ (differs in$bad)}" \
    [ -z "$bad" -a -f "$T/runb/snap_00005.h5" ]

# mDBC (Boundary=2): the walls' normals turn with their bodies, so each ghost node stays across
# the moving face (DualSPHysics 5.4's VRes leaves them as drawn: ../shared/refdata); the plate
# only translates, so its normals stay as drawn; every normal keeps its length
printf 'time;unused;x\n' >"$T/plate.csv"
for i in 0 1 2 3 4 5 6; do awk -v i=$i 'BEGIN {t = 0.05 * i; printf "%.2f;7;%.6f\n", t, 0.4 * t * t}' >>"$T/plate.csv"; done
printf '# t (s) angle (degrees)\n0 0\n2 180\n' >"$T/bar.dat"
expect 0 "gencase the tank with mDBC" "$BIN/vres-gencase" --set Boundary=2 "$T/mv_Def.xml" -o "$T/mv2.h5"
rm "$T/plate.csv" "$T/bar.dat"
expect 0 "run it 0.25 s" "$BIN/vres-run" -q --threads 1 --tout 0.05 "$T/mv2.h5" -o "$T/runm"
ntable() { paste <(values /Domains/D0/Id "$1") <(values /Domains/D0/Mk "$1") <(values /Domains/D0/Type "$1") \
                 <(values /Domains/D0/Normal "$1" | paste - - -) | sort -n; }
ntable "$T/mv2.h5" >"$T/na"
ntable "$T/runm/snap_00005.h5" >"$T/nb"
t=$(awk 'END {print $1}' "$T/runm/run.tsv")
res=$(join "$T/na" "$T/nb" | awk -v t="$t" '
    $3 == 3 && ($4 != 0 || $6 != 0) { k = $2; n[k]++; th = k == 2 ? 0.5 * atan2(0, -1) * t : 0
        ex = $4 * cos(th) + $6 * sin(th); ez = -$4 * sin(th) + $6 * cos(th)
        e = sqrt(($9 - ex)^2 + ($11 - ez)^2) / sqrt($4 * $4 + $6 * $6); if (e > err[k]) err[k] = e
        if (k == 2 && ($9 != $4 || $11 != $6)) turned++ }
    END { printf "%d %d %.3g %.3g %d", n[1], n[2], err[1], err[2], turned }')
set -- $res
echo "# t = $t s: plate $1 normals, relative error $3; bar $2 normals, relative error $4 against R(t) n0, $5 turned"
check "the plate and the bar have mDBC normals ($1, $2)" [ "$1" -gt 0 -a "$2" -gt 0 ]
check "the bar's normals turned with it: $5 of $2 changed, within $4 of R(t) n0 (float precision)" \
    awk -v e="$4" -v a="$5" -v b="$2" 'BEGIN {exit !(e < 1e-6 && a == b)}'
check "the plate's normals as drawn (it translates; error $3)" awk -v e="$3" 'BEGIN {exit !(e == 0)}'
cp -r "$T/runm" "$T/runmb"
expect 0 "mDBC: restart from snap_00002.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/runmb/snap_00002.h5"
bad=
for ds in Position Velocity Density Normal; do
    h5diff -q "$T/runm/snap_00005.h5" "$T/runmb/snap_00005.h5" "/Domains/D0/$ds" "/Domains/D0/$ds" >/dev/null || bad="$bad $ds"
done
check "mDBC: snap_00005.h5 after the restart equals the uninterrupted run's, normals included${bad:+ (differs in$bad)}" \
    [ -z "$bad" -a -f "$T/runmb/snap_00005.h5" ]

# bad tables: one message naming the file (and its line), nothing written
printf '# t angle\n0 0\n2 180\n' >"$T/bar.dat"
line=$(grep -n '<mvrectfile' "$T/mv_Def.xml" | cut -d: -f1)
expect_err 1 "mv_Def.xml:$line: <file name=\"plate.csv\">: cannot open .*plate.csv: No such file" \
    "a missing table file is refused, naming it" "$ASAN/vres-gencase" "$T/mv_Def.xml" -o "$T/x.h5"
check "missing file: nothing written" [ ! -e "$T/x.h5" ]
printf 'time;unused;x\n0;0;0\n0.1;0;0.01\n0.1;0;0.02\n' >"$T/plate.csv"
expect_err 1 "plate.csv:4: time 0.1 is not after the row before's \(0.1\): times must increase" \
    "a table whose time does not increase is refused at its line" "$ASAN/vres-gencase" "$T/mv_Def.xml" -o "$T/x.h5"
printf 'time;unused;x\n0;0;0\n0.1;0;x1\n' >"$T/plate.csv"
expect_err 1 "plate.csv:3: column 2, 'x1', is not a number" "a word among the rows is refused at its line" \
    "$ASAN/vres-gencase" "$T/mv_Def.xml" -o "$T/x.h5"
printf 'time;unused;x\n0;0;0\n0.1;0\n' >"$T/plate.csv"
expect_err 1 "plate.csv:3: 2 columns where <file fields=\"3\"> asks for 3" "a short row is refused at its line" \
    "$ASAN/vres-gencase" "$T/mv_Def.xml" -o "$T/x.h5"
printf 'time;unused;x\n' >"$T/plate.csv"
expect_err 1 "<file name=\"plate.csv\">: no rows of numbers in" "a table without rows is refused" \
    "$ASAN/vres-gencase" "$T/mv_Def.xml" -o "$T/x.h5"
printf 'time;unused;x\n0;0;0\n' >"$T/plate.csv"
sed 's|fieldx="2" />|/>|' "$T/mv_Def.xml" >"$T/nocol.xml"
line=$(grep -n '<file name="plate.csv"' "$T/nocol.xml" | cut -d: -f1)
expect_err 1 "nocol.xml:$line: <file> names no column of positions \(fieldx, fieldy or fieldz\)" \
    "a rectilinear table without a position column is refused" "$ASAN/vres-gencase" "$T/nocol.xml" -o "$T/x.h5"
check "bad tables: nothing written" [ ! -e "$T/x.h5" ]
