#!/usr/bin/env bash
# vres-run with inlet/outlet zones (cases/channel_inout2d: an inlet with fixed velocity and
# density, an outlet extrapolating both from ghost nodes): the stream starts at 0.8 m/s against
# the inlet's 1 m/s, so the zones work through a transient: the inlet creates particles at its
# back and hands them to the fluid, the outlet converts the fluid that enters it and deletes
# its particles past its back, each event in ledger.tsv's zone lines, whose books balance; a
# restart from a snapshot continues bit for bit (the zones' segment masses are in /Interfaces);
# the case's check passes on a short coarse run. Needs python3 with h5py (init_uniform.py).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
PY=python3
$PY -c 'import h5py, numpy' 2>/dev/null || PY=/usr/bin/python3
if ! $PY -c 'import h5py, numpy' 2>/dev/null; then
    ok "# SKIP python3 with h5py and numpy not found"; exit 0
fi
CASE=$CASES/channel_inout2d/channel_inout2d_Def.xml
expect 0 "vres-gencase channel_inout2d" "$BIN/vres-gencase" -q "$CASE" -o "$T/case.h5"
expect 0 "u = 0.8 m/s on the fluid" $PY "$CASES/channel_uniform_vres2d/init_uniform.py" --U 0.8 "$T/case.h5"
expect 0 "run to 0.4 s, output every 0.1 s" "$RUN" --threads 1 --tmax 0.4 --tout 0.1 "$T/case.h5" -o "$T/a"
check "the module list names the zones" grep -q 'modules: .* inout(2 zones)' "$ERR"
L=$T/a/ledger.tsv
# zcol ZONE COLUMN: ledger.tsv's value of COLUMN (1-based, its header) on ZONE's last line
zcol() { awk -F'\t' -v z="$1" -v c="$2" '$3 == z {v = $c} END {print v + 0}' "$L"; }
check "ledger.tsv has 5 lines per zone (outputs 0 to 4)" \
    [ "$(grep -c -P '\tZ1\t' "$L")" -eq 5 -a "$(grep -c -P '\tZ2\t' "$L")" -eq 5 ]
check "the inlet filled its 4 x 10 lattice and created more at its back ($(zcol Z1 8))" [ "$(zcol Z1 8)" -gt 40 ]
check "the inlet's particles became fluid ($(zcol Z1 10))" [ "$(zcol Z1 10)" -gt 0 ]
check "fluid entered the outlet and was converted ($(zcol Z2 11))" [ "$(zcol Z2 11)" -gt 0 ]
check "the outlet deleted particles past its back ($(zcol Z2 12))" [ "$(zcol Z2 12)" -gt 0 ]
check "the outlet created nothing after its fill ($(zcol Z2 8))" [ "$(zcol Z2 8)" -eq 40 ]
drift=$(awk -F'\t' '!/^#/ {d = $20; if (d < 0) d = -d; if (d > D) D = d} END {print D + 0}' "$L")
check "the books balance: fluid mass = start + what the zones gave it (largest drift $drift)" \
    awk -v d="$drift" 'BEGIN {exit !(d <= 1e-12)}'
nin=$(values /Domains/D0/Type "$T/a/snap_00004.h5" | grep -c -x 5)
check "snap_00004.h5 holds at least the zones' two lattices of 40 inlet particles ($nin)" [ "$nin" -ge 80 ]
check "its /Interfaces hold the zones' segments (zone 1 and 2)" \
    [ "$(h5dump -a /Interfaces/I0/zone "$T/a/snap_00004.h5" | grep -c '(0): 1')" -eq 1 -a \
      "$(h5dump -a /Interfaces/I1/zone "$T/a/snap_00004.h5" | grep -c '(0): 2')" -eq 1 ]
rmax=$(awk -F'\t' '!/^#/ {print $9}' "$T/a/run.tsv" | sort -g | tail -1)
check "the velocity step raised the density ($rmax kg/m^3 > 1000)" awk -v r="$rmax" 'BEGIN {exit !(r > 1000.5)}'

