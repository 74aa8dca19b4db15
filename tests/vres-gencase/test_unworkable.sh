#!/usr/bin/env bash
# vres-gencase --check refuses the set-ups no run survives, each with one message naming the
# thing and the measure, exit 1 and nothing written (lib/preflight.c; vres-run refuses the same
# at its start: tests/vres-run/test_unworkable.sh): single-layer walls switched to mDBC, a
# channel fewer particles across than the kernel's diameter 4h and a body smaller than its
# support 2h, a DtMin the first
# step cannot reach, a refinement box its parent's buffer bands fill. The same set-ups drawn
# right pass.
source "$(dirname "$0")/../harness.sh"
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml
mkdir "$T/out"

# refuse NAME PATTERN ARGS...: --check exits 1 with the message, once, and writes nothing
refuse() {
    local name=$1 pat=$2; shift 2
    expect_err 1 "$pat" "$name" "$ASAN/vres-gencase" -q --check "$@" -o "$T/out/x.h5"
    check "$name: one message" [ "$(grep -c "vres-gencase:" "$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
}

# DualSPHysics' dam break (single-layer walls, whose faces give normals) switched to mDBC at dp
# 0.02: h = 0.0282843 m, the fluid next to a wall sees 2h - dp = 1.83 dp of it: 2 layers needed
refuse "single-layer walls under mDBC" \
    "dambreak2d: Boundary=2 \(mDBC\): the walls of mk 0 are 0\.02 m thick \(1 layer of dp 0\.02 m, the median along the normals of the 153 of its particles with a normal the fluid touches\), thinner than the kernel support 2h = 0\.0565685 m less the dp between them and the fluid: the fluid next to them would leak through; draw them 2 layers thick" \
    --dp 0.02 --set Boundary=2 "$DB"
# the same, its XML edited: the mDBC dam break with one layer instead of three
sed 's|<layers vdp="0,1,2" />|<layers vdp="0" />|' "$CASES/dsph_dambreak2d_mdbc/dambreak2d_mdbc_Def.xml" >"$T/one.xml"
check "the edited case has one layer" grep -q '<layers vdp="0" />' "$T/one.xml"
refuse "the mDBC dam break drawn with one layer" "one: Boundary=2 \(mDBC\): the walls of mk 0 are 0\.01 m thick \(1 layer of dp 0\.01 m" "$T/one.xml"
expect 0 "three layers pass" "$BIN/vres-gencase" -q --check --dp 0.02 "$CASES/dsph_dambreak2d_mdbc/dambreak2d_mdbc_Def.xml"
expect 0 "single-layer walls pass under DBC" "$BIN/vres-gencase" -q --check --dp 0.02 "$DB"

# Poiseuille's channel (L = 1 mm) at dp 0.25 mm: 4 particles across, 4h = 1.41 mm
refuse "a channel 4 particles across" \
    "poiseuille2d: the fluid of mk 0 is 4 particles across between walls along z \(0\.001 m at dp 0\.00025 m, the median over its 16 particles\), fewer than the kernel's diameter 4h = 0\.00141421 m" \
    --dp 2.5e-4 "$CASES/poiseuille2d/poiseuille2d_Def.xml"
expect 0 "10 particles across pass" "$BIN/vres-gencase" -q --check --dp 1e-4 "$CASES/poiseuille2d/poiseuille2d_Def.xml"

# a post 0.01 m square (mk 1) on the dam break's floor at dp 0.01: 2 particles across, 2h = 0.0283 m
post() { sed "s|</mainlist>|<setmkbound mk=\"1\" /><drawbox><boxfill>solid</boxfill><point x=\"2\" y=\"-1\" z=\"0.01\" /><size x=\"$1\" y=\"2\" z=\"$1\" /></drawbox></mainlist>|" "$DB"; }
post 0.01 >"$T/post.xml"
refuse "a body 2 particles across" \
    "post: the body of mk 1 is 2 particles across at most \(0\.02 m at dp 0\.01 m, from \(2, 0, 0\.01\) to \(2\.01, 0, 0\.02\)\), smaller than the kernel support 2h = 0\.0282843 m" \
    "$T/post.xml"
post 0.02 >"$T/post3.xml"
expect 0 "a body 3 particles across passes" "$BIN/vres-gencase" -q --check "$T/post3.xml"

# time steps: at dp 0.01 no step is longer than cflnumber h/c0 = 0.2 x 0.0141421 / 88.3672 s
refuse "DtMin above every step" \
    "dambreak2d: DtMin=0\.001 s is not below the longest time step the run can take, cflnumber h/c0 = 0\.2 x 0\.0141421 m / 88\.3672 m/s = 3\.20077e-05 s" \
    --set DtMin=0.001 "$DB"
refuse "CoefDtMin above cflnumber" "dambreak2d: DtMin = CoefDtMin h/c0 = 8\.00192e-05 s \(CoefDtMin=0\.5\) is not below the longest time step" \
    --set CoefDtMin=0.5 "$DB"
refuse "DtMin above DtIni" "dambreak2d: DtMin=2e-05 s is above DtIni=1e-05 s, the first time step the case gives" \
    --set DtIni=1e-5 --set DtMin=2e-5 "$DB"
expect 0 "DtMin below DtIni passes" "$BIN/vres-gencase" -q --check --set DtIni=1e-5 --set DtMin=1e-6 "$DB"

# a refinement box 0.1 m tall whose parent bands (0.06 m each) fill it: the message vres-partition gives
H2D=$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml
sed -e 's|<point x="0.6" y="0" z="0.3" />|<point x="0.6" y="0" z="0.45" />|' -e 's|<endpoint x="1.2" y="0" z="0.7" />|<endpoint x="1.2" y="0" z="0.55" />|' \
    "$H2D" >"$T/thin.xml"
line=$(grep -n "<bufferbox" "$T/thin.xml" | head -1 | cut -d: -f1)
refuse "a box its parent's bands fill" \
    "thin: bufferbox 1 \(line $line\): the box is too small along z: its parent's buffer bands \(0\.06 m each\) fill it; make it wider than 0\.14 m" \
    "$T/thin.xml"
"$BIN/vres-gencase" -q "$T/thin.xml" -o "$T/thin.h5"
expect_err 1 "thin: bufferbox 1 \(line $line\): the box is too small along z: its parent's buffer bands \(0\.06 m each\) fill it; make it wider than 0\.14 m" \
    "vres-partition gives the same message" "$BIN/vres-partition" "$T/thin.h5" -o "$T/out/p.h5"
nothing_in "$T/out" "vres-partition writes nothing"

# every shipped case passes
for x in "$CASES"/*/*.xml; do
    expect 0 "--check passes ${x#$CASES/}" "$BIN/vres-gencase" -q --check "$x"
done
