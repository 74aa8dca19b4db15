#!/usr/bin/env bash
# vres-gencase and <inout> (inlet/outlet zones): a good zone is resolved into the parameters
# inout_Z<k>_* that vres-run reads (vres-store(5)); bad zones, under AddressSanitizer, give one
# clear message naming the file, the line of the element at fault (found in the test's own copy
# with grep -n) and the element, exit 1, nothing written.
source "$(dirname "$0")/../harness.sh"
GEN=$ASAN/vres-gencase
CASE=$CASES/channel_inout2d/channel_inout2d_Def.xml
mkdir "$T/out"

expect 0 "the channel's two zones resolve" "$GEN" -q "$CASE" -o "$T/case.h5"
info=$("$BIN/vres-info" "$T/case.h5")
# param NAME: the values of the store's parameter NAME as vres-info lists them
param() { echo "$info" | awk -v n="$1" '$1 == n {$1 = ""; sub(/^ /, ""); sub(/ +\(xml\)$/, ""); print}'; }
check "zones: 2" [ "$(param inout_zones)" = 2 ]
check "zone 1 face corner (0, 0, 0)" [ "$(param inout_Z1_point)" = "0 0 0" ]
check "zone 2 direction into the fluid (-1, 0, 0)" [ "$(param inout_Z2_direction)" = "-1 0 0" ]
check "zone 2 extent along its line 0.4 m" [ "$(param inout_Z2_extent)" = "0.4 0" ]
check "zone 2 options: 4 layers, inputtreatment 1, refilling 0, velocity and density extrapolated" \
    [ "$(param inout_Z2_options)" = "4 1 0 2 2" ]
line=$(grep -n 'outlet: velocity and density' "$CASE" | cut -d: -f1)
check "zone 2 keeps its line ($line)" [ "$(param inout_Z2_line)" = "$line" ]

# bad NAME PATTERN XMLFILE: exit 1, one message matching PATTERN, no store written.
bad() {
    local name=$1 pat=$2 xml=$3
    expect_err 1 "$pat" "$name" "$GEN" "$xml" -o "$T/out/case.h5"
    check "$name: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
}

# the inlet's <line> (the first one in the file) without its <direction>
awk '/<direction x="1" z="0" \/>/ && !done {done = 1; next} {print}' "$CASE" >"$T/nodir.xml"
line=$(grep -n '<line>' "$T/nodir.xml" | head -1 | cut -d: -f1)
bad "zone with no direction" "nodir\.xml:$line: <line> has no <direction>" "$T/nodir.xml"

sed 's|<direction x="1" z="0" />|<direction x="0" z="0" />|' "$CASE" >"$T/zerodir.xml"
line=$(grep -n '<direction x="0" z="0" />' "$T/zerodir.xml" | cut -d: -f1)
bad "zone with a zero direction" "zerodir\.xml:$line: <direction> of <line> is zero" "$T/zerodir.xml"

sed 's|<direction x="1" z="0" />|<direction x="1" z="1" />|' "$CASE" >"$T/oblique.xml"
line=$(grep -n '<direction x="1" z="1" />' "$T/oblique.xml" | cut -d: -f1)
bad "oblique zone" "oblique\.xml:$line: <direction> \(1, 0, 1\) is not normal to the zone's face" "$T/oblique.xml"

# the inlet's line reaching down into the bottom wall (rows 0.5, 1.5, 2.5 dp below z = 0)
sed 's|<point x="0" z="0" />|<point x="0" z="-0.06" />|' "$CASE" >"$T/wall.xml"
line=$(grep -n 'inlet: fixed velocity' "$T/wall.xml" | cut -d: -f1)
bad "zone crossing a wall" "wall\.xml:$line: inlet/outlet zone 1 crosses a wall: wall particle mk 0 at" "$T/wall.xml"

