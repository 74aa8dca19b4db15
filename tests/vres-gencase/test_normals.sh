#!/usr/bin/env bash
# mDBC normals the way DualSPHysics users write them (cases/dsph_dambreak2d_mdbc): the boundary
# surface drawn as shapes only in a list (setactive drawpoints="0" drawshapes="1", shapeout,
# resetdraw) and named by <normals><norgeometry>. The counts and normals follow by hand from the
# lattice (see the case's header): 20000 fluid, 3021 walls, 3015 of them within distanceh 2h of
# the surface, which lies half a dp inside the tank faces (x = 0.005, x = 3.995, z = 0.005).
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/dsph_dambreak2d_mdbc/dambreak2d_mdbc_Def.xml

expect 0 "the mDBC dam break generates" "$BIN/vres-gencase" "$CASE" -o "$T/m.h5"
check "a note says how many walls got a normal" grep -q "3015 of 3021 wall particles take their normal" "$ERR"
values /Domains/D0/Type "$T/m.h5" >"$T/type"
check "20000 fluid particles (the shapes-only list draws none)" [ "$(grep -cx 0 "$T/type")" -eq 20000 ]
check "3021 wall particles (three layers outside each face)" [ "$(grep -cx 2 "$T/type")" -eq 3021 ]
values /Domains/D0/Position "$T/m.h5" | paste - - - >"$T/pos"
values /Domains/D0/Normal "$T/m.h5" | paste - - - >"$T/nor"
paste "$T/type" "$T/pos" "$T/nor" >"$T/all"

# normal NX NZ X Z: the wall particle at (X, Z) has the normal (NX, 0, NZ) to 1e-6 m
normal() {
    awk -v x="$3" -v z="$4" -v nx="$1" -v nz="$2" '
        $1 == 2 && ($2 - x)^2 + ($4 - z)^2 < 1e-12 { n++; d = ($5 - nx)^2 + $6^2 + ($7 - nz)^2 }
        END { exit !(n == 1 && d < 1e-12) }' "$T/all"
}
check "walls with a normal: 3015" [ "$(awk '$1 == 2 && $5 * $5 + $7 * $7 > 0' "$T/all" | wc -l)" -eq 3015 ]
check "fluid has no normal" [ "$(awk '$1 == 0 && ($5 != 0 || $6 != 0 || $7 != 0)' "$T/all" | wc -l)" -eq 0 ]
check "left wall face (0, 1): (0.005, 0)" normal 0.005 0 0 1
check "left wall third layer (-0.02, 1): (0.025, 0)" normal 0.025 0 -0.02 1
check "right wall (4.01, 2): (-0.015, 0)" normal -0.015 0 4.01 2
check "floor third layer (2, -0.02): (0, 0.025)" normal 0 0.025 2 -0.02
check "corner (-0.01, -0.01): diagonal (0.015, 0.015)" normal 0.015 0.015 -0.01 -0.01
check "corner (-0.02, 0): (0.025, 0.005), 0.0255 m <= 2h" normal 0.025 0.005 -0.02 0
check "corner (-0.02, -0.01) lies 0.029 m > 2h away: no normal" normal 0 0 -0.02 -0.01
check "above the surface's open top (-0.02, 3.02): (0.025, 0)" normal 0.025 0 -0.02 3.02

# without <normals> the same walls take their normals from the drawn tank, which is drawn
# without setnormalinvert: they point out of the tank, as the case asked
sed -e '/<normals active/,/<\/normals>/d' "$CASE" >"$T/nonormals.xml"
expect 0 "without <normals> it generates" "$BIN/vres-gencase" "$T/nonormals.xml" -o "$T/n.h5"
check "a note says the shapes-only drawing is unused" grep -q "drawpoints=\"0\" is not used: the case has no <normals>" "$ERR"

# bad input: one message naming the element and its line
sed -e 's|\[CaseName\]_hdp_Actual.vtk|walls.stl|' "$CASE" >"$T/ext.xml"
line=$(grep -n "walls.stl" "$T/ext.xml" | cut -d: -f1)
expect_err 1 "ext.xml:$line: .*external geometry files are not supported" "an external geometry file is refused" \
    "$ASAN/vres-gencase" "$T/ext.xml" -o "$T/x.h5"
