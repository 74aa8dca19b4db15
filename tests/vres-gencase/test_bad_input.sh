#!/usr/bin/env bash
# vres-gencase on bad input, under AddressSanitizer: one clear message naming the file and the
# line of the element at fault (found in the test's own copy with grep -n), exit 1, nothing
# written.
source "$(dirname "$0")/../harness.sh"
GEN=$ASAN/vres-gencase
CASE=$CASES/dsph_dambreak2d/dambreak2d_Def.xml
mkdir "$T/out"

# bad NAME PATTERN XMLFILE: exit 1, one message matching PATTERN, no store written.
bad() {
    local name=$1 pat=$2 xml=$3
    expect_err 1 "$pat" "$name" "$GEN" "$xml" -o "$T/out/case.h5"
    check "$name: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
}

sed 's|<gamma value="7" />|<gamma value="7">|' "$CASE" >"$T/malformed.xml"
# libxml2 reports the mismatch where the enclosing element closes, naming the open tag's line
open=$(grep -n '<gamma value="7">' "$T/malformed.xml" | cut -d: -f1)
close=$(grep -n '</constantsdef>' "$T/malformed.xml" | cut -d: -f1)
bad "malformed XML" "malformed\.xml:$close: malformed XML: Opening and ending tag mismatch: gamma line $open and constantsdef" "$T/malformed.xml"

sed 's|<setdrawmode mode="full" />|<drawsphere radius="1" />|' "$CASE" >"$T/unknown.xml"
line=$(grep -n drawsphere "$T/unknown.xml" | cut -d: -f1)
bad "unknown element with its line" "unknown\.xml:$line: element <drawsphere> is not supported" "$T/unknown.xml"

sed 's|#WaterWidth|#WaterWidht|' "$CASE" >"$T/undefined.xml"
line=$(grep -n WaterWidht "$T/undefined.xml" | cut -d: -f1)
bad "undefined variable" "undefined\.xml:$line: x=\"#WaterWidht\" of <size>: undefined variable 'WaterWidht'" "$T/undefined.xml"

sed 's|dp="0.01"|dp="0"|' "$CASE" >"$T/dpzero.xml"
line=$(grep -n '<definition dp=' "$T/dpzero.xml" | cut -d: -f1)
bad "dp zero" "dpzero\.xml:$line: dp must be greater than zero \(dp=0\)" "$T/dpzero.xml"
sed 's|dp="0.01"|dp="-0.01"|' "$CASE" >"$T/dpneg.xml"
bad "dp negative" "dpneg\.xml:$line: dp must be greater than zero \(dp=-0\.01\)" "$T/dpneg.xml"

sed 's|point x="0" y="-1" z="0"|point x="50" y="-1" z="50"|' "$CASE" >"$T/empty.xml"
line=$(grep -n '<mainlist>' "$T/empty.xml" | cut -d: -f1)
bad "empty geometry" "empty\.xml:$line: the geometry is empty: no particles were drawn inside pointmin\.\.pointmax" "$T/empty.xml"

sed 's|<cflnumber value="0.2" />|<cflnumber value="0" />|' "$CASE" >"$T/cfl.xml"
line=$(grep -n '<cflnumber' "$T/cfl.xml" | cut -d: -f1)
bad "impossible cflnumber, at its element" "cfl\.xml:$line: cflnumber must be in \(0, 1\] \(cflnumber=0\)" "$T/cfl.xml"

sed 's|<parameter key="Kernel" value="2"|<parameter key="RigidAlgorithm" value="2"|' "$CASE" >"$T/rigid.xml"
line=$(grep -n 'key="RigidAlgorithm"' "$T/rigid.xml" | cut -d: -f1)
bad "unimplemented parameter value" "rigid\.xml:$line: parameter RigidAlgorithm=2 is not implemented in vres \(it implements RigidAlgorithm=0,1" "$T/rigid.xml"

bad "missing file" "nosuch\.xml: cannot open" "$T/nosuch.xml"

expect_err 1 "cannot write" "unwritable -o path" "$GEN" "$CASE" -o "$T/nodir/case.h5"
check "unwritable -o path: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
chmod a-w "$T/out"
if [ -w "$T/out" ]; then
    ok "read-only directory (skipped: running as a user who can write anyway) # SKIP"
else
    expect_err 1 "not writable" "read-only output directory" "$GEN" "$CASE" -o "$T/out/case.h5"
fi
chmod u+w "$T/out"
nothing_in "$T/out" "nothing written for an unwritable path"

# every problem of one pass: an unsupported element and an invalid parameter, each with its line
sed -e 's|<setdrawmode mode="full" />|<drawsphere radius="1" />|' \
    -e 's|<parameter key="StepAlgorithm" value="2"|<parameter key="StepAlgorithm" value="5"|' "$CASE" >"$T/two.xml"
line=$(grep -n drawsphere "$T/two.xml" | cut -d: -f1)
pline=$(grep -n 'key="StepAlgorithm"' "$T/two.xml" | cut -d: -f1)
expect_err 1 "two\.xml:$line: element <drawsphere> is not supported" "two problems: the element" \
    "$GEN" "$T/two.xml" -o "$T/out/case.h5"
check "two problems: the parameter too" grep -qE "two\.xml:$pline: parameter StepAlgorithm=5: valid values are 1,2" "$ERR"
check "two problems: two messages" [ "$(wc -l <"$ERR")" -eq 2 ]
nothing_in "$T/out" "two problems: nothing written"
