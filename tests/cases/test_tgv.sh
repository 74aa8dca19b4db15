#!/usr/bin/env bash
# cases/taylor_green2d: the case is a 1 m periodic square of L/dp particles a side, and its check
# measures the kinetic-energy decay exp(2 b t), b = -8 pi^2 nu / L^2 (refdata/
# taylor_green_2d_analytical.csv), here at a coarse dp (0.04, 625 particles) over the first
# 0.5 s (about 2 s of run). That short run tells the case's cure from the failure it fixes
# (cases/taylor_green2d/README.md): with the case's strong shifting (ShiftCoef -50) the
# decay-rate error is within the check's 0.10 (measured 0.055); with DualSPHysics' default
# shifting (ShiftCoef -2) the particles line up in the stagnation points' strain and the energy
# collapses (measured error 1.79), far outside it.
# Needs python3 with h5py and numpy (the check writes the vortex with pipelines/tgv_init.py).
source "$(dirname "$0")/../harness.sh"
if ! python3 -c 'import h5py, numpy' 2>/dev/null; then
    ok "# SKIP python3 with h5py and numpy not found"; exit 0
fi
DIR=$CASES/taylor_green2d
XML=$DIR/taylor_green2d_Def.xml

expect 0 "vres-gencase --check accepts the case" "$BIN/vres-gencase" -q --check "$XML"
expect 0 "generate it at dp 0.02" "$BIN/vres-gencase" -q "$XML" -o "$T/c.h5"
n=$(values /Domains/D0/Type "$T/c.h5" | awk '$1 == 0' | wc -l)
check "a (L/dp)^2 = 2500 particle fluid square, no walls ($n fluid of $(values /Domains/D0/Type "$T/c.h5" | wc -l))" \
    [ "$n" -eq 2500 ] && [ "$(values /Domains/D0/Type "$T/c.h5" | wc -l)" -eq 2500 ]

# the case as it stands: decay rate within the check's tolerance
expect 0 "check at dp 0.04 to t = 0.5 s passes (shifting -50)" \
    "$DIR/check" --threads 1 --dp 0.04 --tmax 0.5 -o "$T/good"
err=$(awk -F'\t' '$1 == "error" {print $2}' "$OUT")
check "its decay-rate error is below 0.10 ($err)" awk -v e="$err" 'BEGIN {exit !(e == e + 0 && e < 0.10)}'
check "the check reads the run again without rerunning it" \
    bash -c "'$DIR/check' '$T/good' | grep -q -x 'error	$err'"

# DualSPHysics' default shifting coefficient: the vortex collapses
expect 1 "check with ShiftCoef -2 fails (the lattice lines up)" \
    "$DIR/check" --threads 1 --dp 0.04 --tmax 0.5 --set ShiftCoef=-2 -o "$T/weak"
err=$(awk -F'\t' '$1 == "error" {print $2}' "$OUT")
check "its decay-rate error is above 0.5 ($err)" awk -v e="$err" 'BEGIN {exit !(e == e + 0 && e > 0.5)}'

expect 0 "check --help" "$DIR/check" --help
expect_err 2 "usage" "check: an unknown option is a usage error" "$DIR/check" --bogus
mkdir -p "$T/empty"
expect_err 1 "not a vres-run directory" "check: a directory without a run is refused" "$DIR/check" "$T/empty"