awk '/<layers value="4" \/>/ && !done {sub(/value="4"/, "value=\"40\""); done = 1} {print}' "$CASE" >"$T/outside.xml"
line=$(grep -n 'inlet: fixed velocity' "$T/outside.xml" | cut -d: -f1)
bad "zone reaching outside the domain" "outside\.xml:$line: inlet/outlet zone 1 \(40 layers of 0.04 m behind its face\) reaches x = -1.6 m, outside the simulation domain" "$T/outside.xml"

sed 's|<refilling value="0" />|<refilling value="0" /><zsurfmax value="1" />|' "$CASE" >"$T/unknown.xml"
line=$(grep -n '<zsurfmax' "$T/unknown.xml" | head -1 | cut -d: -f1)
expect_err 1 "unknown\.xml:$line: element <zsurfmax> is not supported in <inoutzone>" "unknown zone option" \
    "$GEN" "$T/unknown.xml" -o "$T/out/case.h5"
nothing_in "$T/out" "unknown zone option: nothing written"

sed 's|<refilling value="0" />|<refilling value="1" />|' "$CASE" >"$T/refill.xml"
line=$(grep -n '<refilling value="1" />' "$T/refill.xml" | head -1 | cut -d: -f1)
expect_err 1 "refill\.xml:$line: <refilling value=\"1\"> \(below zsurf\) is not implemented yet" "refilling 1 refused by name" \
    "$GEN" "$T/refill.xml" -o "$T/out/case.h5"
nothing_in "$T/out" "refilling 1: nothing written"

sed 's|<imposevelocity mode="2" />|<imposevelocity mode="1"><velocitytimes><timevalue time="0" v="0" /><timevalue time="1" v="-1" /></velocitytimes></imposevelocity>|' "$CASE" >"$T/vtime.xml"
expect 0 "a velocity time series (<velocitytimes>) resolves" "$GEN" -q "$T/vtime.xml" -o "$T/vtime.h5"
info=$("$BIN/vres-info" "$T/vtime.h5")
check "its two points are kept (inout_Z2_vtimes 2, inout_Z2_vtime_1 = 1 -1)" \
    [ "$(param inout_Z2_vtimes)" = 2 -a "$(param inout_Z2_vtime_1)" = "1 -1" ]

sed 's|<imposevelocity mode="2" />|<imposevelocity mode="1"><velocityfile file="v.csv" /></imposevelocity>|' "$CASE" >"$T/vfile.xml"
line=$(grep -n '<velocityfile' "$T/vfile.xml" | cut -d: -f1)
bad "velocity from a file refused by name" "vfile\.xml:$line: element <velocityfile> is not supported in <imposevelocity>" "$T/vfile.xml"

sed 's|<imposevelocity mode="2" />|<imposevelocity mode="1"><velocitytimes><timevalue time="1" v="0" /><timevalue time="1" v="1" /></velocitytimes></imposevelocity>|' "$CASE" >"$T/vback.xml"
line=$(grep -n '<velocitytimes>' "$T/vback.xml" | cut -d: -f1)
bad "a time series going back in time" "vback\.xml:$line: <timevalue time=\"1\"> does not come after the one before \(1 s\)" "$T/vback.xml"

sed 's|<imposevelocity mode="2" />|<imposevelocity mode="3" />|' "$CASE" >"$T/vgrid.xml"
line=$(grep -n '<imposevelocity mode="3" />' "$T/vgrid.xml" | cut -d: -f1)
bad "velocity interpolated from a grid refused by name" "vgrid\.xml:$line: <imposevelocity mode=\"3\"> \(interpolated from a grid\) is not implemented yet" "$T/vgrid.xml"

sed 's|<imposerhop mode="0" />|<imposerhop mode="1" />|' "$CASE" >"$T/hydro.xml"
line=$(grep -n '<imposerhop mode="1" />' "$T/hydro.xml" | cut -d: -f1)
bad "hydrostatic density without zsurf" "hydro\.xml:$line: <imposerhop mode=\"1\"> \(hydrostatic\) needs the free surface" "$T/hydro.xml"

