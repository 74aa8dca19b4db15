#!/usr/bin/env bash
# vres-probe --gauges: the DualSPHysics <gauges> a case keeps in its store. The fixture is the
# 2D dam break (cases/dsph_dambreak2d, dp 0.02 m, still column 1 m wide, top particle row at
# z = 2 m) with gauges added to its <execution><special>; expectations as in test_probe.sh:
# the free surface half a spacing above the top row (2.01 m, within dp/10), the highest
# particle at 2 m exactly, hydrostatic pressure within rho0 g dp/2, still water.
source "$(dirname "$0")/../harness.sh"
PROBE=$BIN/vres-probe

gauges='<special><gauges>
  <default><computetime start="0" end="10"/><output value="true"/></default>
  <velocity name="Vel"><point x="0.5" y="0" z="1.0"/></velocity>
  <_velocity name="Off"><point x="0.5" y="0" z="1.0"/></_velocity>
  <velocity name="Later"><computetime start="1"/><point x="0.5" y="0" z="1.0"/></velocity>
  <swl name="Swl"><masslimit coef="0.5"/><pointdp coefdp="0.25"/>
    <point0 x="0.5" y="0" z="0.5"/><point2 x="0.5" y="0" z="3"/></swl>
  <swl name="SwlDefault"><pointdp value="0.005"/>
    <point0 x="0.5" y="0" z="0.5"/><point2 x="0.5" y="0" z="3"/></swl>
  <maxz name="MaxZ"><point0 x="0.5" y="0" z="0"/><height value="3"/><distlimit coefdp="1"/></maxz>
  <mesh name="Grid"><point x="0.3" y="0" z="0.5"/>
    <vec1 x="1" y="0" z="0"/><size1 length="0.4" distpt="0.2"/>
    <vec3 x="0" y="0" z="1"/><size3 length="2.0" distpt="0.005"/>
    <outputdata value="vel,rhop,zsurf"/><masslimit coef="0.5"/></mesh>
</gauges></special>'
sed "s|<parameters>|$(printf '%s' "$gauges" | tr '\n' ' ')<parameters>|" \
    "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" >"$T/gauged_Def.xml"
mkdir "$T/run"
if ! "$BIN/vres-gencase" -q "$T/gauged_Def.xml" --dp 0.02 -o "$T/run/snap_00000.h5"; then
    notok "vres-gencase makes the fixture"
    exit 1
fi
F=$T/run/snap_00000.h5
param() { h5dump -a "/Parameters/$1" "$F" | awk -F': ' '/\(0\)/ {print $2}'; }
rho0=$(param rhop0) g=$(param gravity | awk -F', ' '{print -$3}') dp=$(param dp)

expect 0 "--gauges exits 0" "$PROBE" --gauges "$T/run"
cp "$OUT" "$T/g.tsv"
check "header" [ "$(head -1 "$T/g.tsv")" = "$(printf '# time_s\tgauge\tkind\tpoint\tx_m\ty_m\tz_m\tvx_m_s\tvy_m_s\tvz_m_s\tp_Pa\trho_kg_m3')" ]
check "skipped and out-of-time gauges give no row" [ "$(grep -c -E '	(Off|Later)	' "$T/g.tsv")" -eq 0 ]
row() { awk -F'\t' -v n="$1" -v k="$2" '$2 == n && $4 == k' "$T/g.tsv"; }
vel=$(row Vel 0)
check "velocity gauge: still water ($vel)" [ "$(cut -f8-10 <<<"$vel")" = "$(printf '0\t0\t0')" ]
pv=$(cut -f11 <<<"$vel")
check "velocity gauge: hydrostatic pressure at 1 m depth ($pv)" \
    awk -v p="$pv" -v r="$rho0" -v g="$g" -v dp="$dp" 'BEGIN {d = p - r * g; exit !(d < r * g * dp / 2 && d > -r * g * dp / 2)}'
zs=$(row Swl 0 | cut -f7)
check "swl at 2 + dp/2 within dp/10 ($zs)" awk -v z="$zs" -v dp="$dp" 'BEGIN {d = z - 2 - dp / 2; exit !(d < dp / 10 && d > -dp / 10)}'
z4=$(row SwlDefault 0 | cut -f7)
check "swl with DualSPHysics' 2D default mass limit (0.4) lies higher ($z4)" awk -v a="$z4" -v b="$zs" 'BEGIN {exit !(a > b)}'
check "swl values are nan" [ "$(row Swl 0 | cut -f8-12 | tr -d '\t')" = nannannannannan ]
check "maxz: the top particle at 2 m" [ "$(row MaxZ 0 | cut -f5,7)" = "$(printf '0.5\t2')" ]
check "mesh: 3 x 401 grid points" [ "$(awk -F'\t' '$3 == "mesh"' "$T/g.tsv" | wc -l)" -eq 1203 ]
check "mesh: point 4 = i + 3 k is (0.5, 0, 0.505)" [ "$(awk -F'\t' '$3 == "mesh" && $4 == 4 {print $5, $7}' "$T/g.tsv")" = "0.5 0.505" ]
check "mesh: nan above the water, values below" \
    awk -F'\t' '$3 == "mesh" {if ($7 < 2 && $11 == "nan") exit 1; if ($7 > 2.1 && $11 != "nan") exit 1}' "$T/g.tsv"
check "zsurf: 3 columns, each at 2 + dp/2 within dp/10" \
    awk -F'\t' -v dp="$dp" '$3 == "zsurf" {n++; d = $7 - 2 - dp / 2; if (d > dp / 10 || d < -dp / 10) exit 1} END {exit n != 3}' "$T/g.tsv"

# The project's Lobovsky dam break: a mesh of 78 points on the downstream wall and a maxz gauge.
expect 0 "cases/dambreak2d gauges" "$PROBE" --gauges <("$BIN/vres-gencase" -q "$CASES/dambreak2d/dambreak2d_Def.xml" -o -)
check "WallPressure: 78 points 3 to 80 mm" \
    awk -F'\t' '$2 == "WallPressure" {n++; if ($4 == 77 && ($7 - 0.08)^2 > 1e-18) exit 1} END {exit n != 78}' "$OUT"
check "RunUp: one row" [ "$(awk -F'\t' '$2 == "RunUp"' "$OUT" | wc -l)" -eq 1 ]
