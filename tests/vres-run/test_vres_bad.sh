#!/usr/bin/env bash
# vres-run on variable-resolution input it must refuse (AddressSanitizer build): several
# domains without their domain tree (no region boxes, region boxes in some domains only, no
# interfaces), a corrupt /Interfaces (a count that is not the datasets' rows, a NaN position, a
# non-unit normal, domains that are not parent and child), a tracking box without its motion or
# following no moving body, a restart from a partition store (no snapshot), Verlet or the cubic
# spline kernel with two domains, and --device cuda with two domains where no GPU answers. Each gets one message naming the object, exit
# 1, and nothing in the run directory. The stores are vres-partition's of cases/hydrostatic_vres2d, edited with h5py (so
# that vres's own writer, which checks what it writes, is bypassed) or with the parameter
# setter of tests/lib/test_solver.c.
source "$(dirname "$0")/../harness.sh"
RUN=$ASAN/vres-run
CASE=$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml

# refused CODE PATTERN NAME ARGS...: vres-run ARGS -o $T/out exits CODE with PATTERN on stderr,
# in one message (one line), and leaves no run directory content behind.
refused() {
    local code=$1 pat=$2 name=$3; shift 3
    rm -rf "$T/out"
    expect_err "$code" "$pat" "$name" "$RUN" "$@" -o "$T/out"
    check "$name: one message" [ "$(grep -c '^vres-run: ' "$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
}

"$BIN/vres-gencase" -q "$CASE" | "$BIN/vres-partition" -q - -o "$T/parts.h5" || notok "partition hydrostatic_vres2d"
check "the partition has two domains and two interfaces" \
    [ "$(h5ls "$T/parts.h5/Domains" | wc -l)" -eq 2 -a "$(h5ls "$T/parts.h5/Interfaces" | wc -l)" -eq 2 ]
# the good store runs (a few steps), so that each refusal below is the edit's doing
rm -rf "$T/good"
expect 0 "the unedited store runs (0.001 s)" "$RUN" -q --tmax 0.001 "$T/parts.h5" -o "$T/good"

# ---- no domain tree, a corrupt /Interfaces: edited with h5py
PY=
for p in python3 /usr/bin/python3; do
    if "$p" -c 'import h5py, numpy' 2>/dev/null; then PY=$p; break; fi
done
# edit NAME PYTHON: a copy of the store as $T/NAME.h5, with the Python statements run on it
# (f: the file open for writing, np: numpy)
edit() {
    cp "$T/parts.h5" "$T/$1.h5"
    "$PY" -c "import h5py, numpy as np
f = h5py.File('$T/$1.h5', 'r+')
$2
f.close()"
}
REGION="for d in f['Domains'].values():
    for a in ('buffer_min', 'buffer_max', 'hole_min', 'hole_max', 'inner_min', 'inner_max'):
        del d.attrs[a]"
if [ -z "$PY" ]; then
    ok "# SKIP python3 with h5py and numpy not found: no edited stores"
else
    edit notree "$REGION"
    refused 1 'the store has 2 domains but no domain tree \(regions, interfaces\)' "no region boxes" "$T/notree.h5"
    edit halftree "d = f['Domains/D1']
for a in ('buffer_min', 'buffer_max', 'hole_min', 'hole_max', 'inner_min', 'inner_max'):
    del d.attrs[a]"
    refused 1 'halftree\.h5: /Domains/D1: no region boxes .* although /Domains/D0 has them' \
        "region boxes in D0 only" "$T/halftree.h5"
    edit noiface "del f['Interfaces']"
    refused 1 'the store has 2 domains and their regions but no /Interfaces' "no /Interfaces" "$T/noiface.h5"

    # the interface I0, its segment count one more than its datasets' rows
    edit count "a = f['Interfaces/I0'].attrs
a['count'] = np.uint64(int(a['count']) + 1)"
    refused 1 'count\.h5: /Interfaces/I0/[A-Za-z]+: [0-9]+ rows but the interface.s count is [0-9]+' \
        "interface count not its rows" "$T/count.h5"
    edit nanpos "f['Interfaces/I1/Position'][3, 0] = np.nan"
    refused 1 'nanpos\.h5: /Interfaces/I1/Position: segment 3 holds a non-finite value' \
        "NaN interface position" "$T/nanpos.h5"
    edit normal "f['Interfaces/I0/Normal'][2] = [0.5, 0.0, 0.0]"
    refused 1 'normal\.h5: /Interfaces/I0/Normal: segment 2 is not a unit vector' "non-unit interface normal" \
        "$T/normal.h5"
    # a box that follows a body: without its motion (the track_* attributes of vres-store(5)), and
    # with it but following a mkbound that no body with a <motion> has (the fixed walls' 0)
    edit tracking "f['Domains/D1'].attrs['tracking_mk'] = np.int32(0)"
    refused 1 "tracking\.h5: /Domains/D1: attribute 'track_rotation' missing" "a tracking box without its motion" \
        "$T/tracking.h5"
    edit tracking0 "a = f['Domains/D1'].attrs
a['tracking_mk'] = np.int32(0)
a['track_rotation'] = np.eye(3).ravel()
for n in ('track_shift', 'track_velocity', 'track_omega', 'track_center'):
    a[n] = np.zeros(3)
a['track_until'] = 10.0"
    refused 1 'domain D1 follows mkbound 0 \(<tracking>\), which no moving or floating body has' \
        "a box that follows no moving body" "$T/tracking0.h5"
    edit donor "a = f['Interfaces/I0'].attrs
a['donor'] = a['receiving']"
    refused 1 'donor\.h5: /Interfaces/I0: domains ([0-9]+) and \1 are not parent and child' \
        "interface between a domain and itself" "$T/donor.h5"
fi

# ---- a restart needs a snapshot of vres-run, not vres-partition's store
refused 1 'no parameter run_t0: --restart needs a snapshot or checkpoint.h5 written by vres-run' \
    "restart from a partition store" --restart "$T/parts.h5"

# ---- Verlet: the coupling runs the Symplectic scheme only (vres-partition refuses a Verlet case,
# so the partition store's parameter is set afterwards)
SETTER=$ROOT/$VRES_BUILD/tests/test_solver
if VRES_TEST_SET_IN=$T/parts.h5 VRES_TEST_SET_OUT=$T/verlet.h5 VRES_TEST_SET=StepAlgorithm=1 "$SETTER" >/dev/null 2>&1
then
    check "the Verlet store keeps its two domains" [ "$(h5ls "$T/verlet.h5/Domains" | wc -l)" -eq 2 ]
    refused 1 'StepAlgorithm=1 \(Verlet\) with 2 domains: .*Symplectic scheme only' "Verlet with two domains" \
        "$T/verlet.h5"
else notok "make the Verlet store with $SETTER (build it: make $VRES_BUILD/tests/test_solver)"; fi

# ---- the cubic spline: the coupling interpolates with the Wendland kernel (vres-partition refuses
# a Kernel=1 case, so the partition store's parameter is set afterwards)
if VRES_TEST_SET_IN=$T/parts.h5 VRES_TEST_SET_OUT=$T/cubic.h5 VRES_TEST_SET=Kernel=1 "$SETTER" >/dev/null 2>&1
then
    refused 1 'Kernel=1 \(cubic spline\) in a store of 2 domains: variable resolution runs with the Wendland kernel only' \
        "cubic spline with two domains" "$T/cubic.h5"
else notok "make the cubic-spline store with $SETTER (build it: make $VRES_BUILD/tests/test_solver)"; fi

# ---- CUDA: the ASan build has none, and is refused; the normal build finds no GPU here, which is
# refused with nothing written; where a GPU answers, --device cuda runs two domains (test_cuda.sh
# checks that run against the CPU's), never a silent CPU run.
refused 1 'no CUDA support' "--device cuda with two domains (ASan build)" --device cuda "$T/parts.h5"
rm -rf "$T/out"
run "$BIN/vres-run" --device cuda --tmax 0.001 "$T/parts.h5" -o "$T/out"
if grep -q -E 'no CUDA GPU answered|no CUDA support' "$ERR"; then
    check "--device cuda with two domains, no GPU (normal build): exit 1" [ "$STATUS" -eq 1 ]
    nothing_in "$T/out" "--device cuda with two domains, no GPU (normal build): nothing written"
else
    check "--device cuda with two domains, a GPU answers: run on it" grep -q 'modules: .* cuda(' "$ERR"
fi
