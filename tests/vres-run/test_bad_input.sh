#!/usr/bin/env bash
# vres-run on input it must refuse (AddressSanitizer build): a missing store, no fluid, several
# domains or refinement boxes, parameters it does not implement, impossible or missing
# parameters, an unusable run directory. Each gets one clear message naming the problem,
# exit 1 (2 for usage errors), and nothing is written.
source "$(dirname "$0")/../harness.sh"
RUN=$ASAN/vres-run
GEN=$BIN/vres-gencase
TANK=$CASES/hydrostatic2d/hydrostatic2d_Def.xml

# refused CODE PATTERN NAME ARGS...: vres-run ARGS -o $T/out exits CODE with PATTERN on stderr
# and leaves no run directory behind.
refused() {
    local code=$1 pat=$2 name=$3; shift 3
    rm -rf "$T/out"
    expect_err "$code" "$pat" "$name" "$RUN" "$@" -o "$T/out"
    nothing_in "$T/out" "$name: nothing written"
}

"$GEN" -q "$TANK" -o "$T/tank.h5" || notok "gencase the tank"

refused 1 'nope\.h5.*(No such file|cannot open)' "missing store" "$T/nope.h5"
printf 'not hdf5\n' >"$T/junk.h5"
refused 1 'junk\.h5' "not a store" "$T/junk.h5"

# a tank without water
sed -e '/<setmkfluid/,/<\/drawbox>/d' -e 's/<hswl value="0" auto="true"/<hswl value="0.5" auto="false"/' \
    "$TANK" >"$T/dry.xml"
"$GEN" -q "$T/dry.xml" -o "$T/dry.h5" || notok "gencase the dry tank"
refused 1 'no fluid particles' "store without fluid" "$T/dry.h5"

# variable resolution: a case with a refinement box not yet split by vres-partition, and a
# store with three domains but no domain tree (tests/vres-run/test_vres_bad.sh has the rest)
"$GEN" -q --dp 0.02 "$CASES/dambreak2d/dambreak2d_Def.xml" -o "$T/vres.h5" || notok "gencase dambreak2d"
refused 1 'the case defines 1 refinement box \(<vres>\): split it into its domains first \(vres-partition' \
    "case with a <vres> box, not partitioned" "$T/vres.h5"
MAKER=$ROOT/$VRES_BUILD/tests/test_store
if VRES_TEST_STORE_OUT=$T/three.h5 "$MAKER" >/dev/null 2>&1; then
    refused 1 '3 domains but no domain tree' "store with three domains, no domain tree" "$T/three.h5"
else notok "make the three-domain store with $MAKER (build it: make $VRES_BUILD/tests/test_store)"; fi

# parameters not implemented yet: each named, never ignored
for kv in "XPeriodicIncZ=0.1:periodic along x with an increment 0.1 m along z \(XPeriodicIncZ\): not implemented yet" \
          "Shifting=4:Shifting=4 \(advanced shifting\) is not implemented yet" \
          "DensityDT=3:DensityDT=3 .* not implemented yet" \
          "DtFixed=0.0001:DtFixed=0.0001 .* not implemented yet"; do
    set=${kv%%:*}
    "$GEN" -q --set "$set" "$TANK" -o "$T/p.h5" || notok "gencase --set $set"
    refused 1 "${kv#*:}" "refuses $set" "$T/p.h5"
done
# CFL outside (0, 1]: vres-gencase refuses it, so the store is edited by the solver unit test
SETTER=$ROOT/$VRES_BUILD/tests/test_solver
if VRES_TEST_SET_IN=$T/tank.h5 VRES_TEST_SET_OUT=$T/cfl.h5 VRES_TEST_SET=cflnumber=2 "$SETTER" >/dev/null 2>&1; then
    refused 1 'cflnumber=2: must lie in \(0, 1\]' "CFL 2" "$T/cfl.h5"
else notok "make the CFL store with $SETTER (build it: make $VRES_BUILD/tests/test_solver)"; fi

# Visco and TimeMax missing: Visco has no option, TimeMax has --tmax
sed -e '/key="Visco"/d' -e '/key="TimeMax"/d' -e '/key="TimeOut"/d' "$TANK" >"$T/bare.xml"
"$GEN" -q "$T/bare.xml" -o "$T/bare.h5" 2>/dev/null || notok "gencase the case without Visco"
refused 1 'no parameter Visco' "missing Visco" "$T/bare.h5"
refused 1 'no TimeMax; give --tmax' "missing TimeMax" "$T/bare.h5"
refused 1 'no TimeOut; give --tout' "missing TimeOut" "$T/bare.h5"

# the run directory
touch "$T/file"
expect_err 1 'file/run.*Not a directory' "run directory under a file" "$RUN" --tmax 0.001 "$T/tank.h5" -o "$T/file/run"
check "nothing made under the file" [ -f "$T/file" ] && [ ! -s "$T/file" ]
mkdir -p "$T/used" && : >"$T/used/run.tsv"
expect_err 1 'already holds a run' "run directory holding a run" "$RUN" --tmax 0.001 "$T/tank.h5" -o "$T/used"
check "the earlier run is left alone" [ "$(ls -A "$T/used")" = run.tsv ]

# devices and usage
# the ASan build has no CUDA; the normal build says there is no GPU, or with a GPU that the
# CUDA solver is not written yet: refused either way, never a silent CPU run
refused 1 'no CUDA support' "--device cuda (ASan build: no CUDA)" --device cuda "$T/tank.h5"
rm -rf "$T/out"
expect_err 1 'no CUDA GPU answered|no CUDA support|CUDA solver not implemented yet' "--device cuda (normal build)" \
    "$BIN/vres-run" --device cuda "$T/tank.h5" -o "$T/out"
nothing_in "$T/out" "--device cuda (normal build): nothing written"
refused 2 'must be auto, cpu or cuda' "unknown device" --device gpu "$T/tank.h5"
refused 2 '--threads 0: must be at least 1' "zero threads" --threads 0 "$T/tank.h5"
expect_err 2 'missing -o RUNDIR' "no -o" "$RUN" "$T/tank.h5"
