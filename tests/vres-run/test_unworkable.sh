#!/usr/bin/env bash
# vres-run refuses at its start, before any step and before its run directory exists, the
# set-ups vres-gencase --check refuses (lib/preflight.c; tests/vres-gencase/test_unworkable.sh):
# single-layer walls under mDBC, a channel fewer particles across than the kernel's diameter and
# a body smaller than its support, a DtMin above every time step. Each is one message naming the thing; exit 1.
source "$(dirname "$0")/../harness.sh"
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml
R=$ASAN/vres-run

# refuse NAME PATTERN STORE: vres-run exits 1 with the message once and makes no run directory
refuse() {
    local name=$1 pat=$2 store=$3
    expect_err 1 "$pat" "$name" "$R" -q --threads 1 --tmax 0.001 "$store" -o "$T/run"
    check "$name: one message" [ "$(grep -c "vres-run:" "$ERR")" -eq 1 ]
    check "$name: no run directory" [ ! -e "$T/run" ]
}

"$BIN/vres-gencase" -q --dp 0.02 --set Boundary=2 "$DB" -o "$T/mdbc1.h5"
refuse "single-layer walls under mDBC" \
    "dambreak2d: Boundary=2 \(mDBC\): the walls of mk 0 are 0\.02 m thick \(1 layer of dp 0\.02 m, the median along the normals of the 153 of its particles with a normal the fluid touches\), thinner than the kernel support 2h = 0\.0565685 m" \
    "$T/mdbc1.h5"
# the same walls three layers thick run (one step)
"$BIN/vres-gencase" -q --dp 0.05 "$CASES/dsph_dambreak2d_mdbc/dambreak2d_mdbc_Def.xml" -o "$T/mdbc3.h5"
expect 0 "three layers under mDBC run" "$BIN/vres-run" -q --threads 1 --tmax 1e-4 "$T/mdbc3.h5" -o "$T/run3"

"$BIN/vres-gencase" -q --dp 2.5e-4 "$CASES/poiseuille2d/poiseuille2d_Def.xml" -o "$T/chan.h5"
refuse "a channel 4 particles across" "poiseuille2d: the fluid of mk 0 is 4 particles across between walls along z" "$T/chan.h5"

sed 's|</mainlist>|<setmkbound mk="1" /><drawbox><boxfill>solid</boxfill><point x="2" y="-1" z="0.01" /><size x="0.01" y="2" z="0.01" /></drawbox></mainlist>|' \
    "$DB" >"$T/post.xml"
"$BIN/vres-gencase" -q "$T/post.xml" -o "$T/post.h5"
refuse "a body 2 particles across" "post: the body of mk 1 is 2 particles across at most \(0\.02 m at dp 0\.01 m" "$T/post.h5"

"$BIN/vres-gencase" -q --dp 0.05 --set DtMin=0.001 "$DB" -o "$T/dtmin.h5"
refuse "DtMin above every step" "dambreak2d: DtMin=0\.001 s is not below the longest time step the run can take, cflnumber h/c0 = 0\.2 x 0\.0707107 m / 87\.4746 m/s = 0\.000161671 s" \
    "$T/dtmin.h5"
"$BIN/vres-gencase" -q --dp 0.05 --set DtIni=1e-5 --set DtMin=2e-5 "$DB" -o "$T/dtini.h5"
refuse "DtMin above DtIni" "dambreak2d: DtMin=2e-05 s is above DtIni=1e-05 s" "$T/dtini.h5"
