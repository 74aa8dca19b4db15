#!/usr/bin/env bash
# vres-partition's options for sweeps: --dpratio, --buffsizeh, --overlappingh, --levels and
# --single override the store's boxes; with no box (or --single) it writes one domain, on which
# vres-run runs as on vres-gencase's store.
source "$(dirname "$0")/../harness.sh"
H2D=$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml
"$BIN/vres-gencase" -q "$H2D" -o "$T/h.h5"
attr() { h5dump -m '%.17g' -a "$1" "$2" | awk '/\([0-9]+\):/ {sub(/.*\([0-9]+\): */, ""); gsub(/,/, ""); printf "%s%s", n++ ? " " : "", $0} END {print ""}'; }

expect 0 "--dpratio 4" "$BIN/vres-partition" --dpratio 4 "$T/h.h5" -o "$T/r4.h5"
check "the box's dp is 0.005" [ "$(attr /Domains/D1/dp "$T/r4.h5")" = 0.0050000000000000001 ]
check "the store lists the box with dpratio 4" [ "$(attr /VRes/B0/dpratio "$T/r4.h5")" = 4 ]
check "D1: 80 x 40 fluid at dp 0.005" grep -q "D1: dp 0.005 m, 3200 fluid" "$ERR"
expect 0 "--buffsizeh 3" "$BIN/vres-partition" --buffsizeh 3 "$T/h.h5" -o "$T/b3.h5"
# 3 h = 0.0424 m: 5 child layers (0.05 m) out, 5 root layers (0.1 m) in
check "the child's band is 5 layers wide" [ "$(attr /Domains/D1/buffer_min "$T/b3.h5")" = "0.54999999999999993 0 0.25" ]
check "the root's band is 5 layers wide" [ "$(attr /Domains/D1/inner_min "$T/b3.h5" | cut -d' ' -f1)" = 0.69999999999999996 ]
expect 0 "--overlappingh 3" "$BIN/vres-partition" --overlappingh 3 "$T/h.h5" -o "$T/o3.h5"
# 3 h_child = 0.0424 m into the box: the root's fluid keeps the nodes up to 0.63, its hole starts at 0.64
check "the root's fluid reaches into the box" [ "$(attr /Domains/D1/hole_min "$T/o3.h5" | cut -d' ' -f1)" = 0.64000000000000001 ]
check "the child's fluid box stays the box" [ "$(attr /Domains/D1/box_min "$T/o3.h5" | cut -d' ' -f1)" = 0.59999999999999998 ]

expect 0 "--single" "$BIN/vres-partition" --single "$T/h.h5" -o "$T/s.h5"
check "--single: one domain" grep -q "hydrostatic_vres2d: 1 domain, 0 interface segments" "$ERR"
check "--single: the root's 1250 fluid, no buffer" grep -q "D0: dp 0.02 m, 1250 fluid, 0 buffer, 390 walls" "$ERR"
check "--single: no box listed" [ "$(h5ls "$T/s.h5/VRes" | wc -l)" -eq 0 ]
expect 0 "--levels 1 is the root alone" "$BIN/vres-partition" --levels 1 "$T/h.h5" -o "$T/l1.h5"
check "--levels 1: one domain" grep -q "1 domain, 0 interface segments" "$ERR"
expect 0 "--levels 2 keeps the box" "$BIN/vres-partition" --levels 2 "$T/h.h5" -o "$T/l2.h5"
check "--levels 2: two domains" grep -q "2 domains" "$ERR"

# nested boxes: a second level inside the first (dp 0.005), and --levels 2 drops it
sed -e 's|<dpratio v="2" />|<dpratio v="2" />\n                <bufferbox><point x="0.7" y="0" z="0.32"/><endpoint x="0.9" y="0" z="0.6"/><dpratio v="2"/></bufferbox>|' \
    "$H2D" >"$T/nested.xml"
"$BIN/vres-gencase" -q "$T/nested.xml" -o "$T/n.h5"
expect 0 "two nested levels" "$ASAN/vres-partition" "$T/n.h5" -o "$T/np.h5"
check "three domains, D2 in D1 at dp 0.005" [ "$(attr /Domains/D2/parent "$T/np.h5") $(attr /Domains/D2/dp "$T/np.h5")" = "1 0.0050000000000000001" ]
check "four interfaces" [ "$(h5ls "$T/np.h5/Interfaces" | wc -l)" -eq 4 ]
expect 0 "--levels 2 of the nested case" "$BIN/vres-partition" --levels 2 "$T/n.h5" -o "$T/n2.h5"
check "--levels 2: two domains" grep -q "2 domains" "$ERR"
# siblings side by side
sed -e 's|<point x="0.6" y="0" z="0.3" />|<point x="0.6" y="0" z="0.3" />|' \
    -e 's|</bufferbox>|</bufferbox>\n            <bufferbox><point x="0.1" y="0" z="0.1"/><endpoint x="0.4" y="0" z="0.4"/><dpratio v="2"/></bufferbox>|' \
    "$H2D" >"$T/sib.xml"
"$BIN/vres-gencase" -q "$T/sib.xml" -o "$T/sib.h5"
expect 0 "two sibling boxes" "$BIN/vres-partition" "$T/sib.h5" -o "$T/sibp.h5"
check "siblings: both children of D0" [ "$(attr /Domains/D1/parent "$T/sibp.h5") $(attr /Domains/D2/parent "$T/sibp.h5")" = "0 0" ]

# no refinement box: one domain, and vres-run runs on it as on the gencase store
"$BIN/vres-gencase" -q "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/plain.h5"
expect 0 "a store without boxes partitions" "$BIN/vres-partition" "$T/plain.h5" -o "$T/plainp.h5"
check "into one domain" grep -q "hydrostatic2d: 1 domain, 0 interface segments" "$ERR"
expect 0 "vres-run runs the partitioned store" "$BIN/vres-run" -q --tmax 0.002 --tout 0.002 "$T/plainp.h5" -o "$T/run"
check "and writes its snapshots" [ -f "$T/run/snap_00001.h5" ]