check "nothing written" [ ! -e "$T/x.h5" ]
sed -e 's|<norgeometry>|<norsphere mkbound="0"><radius v="0.1"/></norsphere><norgeometry>|' "$CASE" >"$T/sphere.xml"
line=$(grep -n "<norsphere" "$T/sphere.xml" | cut -d: -f1)
expect_err 1 "sphere.xml:$line: element <norsphere> of <normals> is not supported" "norsphere is refused by name" \
    "$ASAN/vres-gencase" "$T/sphere.xml" -o "$T/x.h5"
check "norsphere: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
# <norplane> is read (tests/vres-gencase/test_inout.sh): one without its point is refused by name
sed -e 's|<norgeometry>|<norplane mkbound="0"><normal x="0" y="0" z="1"/></norplane><norgeometry>|' "$CASE" >"$T/plane.xml"
line=$(grep -n "<norplane" "$T/plane.xml" | cut -d: -f1)
expect_err 1 "plane.xml:$line: <norplane> needs <point x y z> or <point auto=\"true\">" "a norplane without its point is refused" \
    "$ASAN/vres-gencase" "$T/plane.xml" -o "$T/x.h5"
check "norplane: nothing written" [ ! -e "$T/x.h5" ]
sed -e 's|<setactive drawpoints="0" drawshapes="1" />|<setactive drawpoints="0" drawlines="1" />|' "$CASE" >"$T/attr.xml"
line=$(grep -n "drawlines" "$T/attr.xml" | cut -d: -f1)
expect_err 1 "attr.xml:$line: attribute 'drawlines' of <setactive> is not supported" "an unknown setactive attribute" \
    "$ASAN/vres-gencase" "$T/attr.xml" -o "$T/x.h5"
sed -e 's|<setshapemode>actual \| bound</setshapemode>|<setshapemode>actual \| walls</setshapemode>|' "$CASE" >"$T/mode.xml"
line=$(grep -n "actual | walls" "$T/mode.xml" | cut -d: -f1)
expect_err 1 "mode.xml:$line: <setshapemode>: unknown word 'walls'" "an unknown setshapemode word" \
    "$ASAN/vres-gencase" "$T/mode.xml" -o "$T/x.h5"
expect 0 "the ASan build reads the good case cleanly" "$ASAN/vres-gencase" -q "$CASE" -o "$T/a.h5"

# <lattice bound="2">: the walls' cell centres too, half a dp outside each of the three layers'
# sheets (1004 + 1010 + 1016 = 3030 by the counts above, each layer's sheet a centre further
# along its faces), measured against the same surface: their normals reach it as their
# neighbours' do (the left wall's centres at x -0.005 and -0.015: 0.01 and 0.02; the one at
# -0.025 lies beyond distanceh 2h = 0.028 m and gets none)
sed 's|<constantsdef>|<constantsdef><lattice bound="2" fluid="1" />|' "$CASE" >"$T/bcc.xml"
expect 0 "the mDBC dam break with body-centred walls generates" "$BIN/vres-gencase" "$T/bcc.xml" -o "$T/b.h5"
values /Domains/D0/Type "$T/b.h5" >"$T/type"
check "lattice 2: 20000 fluid" [ "$(grep -cx 0 "$T/type")" -eq 20000 ]
check "lattice 2: 3021 + 3030 walls" [ "$(grep -cx 2 "$T/type")" -eq 6051 ]
values /Domains/D0/Position "$T/b.h5" | paste - - - >"$T/pos"
values /Domains/D0/Normal "$T/b.h5" | paste - - - >"$T/nor"
paste "$T/type" "$T/pos" "$T/nor" >"$T/all"
check "lattice 2: left wall face (0, 1): (0.005, 0) as before" normal 0.005 0 0 1
check "lattice 2: centre (-0.005, 1.005): (0.01, 0)" normal 0.01 0 -0.005 1.005
check "lattice 2: centre (-0.015, 1.005): (0.02, 0)" normal 0.02 0 -0.015 1.005
check "lattice 2: centre (-0.025, 1.005): none, beyond 2h" normal 0 0 -0.025 1.005
check "lattice 2: floor centre (2.005, -0.015): (0, 0.02)" normal 0 0.02 2.005 -0.015
