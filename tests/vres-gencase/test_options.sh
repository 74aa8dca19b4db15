#!/usr/bin/env bash
# vres-gencase --set and --dp: a variable override changes the geometry, a parameter or constant
# override is recorded with origin "set", --dp redraws at another spacing; names that match
# nothing are refused. Expected counts are lattice counts worked by hand for the dam break.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/dsph_dambreak2d/dambreak2d_Def.xml

# count_type STORE TYPE: particles of the root domain with that type code.
count_type() {
    h5dump -y -w 1 -d /Domains/D0/Type "$1" | grep -E '^ *[0-9]+,?$' | tr -d ' ,' | grep -cx "$2"
}
# param STORE NAME: value of a /Parameters attribute (first number).
param() {
    h5dump -a "/Parameters/$2" "$1" | sed -n 's/^ *(0): *//p' | head -1
}

# WaterWidth 0.5: 51 x 201 nodes, minus the 251 on the left wall and floor = 10000 fluid.
expect 0 "--set of a variable" "$BIN/vres-gencase" "$CASE" --set WaterWidth=0.5 -o "$T/w.h5"
check "--set WaterWidth=0.5 gives 10000 fluid" [ "$(count_type "$T/w.h5" 0)" -eq 10000 ]
check "--set of a variable is noted" grep -q "variable WaterWidth = 0.5 from --set" "$ERR"
check "the override is kept in /Geometry" grep -q "WaterWidth=0.5" <(h5dump -d /Geometry/overrides "$T/w.h5")

expect 0 "--set of a parameter and a constant" "$BIN/vres-gencase" -q "$CASE" --set TimeMax=3.5 --set cflnumber=0.1 -o "$T/p.h5"
check "TimeMax is 3.5" [ "$(param "$T/p.h5" TimeMax)" = "3.5" ]
check "TimeMax origin is set" [ "$(param "$T/p.h5" TimeMax.origin)" = '"set"' ]
check "cflnumber is 0.1" [ "$(param "$T/p.h5" cflnumber)" = "0.1" ]

# dp 0.02: fluid 51 x 101 - 151 = 5000, walls 201 + 2*150 = 501.
expect 0 "--dp 0.02" "$BIN/vres-gencase" -q "$CASE" --dp 0.02 -o "$T/d.h5"
check "--dp 0.02 gives 5000 fluid" [ "$(count_type "$T/d.h5" 0)" -eq 5000 ]
check "--dp 0.02 gives 501 walls" [ "$(count_type "$T/d.h5" 2)" -eq 501 ]
check "dp origin is dp" [ "$(param "$T/d.h5" dp.origin)" = '"dp"' ]
expect 0 "--set dp=0.02 is --dp" "$BIN/vres-gencase" -q "$CASE" --set dp=0.02 -o "$T/d2.h5"
check "--set dp=0.02 gives 5000 fluid" [ "$(count_type "$T/d2.h5" 0)" -eq 5000 ]
check "history records the command line" grep -q "vres-gencase -q .*--dp 0.02" <(h5dump -a /history "$T/d.h5")

mkdir "$T/none"
expect_err 1 "--set Nothing=1: the case has no variable" "unknown --set name refused" \
    "$BIN/vres-gencase" "$CASE" --set Nothing=1 -o "$T/none/x.h5"
nothing_in "$T/none" "nothing written for an unknown --set name"
expect_err 2 "must be greater than zero" "--dp 0 is a usage error" "$BIN/vres-gencase" "$CASE" --dp 0 -o "$T/none/x.h5"
nothing_in "$T/none" "nothing written for --dp 0"
