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

sed 's|<zone2d>|<zone2d><particles mkfluid="1" direction="right" />|' "$CASE" >"$T/parts.xml"
line=$(grep -n '<particles' "$T/parts.xml" | head -1 | cut -d: -f1)
expect_err 1 "parts\.xml:$line: element <particles> is not supported in <zone2d>" "zones from particles refused by name" \
    "$GEN" "$T/parts.xml" -o "$T/out/case.h5"
nothing_in "$T/out" "zone from particles: nothing written"

# the outlet moved onto the inlet: within a zone depth of it
sed 's|<point x="#Lx" z="0" />|<point x="0.1" z="0" />|; s|<point2 x="#Lx" z="#L" />|<point2 x="0.1" z="#L" />|' "$CASE" >"$T/overlap.xml"
line=$(grep -n 'outlet: velocity and density' "$T/overlap.xml" | cut -d: -f1)
bad "overlapping zones" "overlap\.xml:$line: inlet/outlet zone 2 lies within a zone depth of zone 1" "$T/overlap.xml"