# an inlet profile: <velocity3> (parabolic in z) kept as inout_Z1_vprofile (kind, v1..3, z1..3)
sed 's|<velocity v="1" units_comment="m/s" />|<velocity3 v="0" v2="1.5" v3="0" z="0" z2="0.2" z3="0.4" />|' "$CASE" >"$T/prof.xml"
expect 0 "an inlet velocity profile (<velocity3>) resolves" "$GEN" -q "$T/prof.xml" -o "$T/prof.h5"
info=$("$BIN/vres-info" "$T/prof.h5")
check "its kind and points are kept ($(param inout_Z1_vprofile))" [ "$(param inout_Z1_vprofile)" = "3 0 1.5 0 0 0.2 0.4" ]
sed 's|<velocity v="1" units_comment="m/s" />|<velocity2 v="0" v2="1.5" z="0.2" z2="0.2" />|' "$CASE" >"$T/prof2.xml"
line=$(grep -n '<velocity2' "$T/prof2.xml" | cut -d: -f1)
bad "a profile with two points at one height" "prof2\.xml:$line: <velocity2>: two points at the same height z = 0.2" "$T/prof2.xml"

# the inlet as DualSPHysics' examples write it: the fluid's first column drawn with mkfluid 1
# and <particles mkfluid="1" direction="right"/>: the face dp/2 in front of that column (x = 0),
# spanning the column plus dp/2 at each end (0.4 m), as the <line> form gives
awk '/<setmkbound mk="0" \/>/ && !d {print "<setmkfluid mk=\"1\" /><drawbox><boxfill>left</boxfill><point x=\"0\" y=\"0\" z=\"0\" /><size x=\"#Lx\" y=\"0\" z=\"#L\" /></drawbox>"; d = 1}
     /<zone2d>/ && !z {print "<zone2d><particles mkfluid=\"1\" direction=\"right\" /></zone2d>"; skip = 1; z = 1; next}
     skip && /<\/zone2d>/ {skip = 0; next} !skip {print}' "$CASE" >"$T/parts.xml"
expect 0 "a zone from particles (<particles mkfluid direction>) resolves" "$GEN" -q "$T/parts.xml" -o "$T/parts.h5"
info=$("$BIN/vres-info" "$T/parts.h5")
check "zone 1 from particles: face corner (0, 0, 0) as the line's ($(param inout_Z1_point))" [ "$(param inout_Z1_point)" = "0 0 0" ]
check "zone 1 from particles: direction (1, 0, 0), extent 0.4 m ($(param inout_Z1_direction); $(param inout_Z1_extent))" \
    [ "$(param inout_Z1_direction)" = "1 0 0" -a "$(param inout_Z1_extent)" = "0.4 0" ]
for v in 'mkfluid="5" direction="right"|the case draws no fluid particle of mkfluid 5' \
    'mkfluid="1" direction="up"|<particles> needs direction="top\|bottom\|left\|right\|front\|back\|custom"' \
    'mkfluid="1" direction="back"|a direction along y \(front, back\) has no meaning in a 2D case' \
    'mkfluid="0" direction="right"|its 500 particles spread 1.96 m along the direction: they must lie in one line'; do
    sed "s|<particles mkfluid=\"1\" direction=\"right\" />|<particles ${v%%|*} />|" "$T/parts.xml" >"$T/badparts.xml"
    line=$(grep -n '<particles' "$T/badparts.xml" | cut -d: -f1)
    bad "zone from particles: ${v%%|*}" "badparts\.xml:$line: .*${v#*|}" "$T/badparts.xml"
done
sed 's|<zone2d><particles mkfluid="1" direction="right" /></zone2d>|<zone2d><particles mkfluid="1" direction="right" /><line><point x="0" z="0" /><point2 x="0" z="0.4" /><direction x="1" z="0" /></line></zone2d>|' "$T/parts.xml" >"$T/both.xml"
line=$(grep -n '<zone2d><particles' "$T/both.xml" | cut -d: -f1)
bad "a zone with both a line and particles" "both\.xml:$line: <zone2d> needs one <line> or one <particles>" "$T/both.xml"

