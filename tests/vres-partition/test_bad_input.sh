#!/usr/bin/env bash
# vres-partition refuses what the coupling cannot run, each with one message naming the box
# and its case line, and writes nothing: a child not inside its parent, overlapping siblings, a
# buffer narrower than the kernel support, dpratio <= 0, a box cutting a floating body, Verlet
# or the cubic spline; and bad input files (run with the ASan build).
source "$(dirname "$0")/../harness.sh"
H2D=$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml
P=$ASAN/vres-partition
mkdir "$T/out"
"$BIN/vres-gencase" -q "$H2D" -o "$T/h.h5"
line=$(grep -n "<bufferbox" "$H2D" | head -1 | cut -d: -f1)

# refuse NAME PATTERN ARGS...: exit 1, the message, nothing written
refuse() {
    local name=$1 pat=$2; shift 2
    expect_err 1 "$pat" "$name" "$P" "$@" -o "$T/out/p.h5"
    check "$name: one message" [ "$(grep -c "vres-partition:" "$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
}

refuse "--dpratio 0" "bufferbox 1 \(line $line\): dpratio=0: it must be greater than zero" --dpratio 0 "$T/h.h5"
refuse "--dpratio -1" "bufferbox 1 \(line $line\): dpratio=-1" --dpratio -1 "$T/h.h5"
refuse "--buffsizeh 1.5" "bufferbox 1 \(line $line\): buffsizeh=1.5 makes its buffer 0.0212132 m wide, narrower than the kernel support 2h = 0.0282843 m" \
    --buffsizeh 1.5 "$T/h.h5"
refuse "--overlappingh -1" "overlappingh=-1: it must not be negative" --overlappingh -1 "$T/h.h5"
expect_err 1 "--levels 0: the number of levels counts the root" "--levels 0 is refused" "$P" --levels 0 "$T/h.h5" -o "$T/out/p.h5"

# a nested box reaching out of its parent (x from 0.5, its parent from 0.6)
sed -e 's|<dpratio v="2" />|<dpratio v="2" />\n                <bufferbox><point x="0.5" y="0" z="0.35"/><endpoint x="0.9" y="0" z="0.6"/><dpratio v="2"/></bufferbox>|' \
    "$H2D" >"$T/out.xml"
"$BIN/vres-gencase" -q "$T/out.xml" -o "$T/outside.h5"
refuse "a child not inside its parent" "bufferbox 2 \(line $((line + 4))\): it is not inside its parent bufferbox 1 \(line $line\)" "$T/outside.h5"
# a child whose buffer band leaves its parent although the box itself is inside (3 layers of 0.005)
sed -e 's|<dpratio v="2" />|<dpratio v="2" />\n                <bufferbox><point x="0.605" y="0" z="0.35"/><endpoint x="0.9" y="0" z="0.6"/><dpratio v="2"/></bufferbox>|' \
    "$H2D" >"$T/band.xml"
"$BIN/vres-gencase" -q "$T/band.xml" -o "$T/band.h5"
refuse "a child's band leaving its parent" "bufferbox 2 \(line $((line + 4))\): it is not inside its parent" "$T/band.h5"
# overlapping siblings
sed -e 's|</bufferbox>|</bufferbox>\n            <bufferbox><point x="0.3" y="0" z="0.1"/><endpoint x="0.7" y="0" z="0.4"/><dpratio v="2"/></bufferbox>|' \
    "$H2D" >"$T/sib.xml"
"$BIN/vres-gencase" -q "$T/sib.xml" -o "$T/sib.h5"
refuse "overlapping siblings" "bufferbox 1 \(line $line\): it overlaps its sibling bufferbox 2 \(line $((line + 5))\)" "$T/sib.h5"
# a buffer narrower than 2h given in the case (vres-gencase writes it; --check warns)
sed -e 's|<dpratio v="2" />|<dpratio v="2" /><buffsizeh v="1.5" />|' "$H2D" >"$T/narrow.xml"
"$BIN/vres-gencase" -q "$T/narrow.xml" -o "$T/narrow.h5"
refuse "a narrow buffer in the case" "bufferbox 1 \(line $line\): buffsizeh=1.5 .*narrower than the kernel support" "$T/narrow.h5"
# a box too thin for its parent's two buffer bands
sed -e 's|<point x="0.6" y="0" z="0.3" />|<point x="0.6" y="0" z="0.45" />|' -e 's|<endpoint x="1.2" y="0" z="0.7" />|<endpoint x="1.2" y="0" z="0.55" />|' \
    "$H2D" >"$T/thin.xml"
"$BIN/vres-gencase" -q "$T/thin.xml" -o "$T/thin.h5"
refuse "a box too thin" "bufferbox 1 \(line $line\): the box is too small along z" "$T/thin.h5"
# a box cutting a floating body (a float of mkbound 5 from x 0.5 to 0.7, the box from 0.6)
sed -e 's|</mainlist>|<setmkbound mk="5"/><setnormalinvert invert="false"/><drawbox><boxfill>solid</boxfill><point x="0.5" y="0" z="0.38"/><size x="0.2" y="0" z="0.1"/></drawbox></mainlist>|' \
    -e 's|<vres>|<floatings><floating mkbound="5" rhopbody="800"/></floatings><vres>|' "$H2D" >"$T/float.xml"
"$BIN/vres-gencase" -q "$T/float.xml" -o "$T/float.h5"
refuse "a box cutting a floating body" "bufferbox 1 \(line $line\): it cuts floating body mkbound 5" "$T/float.h5"
# the same float wholly inside the box is fine
sed -e 's|<point x="0.5" y="0" z="0.38"/><size x="0.2"|<point x="0.7" y="0" z="0.38"/><size x="0.1"|' "$T/float.xml" >"$T/float_in.xml"
"$BIN/vres-gencase" -q "$T/float_in.xml" -o "$T/float_in.h5"
expect 0 "a float wholly inside the box is fine" "$P" -q "$T/float_in.h5" -o "$T/float_in_p.h5"
check "its particles are floating in D1" [ "$(values /Domains/D1/Type "$T/float_in_p.h5" | grep -cx 4)" -gt 0 ]

# stores vres-gencase cannot write: Verlet or the cubic spline with a box, corrupt /Interfaces
if VRES_TEST_BAD_STORES=$T "$ROOT/$VRES_BUILD/tests/test_partition" >/dev/null 2>&1; then
    refuse "Verlet" "bufferbox 1 \(line $line\): variable resolution needs StepAlgorithm=2 \(Symplectic\); the store has 1 \(Verlet\)" "$T/verlet.h5"
    refuse "the cubic spline" "variable resolution supports only Kernel=2 \(Wendland\); the store has 1 \(cubic spline\)" "$T/cubic.h5"
    expect_err 1 "badnormal.h5: /Interfaces/I1/Normal: segment 0 is not a unit vector" "a non-unit normal is refused on reading" \
        "$ASAN/vres-info" "$T/badnormal.h5"
    expect_err 1 "selfiface.h5: /Interfaces/I1: domains 1 and 1 are not parent and child" "an interface of a domain with itself" \
        "$ASAN/vres-info" "$T/selfiface.h5"
else
    notok "make the bad stores with $VRES_BUILD/tests/test_partition (build it: make $VRES_BUILD/tests/test_partition)"
fi

# input that is not a gencase store
"$BIN/vres-partition" -q "$T/h.h5" -o "$T/parts.h5"
refuse "a partitioned store" "the store holds 2 domains: partition the store vres-gencase writes" "$T/parts.h5"
refuse "a missing file" "nosuch.h5: cannot open" "$T/nosuch.h5"
printf 'not hdf5\n' >"$T/text.h5"
refuse "a text file" "not an HDF5 file" "$T/text.h5"
expect_err 2 "Try 'vres-partition --help'" "no store is a usage error" "$P"
if command -v script >/dev/null; then
    script -qec "$P $T/h.h5" "$T/typescript" >/dev/null 2>&1
    check "no binary store written to a terminal" grep -q "refusing to write a binary store to a terminal" "$T/typescript"
fi
