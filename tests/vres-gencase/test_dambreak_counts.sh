#!/usr/bin/env bash
# vres-gencase draws DualSPHysics' 2D dam-break validation case (cases/dsph_dambreak2d: tank
# 4 m long with walls at the bottom, left and right, water column 1 m x 2 m, dp 0.01) with the
# particle counts DualSPHysics itself reports for it: 1001 boundary ("Fixed") and 20000 fluid
# particles, 21001 in all. Source: DualSPHysics run logs of CaseDambreakVal2D
# (examples/main/01_DamBreak) with DualSPHysics v5.0.140 and v5.4.355, quoted verbatim in
# github.com/vegetableno1/DualSPHysics-mcp, tests/conftest.py ("CaseNbound=1,001",
# "CaseNfluid=20,000", "Fixed....: 1,001 id:(0-1000)", "Fluid....: 20,000 id:(1001-21000)");
# DESIGN.md quotes the same 21,001. The counts are exact (a lattice count), so no tolerance.
# The ids run walls first (0..1000) then fluid (1001..21000), as in those logs.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/dsph_dambreak2d/dambreak2d_Def.xml

# count_type STORE TYPE: number of particles of the root domain with that type code.
count_type() {
    h5dump -y -w 1 -d /Domains/D0/Type "$1" | grep -E '^ *[0-9]+,?$' | tr -d ' ,' | grep -cx "$2"
}

expect 0 "dam break generated" "$BIN/vres-gencase" -q "$CASE" -o "$T/db.h5"
check "fluid particles: 20000 (DualSPHysics CaseNfluid)" [ "$(count_type "$T/db.h5" 0)" -eq 20000 ]
check "wall particles: 1001 (DualSPHysics CaseNbound)" [ "$(count_type "$T/db.h5" 2)" -eq 1001 ]
check "no other particle types" [ "$(h5dump -y -w 1 -d /Domains/D0/Type "$T/db.h5" | grep -cE '^ *[0-9]+,?$')" -eq 21001 ]
# ids: walls 0..1000 first, then fluid 1001..21000 (DualSPHysics' order)
types=$(h5dump -y -w 1 -d /Domains/D0/Type "$T/db.h5" | grep -E '^ *[0-9]+,?$' | tr -d ' ,')
check "walls first: particles 0..1000 are walls" [ "$(head -n 1001 <<<"$types" | sort -u)" = "2" ]
check "then fluid: particles 1001..21000 are fluid" [ "$(tail -n 20000 <<<"$types" | sort -u)" = "0" ]
ids=$(h5dump -y -w 1 -d /Domains/D0/Id "$T/db.h5" | grep -E '^ *[0-9]+,?$' | tr -d ' ,')
check "ids are 0..21000 in order" [ "$(sed -n '1p;1001p;1002p;$p' <<<"$ids" | tr '\n' ' ')" = "0 1000 1001 21000 " ]