# <initials><velocity mkfluid x y z>: the fluid of that mk starts with that velocity, others at rest
sed 's|</geometry>|</geometry><initials><velocity mkfluid="1" x="0.5" y="0" z="-0.25" /></initials>|' "$T/parts.xml" >"$T/init.xml"
expect 0 "<initials> resolves" "$GEN" -q "$T/init.xml" -o "$T/init.h5"
paste <(values /Domains/D0/Type "$T/init.h5") <(values /Domains/D0/Mk "$T/init.h5") \
    <(values /Domains/D0/Velocity "$T/init.h5" | paste - - -) >"$T/initv"
check "initials: the 10 fluid particles of mk 1 move at (0.5, 0, -0.25) m/s" \
    [ "$(awk '$1 == 0 && $2 == 1 && $3 == 0.5 && $4 == 0 && $5 == -0.25' "$T/initv" | wc -l)" -eq 10 ]
check "initials: every other particle at rest" [ "$(awk '!($1 == 0 && $2 == 1) && ($3 != 0 || $4 != 0 || $5 != 0)' "$T/initv" | wc -l)" -eq 0 ]
sed 's|<velocity mkfluid="1" x="0.5" y="0" z="-0.25" />|<velocity mkfluid="1"><direction x="1" y="0" z="0" /><velocity3 v="0" v2="1" v3="0" z="0" z2="0.2" z3="0.4" /></velocity>|' "$T/init.xml" >"$T/init3.xml"
expect 0 "<initials> with a parabolic profile (<velocity3>) resolves" "$GEN" -q "$T/init3.xml" -o "$T/init3.h5"
paste <(values /Domains/D0/Type "$T/init3.h5") <(values /Domains/D0/Mk "$T/init3.h5") \
    <(values /Domains/D0/Position "$T/init3.h5" | paste - - -) <(values /Domains/D0/Velocity "$T/init3.h5" | paste - - -) >"$T/init3v"
check "initials velocity3: u = z (0.4 - z) / 0.04 on mk 1 to 1e-6" \
    [ "$(awk '$1 == 0 && $2 == 1 {n++; e = $6 - $5 * (0.4 - $5) / 0.04; if (e < 0) e = -e; if (e > 1e-6 || $8 != 0) bad++} END {print n + 0, bad + 0}' "$T/init3v")" = "10 0" ]
sed 's|<velocity mkfluid="1" x="0.5" y="0" z="-0.25" />|<velwave mkfluid="1" depth="1" hmaxwave="0.1" x0="0" />|' "$T/init.xml" >"$T/initw.xml"
line=$(grep -n '<velwave' "$T/initw.xml" | cut -d: -f1)
bad "<initials><velwave> refused by name" "initw\.xml:$line: element <velwave> is not supported in <initials>" "$T/initw.xml"

# <normals><norplane>: the walls of the mk take the vector to the plane (auto: half a dp past
# their outermost row) as their normal; with planes only, the drawing's normals are dropped
sed 's|</geometry>|</geometry><normals><norplane mkbound="0"><point auto="true" /><normal x="0" y="0" z="-1" /><maxdisth v="1.5" /></norplane></normals>|' "$CASE" >"$T/norplane.xml"
expect 0 "<norplane> resolves" "$GEN" -q "$T/norplane.xml" -o "$T/norplane.h5"
paste <(values /Domains/D0/Type "$T/norplane.h5") <(values /Domains/D0/Position "$T/norplane.h5" | paste - - -) \
    <(values /Domains/D0/Normal "$T/norplane.h5" | paste - - -) >"$T/nor"