# restart from snapshot 2 in a copy of the run directory: snapshots 3 and 4 and ledger.tsv equal
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00002.h5" "$RUN" -q --threads 1 --restart "$T/b/snap_00002.h5"
for k in 3 4; do
    f=$(printf 'snap_%05d.h5' $k) bad=
    for ds in Position Velocity Density Pressure Mass Type Mk Id; do
        h5diff -q "$T/a/$f" "$T/b/$f" "/Domains/D0/$ds" "/Domains/D0/$ds" >/dev/null || bad="$bad $ds"
    done
    for i in I0 I1; do
        h5diff -q "$T/a/$f" "$T/b/$f" "/Interfaces/$i/Mass" "/Interfaces/$i/Mass" >/dev/null || bad="$bad $i/Mass"
    done
    check "$f after the restart: particles and segment masses bit for bit${bad:+ (differ:$bad)}" [ -z "$bad" ]
done
check "ledger.tsv after the restart: the same file" cmp -s "$T/a/ledger.tsv" "$T/b/ledger.tsv"

# --device cuda where no GPU answers: refused, nothing written; where one does, the zones run on
# it (code no GPU had run when it was written) with one warning saying so
run "$RUN" --device cuda --tmax 0.05 "$T/case.h5" -o "$T/cu"
if grep -q -E 'no CUDA GPU answered|no CUDA support' "$ERR"; then
    check "--device cuda, no GPU: exit 1" [ "$STATUS" -eq 1 ]
    check "--device cuda, no GPU: nothing written" [ ! -e "$T/cu" ]
else
    check "--device cuda with a GPU: the zones run there" [ "$STATUS" -eq 0 ]
    check "--device cuda with a GPU: one warning that its zone code is new to a GPU" \
        [ "$(grep -c 'inlet/outlet zones: the CUDA backend.s code for them has not been run on a GPU before' "$ERR")" -eq 1 ]
fi

# the case's check, reduced: dp 0.05 m (8 rows), one flow-through time (2 s)
expect 0 "channel_inout2d/check --dp 0.05 --tmax 2" "$CASES/channel_inout2d/check" --threads 1 --dp 0.05 --tmax 2 -o "$T/chk"
check "it reports a pass" grep -q -P '^verdict\tpass$' "$OUT"

# a velocity given as a time series (imposevelocity mode 1, <velocitytimes>): the inlet's
# particles carry its value at the snapshot's time, linear between the points (0.8 m/s at
# t = 0, 1.2 m/s at t = 0.4 s: 1 m/s at 0.2 s)
sed 's|<velocity v="1" units_comment="m/s" />|<velocitytimes><timevalue time="0" v="0.8" /><timevalue time="0.4" v="1.2" /></velocitytimes>|; s|<imposevelocity mode="0">|<imposevelocity mode="1">|' \
    "$CASE" >"$T/ramp.xml"
expect 0 "vres-gencase with the inlet's velocity ramped" "$BIN/vres-gencase" -q "$T/ramp.xml" -o "$T/ramp.h5"
expect 0 "u = 0.8 m/s on the fluid" $PY "$CASES/channel_uniform_vres2d/init_uniform.py" --U 0.8 "$T/ramp.h5"
expect 0 "run to 0.2 s" "$RUN" -q --threads 1 --tmax 0.2 --tout 0.2 "$T/ramp.h5" -o "$T/r"
f=$T/r/snap_00001.h5
t=$(h5dump -a /time "$f" | sed -n 's/^ *(0): //p')
# the inlet's particles (type 5, x < 0): their x velocities, one value when the zone imposes one
vx=$(paste <(values /Domains/D0/Type "$f") <(values /Domains/D0/Position "$f" | paste - - -) \
           <(values /Domains/D0/Velocity "$f" | paste - - -) | awk '$1 == 5 && $2 < 0 {printf "%.6f\n", $5}' | sort -u)
want=$(awk -v t="$t" 'BEGIN {printf "%.6f\n", 0.8 + 0.4 * t / 0.4}')
check "the inlet's particles all move at the series' value at t = $t s ($want m/s: $vx)" [ "$vx" = "$want" ]
