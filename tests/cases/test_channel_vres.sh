# cases/channel_vres2d and cases/channel_uniform_vres2d: the coupled periodic channel through
# vres-gencase | vres-partition | vres-run at a coarse dp (0.1 m, box at 0.05 m), short runs
# (3 and 5 s): the partition of a box that reaches the periodic edges (the slab of the
# uniform case) fills the period with the child's fluid; the runs start, mass crosses both
# faces, and the check's independent counts (channel_analyse.py: particle ids between
# snapshots, from the root's side and the child's) match the ledger: its books exactly, the
# two sides of each face to one root column, the created and deleted masses to one band.
# Needs python3 with h5py and numpy.
source "$(dirname "$0")/../harness.sh"
PY=python3
$PY -c 'import h5py, numpy' 2>/dev/null || PY=/usr/bin/python3
if ! $PY -c 'import h5py, numpy' 2>/dev/null; then
    ok "# SKIP python3 with h5py and numpy not found"; exit 0
fi
export OMP_WAIT_POLICY=passive
key() { awk -F'\t' -v k="$1" '$1 == k {print $2}' "$2"; }

# the slab of the uniform case: D1's fluid region spans the period z in [0, 1] m
expect 0 "vres-gencase channel_uniform_vres2d at dp 0.1" "$BIN/vres-gencase" -q --dp 0.1 \
    "$CASES/channel_uniform_vres2d/channel_uniform_vres2d_Def.xml" -o "$T/u.h5"
expect 0 "vres-partition of the periodic box" "$BIN/vres-partition" -q "$T/u.h5" -o "$T/up.h5"
box=$(for a in box_min box_max; do h5dump -a "/Domains/D1/$a" "$T/up.h5" | awk '/\(0\):/ {sub(/.*\(0\): */, ""); print}'; done | paste -s -d ' ')
check "D1's box reaches the periodic edges: [1, 2] x [0, 1] m ($box)" [ "$box" = "1, 0, 0 2, 0, 1" ]
nf1=$(values /Domains/D1/Type "$T/up.h5" | grep -c -x 0)
check "D1 has 20 x 20 fluid particles at dp 0.05, none of its rows at the seam left to a buffer ($nf1)" [ "$nf1" -eq 400 ]

# the uniform stream, 0.3 s: exact, and 300 kg through each face
expect 0 "channel_uniform_vres2d/check --vres at dp 0.1 to 0.3 s" \
    "$CASES/channel_uniform_vres2d/check" --threads 1 --dp 0.1 --tmax 0.3 -o "$T/uni"
cp "$OUT" "$T/uni.out"
for k in cross_in_coarse_kg cross_in_fine_kg cross_out_fine_kg cross_out_coarse_kg created_D1_kg deleted_D1_kg created_D0_kg deleted_D0_kg; do
    v=$(key $k "$T/uni.out")
    check "uniform: $k = 300 (rho0 U t L: $v)" awk -v v="$v" 'BEGIN {exit !(v == 300)}'
done
check "uniform: the ledger's books are the snapshots' ($(key ledger_books "$T/uni.out"))" [ "$(key ledger_books "$T/uni.out")" = 0 ]
check "uniform: the stream stays uniform in the box (error $(key error "$T/uni.out"))" \
    awk -v e="$(key error "$T/uni.out")" 'BEGIN {exit !(e == e + 0 && e <= 1e-6)}'

# Poiseuille start-up, 1 s: mass crosses, both sides and the ledger agree
expect 0 "channel_vres2d/check --vres at dp 0.1 to 1 s" "$CASES/channel_vres2d/check" --threads 1 --dp 0.1 --tmax 1 -o "$T/poi"
cp "$OUT" "$T/poi.out"
cin=$(key cross_in_coarse_kg "$T/poi.out")
check "Poiseuille: mass crossed into the box ($cin kg, at least two root columns of 100 kg)" awk -v v="$cin" 'BEGIN {exit !(v >= 200)}'
check "Poiseuille: the two sides of each face agree to one root column ($(key cross_mismatch "$T/poi.out"))" \
    awk -v v="$(key cross_mismatch "$T/poi.out")" 'BEGIN {exit !(v == v + 0 && v <= 1)}'
check "Poiseuille: created and deleted follow the crossing to one band ($(key ledger_vs_crossing "$T/poi.out"))" \
    awk -v v="$(key ledger_vs_crossing "$T/poi.out")" 'BEGIN {exit !(v == v + 0 && v <= 1)}'
check "Poiseuille: the ledger's books are the snapshots' ($(key ledger_books "$T/poi.out"))" [ "$(key ledger_books "$T/poi.out")" = 0 ]
check "Poiseuille: the check passes" grep -q -x 'verdict	pass' "$T/poi.out"