# the plane: 0.5 dp (0.02 m) below the bottom wall's lowest row (z = -0.1 m), normals down;
# maxdisth 1.5 h = 0.085 m takes the rows z = -0.1 and -0.06 (0.02 and 0.06 m from it, 70
# columns each), not z = -0.02 (0.1 m) nor the top wall above the fluid
check "norplane: the 140 particles of the two bottom rows get the vector to the plane" \
    [ "$(awk '$1 != 0 && ($4 + 0.1 < 1e-9 && $4 + 0.1 > -1e-9 || $4 + 0.06 < 1e-9 && $4 + 0.06 > -1e-9) {
              e = $7 + ($4 + 0.12); if (e < 0) e = -e; if (e < 1e-6 && $5 == 0 && $6 == 0) n++} END {print n + 0}' "$T/nor")" -eq 140 ]
check "norplane: every other wall particle has none" \
    [ "$(awk '$1 != 0 && ($5 != 0 || $6 != 0 || $7 != 0)' "$T/nor" | wc -l)" -eq 140 ]
# a refinement box clear of the walls (at dp 0.02: x 0.8..1.2, z 0.12..0.28 m, its band
# reaching z 0.092 m): the box's domain draws no wall of the plane's mk, which is not an error
# there (a note), and the root's walls keep the plane's normals (DualSPHysics' cylinder case:
# norplanes for the channel's walls, a box around the cylinder)
sed 's|</geometry>|</geometry><vres><bufferbox><point x="0.8" y="0" z="0.12" /><endpoint x="1.2" y="0" z="0.28" /><dpratio v="2" /></bufferbox></vres>|' "$T/norplane.xml" >"$T/norbox.xml"
expect 0 "<norplane> and a box clear of its walls: vres-gencase at dp 0.02" "$GEN" -q --dp 0.02 "$T/norbox.xml" -o "$T/norbox.h5"
expect 0 "vres-partition draws the box's domain without the plane's walls" "$ASAN/vres-partition" -v "$T/norbox.h5" -o "$T/norboxp.h5"
check "said (-v): no wall of that mk in the box's region" grep -q 'norplane mkbound="0">: no wall particle of that mk in this domain' "$ERR"
walln() { paste <(values /Domains/D0/Type "$1") <(values /Domains/D0/Position "$1" | paste - - -) \
              <(values /Domains/D0/Normal "$1" | paste - - -) | awk '$1 != 0 && ($5 != 0 || $6 != 0 || $7 != 0)' | sort; }
walln "$T/norbox.h5" >"$T/norb0"
walln "$T/norboxp.h5" >"$T/norb1"
check "the root's walls after partition keep the plane's normals ($(wc -l <"$T/norb1") of them, as vres-gencase's)" \
    bash -c "[ -s '$T/norb0' ] && cmp -s '$T/norb0' '$T/norb1'"
check "the box's domain has no wall" [ "$(values /Domains/D1/Type "$T/norboxp.h5" | awk '$1 >= 2 && $1 <= 4' | wc -l)" -eq 0 ]
sed 's|<point auto="true" />|<point auto="true" /><onlypos><posmin x="0" /></onlypos>|' "$T/norplane.xml" >"$T/norpos.xml"
line=$(grep -n '<onlypos>' "$T/norpos.xml" | cut -d: -f1)
bad "<norplane><onlypos> refused by name" "norpos\.xml:$line: element <onlypos> is not supported in <norplane>" "$T/norpos.xml"

# the outlet moved onto the inlet: within a zone depth of it
sed 's|<point x="#Lx" z="0" />|<point x="0.1" z="0" />|; s|<point2 x="#Lx" z="#L" />|<point2 x="0.1" z="#L" />|' "$CASE" >"$T/overlap.xml"
line=$(grep -n 'outlet: velocity and density' "$T/overlap.xml" | cut -d: -f1)
bad "overlapping zones" "overlap\.xml:$line: inlet/outlet zone 2 lies within a zone depth of zone 1" "$T/overlap.xml"
