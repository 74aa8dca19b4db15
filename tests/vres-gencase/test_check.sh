#!/usr/bin/env bash
# vres-gencase --check: the pre-flight checks, writing nothing. The dam break is clean; a
# refinement box with buffsizeh 1.5 has a buffer narrower than the kernel support 2h and is
# named by its index and line; fluid left outside a cut simulation domain is reported.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/dsph_dambreak2d/dambreak2d_Def.xml
mkdir "$T/out"

expect 0 "the dam break passes --check" "$BIN/vres-gencase" --check "$CASE"
check "--check writes nothing on stdout" [ ! -s "$OUT" ]

# a buffer box 1.5 h wide, in a <vres> block inserted after </geometry> (the case is Symplectic)
sed -e 's|</geometry>|</geometry>\n        <vres>\n            <bufferbox>\n                <point x="0.2" y="0" z="0.2" />\n                <size x="0.5" y="0" z="1" />\n                <dpratio v="2" />\n                <buffsizeh v="1.5" />\n            </bufferbox>\n        </vres>|' \
    "$CASE" >"$T/narrow.xml"
line=$(grep -n "<bufferbox>" "$T/narrow.xml" | cut -d: -f1)
expect_err 1 "bufferbox 1 \(line $line\): buffsizeh=1.5 .*narrower than the kernel support 2h" \
    "--check names the narrow buffer" "$ASAN/vres-gencase" --check "$T/narrow.xml" -o "$T/out/x.h5"
check "one line per problem" [ "$(grep -c "bufferbox" "$ERR")" -eq 1 ]
nothing_in "$T/out" "--check writes no store"
expect 0 "the same case generates without --check" "$BIN/vres-gencase" -q "$T/narrow.xml" -o "$T/out/n.h5"

# simulation domain cut at x = 0.5: half the water column lies outside it
sed 's|<posmax x="default"|<posmax x="0.5"|' "$CASE" >"$T/cut.xml"
expect_err 1 "fluid particles lie outside the simulation domain" "--check finds fluid outside the domain" \
    "$ASAN/vres-gencase" --check "$T/cut.xml"

# cases/dambreak2d without its widened domain: the refinement box reaches 5 cm below the floor,
# outside the simulation domain. DualSPHysics accepts that; vres cuts the box to the domain and
# says so in one note naming the box and its line.
sed 's|z="default - 0.05"|z="default"|' "$CASES/dambreak2d/dambreak2d_Def.xml" >"$T/below.xml"
line=$(grep -n "<bufferbox>" "$T/below.xml" | cut -d: -f1)
expect 0 "a box reaching below the floor passes --check" "$ASAN/vres-gencase" --check "$T/below.xml"
check "one note names the box, its line and the clipped box" \
    [ "$(grep -c "below.xml:$line: note: <bufferbox> 1 reaches outside the simulation domain: clipped to (1.25, 0, -0.0125) to (1.66, 0, 0.65)" "$ERR")" -eq 1 ]
expect 0 "and generates" "$BIN/vres-gencase" -q "$T/below.xml" -o "$T/out/below.h5"
# attr PATH FILE: an attribute's values on one line
attr() { h5dump -m '%.17g' -a "$1" "$2" | awk '/\([0-9]+\):/ {sub(/.*\([0-9]+\): */, ""); gsub(/,/, ""); printf "%s%s", n++ ? " " : "", $0} END {print ""}'; }
check "the store keeps the clipped box" [ "$(attr /VRes/B0/point "$T/out/below.h5")" = "1.25 0 -0.012499999999999999" ]
check "and its line" [ "$(attr /VRes/B0/line "$T/out/below.h5")" = "$line" ]
sed -e 's|<point x="1.25" y="0" z="-0.05" />|<point x="1.25" y="0" z="-0.5" />|' -e 's|<size x="0.41" y="0" z="0.70" />|<size x="0.41" y="0" z="0.3" />|' \
    "$T/below.xml" >"$T/outside.xml"
expect_err 1 "outside.xml:$line: <bufferbox> 1 lies outside the simulation domain along z" \
    "a box wholly outside the domain is refused" "$ASAN/vres-gencase" --check "$T/outside.xml"
