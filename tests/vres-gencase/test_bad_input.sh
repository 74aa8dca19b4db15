#!/usr/bin/env bash
# vres-gencase on bad input, under AddressSanitizer: one clear message naming the file (and the
# line where there is one), exit 1, nothing written.
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
bad "malformed XML" "malformed\.xml:[0-9]+: malformed XML: .*mismatch" "$T/malformed.xml"

sed 's|<setdrawmode mode="full" />|<drawsphere radius="1" />|' "$CASE" >"$T/unknown.xml"
line=$(grep -n drawsphere "$T/unknown.xml" | cut -d: -f1)
bad "unknown element with its line" "unknown\.xml:$line: element <drawsphere> is not supported" "$T/unknown.xml"

sed 's|#WaterWidth|#WaterWidht|' "$CASE" >"$T/undefined.xml"
bad "undefined variable" "undefined\.xml:[0-9]+: .*undefined variable 'WaterWidht'" "$T/undefined.xml"

sed 's|dp="0.01"|dp="0"|' "$CASE" >"$T/dpzero.xml"
bad "dp zero" "dpzero\.xml:[0-9]+: dp must be greater than zero" "$T/dpzero.xml"
sed 's|dp="0.01"|dp="-0.01"|' "$CASE" >"$T/dpneg.xml"
bad "dp negative" "dpneg\.xml:[0-9]+: dp must be greater than zero" "$T/dpneg.xml"

sed 's|point x="0" y="-1" z="0"|point x="50" y="-1" z="50"|' "$CASE" >"$T/empty.xml"
bad "empty geometry" "empty\.xml:[0-9]+: the geometry is empty" "$T/empty.xml"

sed 's|<cflnumber value="0.2" />|<cflnumber value="0" />|' "$CASE" >"$T/cfl.xml"
bad "impossible cflnumber" "cfl\.xml:[0-9]+: cflnumber must be in \(0, 1\]" "$T/cfl.xml"

sed 's|<parameter key="Kernel" value="2"|<parameter key="Kernel" value="1"|' "$CASE" >"$T/kernel.xml"
bad "unimplemented parameter value" "kernel\.xml:[0-9]+: parameter Kernel=1 is not implemented" "$T/kernel.xml"

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
expect_err 1 "two\.xml:[0-9]+: element <drawsphere> is not supported" "two problems: the element" \
    "$GEN" "$T/two.xml" -o "$T/out/case.h5"
check "two problems: the parameter too" grep -qE "two\.xml:[0-9]+: parameter StepAlgorithm=5: valid values are 1,2" "$ERR"
check "two problems: two messages" [ "$(wc -l <"$ERR")" -eq 2 ]
nothing_in "$T/out" "two problems: nothing written"
