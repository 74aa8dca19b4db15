#!/usr/bin/env bash
# vres-run with particle shifting (Shifting=3, ShiftCoef=-2): a layer of water 0.2 m deep over a
# DBC bottom, periodic along x (0.4 m), driven along x by gravity (0.5, 0, -9.81) m/s^2 for 0.4 s,
# so that it flows (about 0.2 m/s) and shifting acts (dr = A h |v| dt grad C). Reference: a
# free surface stays where it is (the layer keeps its depth: mass and volume are conserved and
# nothing lifts it). With the free-surface treatment (ShiftTFS=1.5: no shifting where div r <
# 1.5) every particle of the top row must keep its height to 0.25 dp (measured: within 0.005 dp,
# 2026-11); without it (ShiftTFS=0) grad C, which points into the water at the surface, pushes
# the top row up, and the same check must fail there (measured: 1.3 dp), so the test tells the
# two apart. The layer stays stable: exit 0, mass kept.
source "$(dirname "$0")/../harness.sh"
DP=0.02
cat >"$T/layer_Def.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<case>
    <casedef>
        <constantsdef>
            <gravity x="0.5" y="0" z="-9.81" /> <rhop0 value="1000" /> <gamma value="7" />
            <hswl value="0.2" auto="false" /> <speedsystem value="0" auto="true" />
            <coefsound value="20" /> <speedsound value="0" auto="true" />
            <coefh value="1.0" /> <cflnumber value="0.2" />
        </constantsdef>
        <mkconfig boundcount="240" fluidcount="9" />
        <geometry>
            <definition dp="0.02">
                <pointref x="0.01" y="0" z="0.01" />
                <pointmin x="-0.1" y="0" z="-0.1" /> <pointmax x="0.5" y="0" z="0.4" />
            </definition>
            <commands>
                <mainlist>
                    <setdrawmode mode="solid" />
                    <setmkfluid mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="0" /> <size x="0.4" y="0" z="0.2" /> </drawbox>
                    <setmkbound mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="-0.06" /> <size x="0.4" y="0" z="0.06" /> </drawbox>
                </mainlist>
            </commands>
        </geometry>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Visco" value="0.01" />
            <parameter key="DensityDT" value="2" /> <parameter key="XPeriodicIncZ" value="0" />
            <parameter key="Shifting" value="3" /> <parameter key="ShiftCoef" value="-2" />
            <parameter key="TimeMax" value="0.4" /> <parameter key="TimeOut" value="0.4" />
            <parameter key="RhopOutMin" value="700" /> <parameter key="RhopOutMax" value="1300" />
            <simulationdomain comment="x fixed to the period [0, 0.4) m; room above the surface">
                <posmin x="0" y="default" z="default" /> <posmax x="0.4" y="default" z="default + 50%" />
            </simulationdomain>
        </parameters>
    </execution>
</case>
XML
# rise RUN: the largest |z - z0| (m) of the particles of the top row (z0 = 0.19 m), the largest
# speed, and the counts of top-row and of all particles read (zero fails the checks below)
rise() {
    paste <(values /Domains/D0/Id "$T/l.h5") <(values /Domains/D0/Position "$T/l.h5" | paste - - -) | sort -n >"$T/p0"
    paste <(values /Domains/D0/Id "$1/snap_00001.h5") <(values /Domains/D0/Position "$1/snap_00001.h5" | paste - - -) \
          <(values /Domains/D0/Velocity "$1/snap_00001.h5" | paste - - -) | sort -n >"$T/p1"
    join "$T/p0" "$T/p1" | awk '$4 > 0.185 {ntop++; d = $7 - $4; d = d < 0 ? -d : d; if (d > e) e = d}
                                {n++; s = sqrt($8 * $8 + $10 * $10); if (s > v) v = s} END {print e + 0, v + 0, ntop + 0, n + 0}'
}
for tfs in 1.5 0; do
    expect 0 "gencase the flowing layer (ShiftTFS=$tfs)" "$BIN/vres-gencase" --set ShiftTFS=$tfs "$T/layer_Def.xml" -o "$T/l.h5"
    expect 0 "run 0.4 s with shifting (ShiftTFS=$tfs)" "$BIN/vres-run" "$T/l.h5" -o "$T/run$tfs"
    check "modules name shifting (ShiftTFS=$tfs)" grep -q "shifting(full, coef=-2, tfs=$tfs)" "$ERR"
    check "fluid mass kept on 2 rows (ShiftTFS=$tfs)" \
        awk -F'\t' '!/^#/ {if (!n++) m = $6; else if ($6 != m) bad = 1} END {exit bad || n != 2}' "$T/run$tfs/run.tsv"
    read r v ntop n < <(rise "$T/run$tfs")
    echo "# ShiftTFS=$tfs: top row moved up to $r m vertically; largest speed $v m/s ($ntop of $n particles in the top row)"
    # 0.4 m / dp = 20 particles per row; 10 rows of water and 3 of wall
    check "every particle was read (ShiftTFS=$tfs: $ntop in the top row, $n in all)" [ "$ntop" -eq 20 -a "$n" -eq 260 ]
    if [ "$tfs" = 0 ]; then
        check "without surface treatment the top row lifts ($r m > 0.25 dp)" awk -v r="$r" -v dp=$DP 'BEGIN {exit !(r > 0.25 * dp)}'
    else
        check "the layer flows (largest speed $v m/s > 0.1)" awk -v v="$v" 'BEGIN {exit !(v > 0.1)}'
        check "top row keeps its height to 0.25 dp ($r m)" awk -v r="$r" -v dp=$DP 'BEGIN {exit !(r < 0.25 * dp)}'
    fi
done
