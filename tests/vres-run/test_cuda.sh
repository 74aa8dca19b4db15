#!/usr/bin/env bash
# vres-run's choice of device and the CUDA backend (DESIGN section 6). Without a GPU
# (cudaGetDeviceCount fails, error 35 on these machines): --device cuda is one clear error, exit
# 1, and no run directory is made; --device auto runs on the CPU and says so in one line. With a
# GPU: --device cuda runs the tank on it, names it in the module list, and keeps the particles
# (ids, fluid count and mass: no particle is lost or duplicated by the device's cell sort), and
# excludes what leaves the domain on the device (each particle kept or excluded, once), and runs
# two domains (the coupling's hooks) as the CPU does, within the ledger's bound and 1%, and moves
# a floating body as the CPU does. A
# build where nvcc was found has the CUDA backend in libvres: vres_backend_cuda_open defined by
# solver_cuda.cu's object, once (solver.c's stub is compiled only without it).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
LIB=$ROOT/$VRES_BUILD/libvres.a

"$BIN/vres-gencase" -q --dp 0.04 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5" || notok "gencase the tank"

# the Makefile builds the CUDA sources wherever it finds nvcc (on PATH or /usr/local/cuda)
if command -v nvcc >/dev/null 2>&1 || [ -x /usr/local/cuda/bin/nvcc ]; then
    nm -A --defined-only "$LIB" 2>/dev/null | grep -E ' T vres_backend_cuda_open$' >"$T/nm"
    check "libvres has the CUDA backend (vres_backend_cuda_open from solver_cuda.cu)" \
        grep -q -E 'solver_cuda\.cu\.o: *[0-9a-f]+ T vres_backend_cuda_open$' "$T/nm"
    check "libvres defines vres_backend_cuda_open once (no stub beside it)" [ "$(wc -l <"$T/nm")" -eq 1 ]
else
    ok "CUDA backend in libvres # SKIP no nvcc: the CUDA backend is not built"
fi

# a GPU is there when --device auto does not fall back to the CPU
expect 0 "--device auto runs" "$RUN" --device auto --tmax 0.01 --tout 0.01 "$T/tank.h5" -o "$T/auto"
if grep -q 'device auto: .*running on the CPU' "$ERR"; then
    check "--device auto without a GPU: one line says it runs on the CPU" \
        [ "$(grep -c -E 'no CUDA GPU answered|no CUDA support|running on the CPU' "$ERR")" -eq 1 ]
    check "--device auto without a GPU: the CPU backend in the module list" grep -q 'modules: .* cpu-openmp(' "$ERR"
    check "--device auto without a GPU: the run is written" [ -f "$T/auto/snap_00001.h5" ]
    expect_err 1 '^vres-run: --device cuda: (no CUDA GPU answered|this build has no CUDA support)' \
        "--device cuda without a GPU: refused" "$RUN" --device cuda --tmax 0.01 "$T/tank.h5" -o "$T/out"
    check "--device cuda without a GPU: one line of error" [ "$(wc -l <"$ERR")" -eq 1 ]
    check "--device cuda without a GPU: no run directory made" [ ! -e "$T/out" ]
else
    expect 0 "--device cuda with a GPU: runs the tank" "$RUN" --device cuda --tmax 0.01 --tout 0.01 "$T/tank.h5" -o "$T/gpu"
    check "--device cuda with a GPU: the CUDA backend in the module list" grep -q 'modules: .* cuda(' "$ERR"
    values /Domains/D0/Id "$T/tank.h5" | sort -n >"$T/id0"
    values /Domains/D0/Id "$T/gpu/snap_00001.h5" | sort -n >"$T/id1"
    check "--device cuda: the same particle ids after the run" cmp -s "$T/id0" "$T/id1"
    # the store's fluid count and mass, read with h5dump; run.tsv prints the mass to 9 digits
    read nf mf < <(paste <(values /Domains/D0/Type "$T/tank.h5") <(values /Domains/D0/Mass "$T/tank.h5") |
                   awk '$1 == 0 {n++; m += $2} END {printf "%d %.9g\n", n, m}')
    check "--device cuda: fluid count and mass kept ($nf particles, $mf kg)" \
        awk -F'\t' -v n="$nf" -v m="$mf" '!/^#/ && ($4 != n || ($6 - m) ^ 2 > (1e-8 * m) ^ 2) {exit 1}' \
        "$T/gpu/run.tsv"
    # the exclusion runs on the device (mark, select, gather with CUB): the upside-down tank
    # throws its water out; every particle is then in the last snapshot or in excluded.tsv, once
    "$BIN/vres-gencase" -q --dp 0.05 --set 'gravity=0,0,9.81' "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" \
        -o "$T/up.h5" || notok "gencase the upside-down tank"
    expect 0 "--device cuda: the upside-down tank runs" "$RUN" --device cuda --tmax 0.4 --tout 0.1 "$T/up.h5" -o "$T/gup"
    check "--device cuda: particles excluded" [ "$(grep -c -v '^#' "$T/gup/excluded.tsv")" -gt 10 ]
    cat <(values /Domains/D0/Id "$T/gup/snap_00004.h5") <(grep -v '^#' "$T/gup/excluded.tsv" | cut -f3) |
        sort -n >"$T/ids"
    values /Domains/D0/Id "$T/up.h5" | sort -n >"$T/ids0"
    check "--device cuda: each particle kept or excluded, once" cmp -s "$T/ids" "$T/ids0"
    # two domains (solver_cuda_couple.cu): the hydrostatic tank with its box, on the GPU and on
    # the CPU; the sums differ in order and rounding (no bit equality across devices), so the
    # GPU's run is held to what the CPU's shows: the ledger within its bound, and each
    # domain's fluid count at the end within 1% of the CPU's
    "$BIN/vres-gencase" -q --dp 0.04 "$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml" |
        "$BIN/vres-partition" -q - -o "$T/vres.h5" || notok "partition the hydrostatic tank with its box"
    expect 0 "--device cuda: two domains run" "$RUN" --device cuda --tmax 0.05 --tout 0.025 "$T/vres.h5" -o "$T/gv"
    check "--device cuda, two domains: the CUDA backend" grep -q 'modules: .* cuda(' "$ERR"
    check "--device cuda, two domains: one line says its coupling is new to a GPU" \
        [ "$(grep -c 'coupling of variable resolution: the CUDA backend.s code for them has not been run on a GPU before' "$ERR")" -eq 1 ]
    expect 0 "--device cpu: the same two domains" "$RUN" --device cpu --tmax 0.05 --tout 0.025 "$T/vres.h5" -o "$T/cv"
    ledger_within_bound "$T/gv/snap_00002.h5" "$T/gv" 6
    for k in 0 1; do
        read ng nc < <(paste <(grep -v '^#' "$T/gv/ledger.tsv" | awk -F'\t' -v k=$k '$3 == k' | tail -1 | cut -f5) \
                             <(grep -v '^#' "$T/cv/ledger.tsv" | awk -F'\t' -v k=$k '$3 == k' | tail -1 | cut -f5))
        check "--device cuda, two domains: D$k's fluid count $ng within 1% of the CPU's $nc" \
            awk -v a="$ng" -v b="$nc" 'BEGIN {exit !(b > 0 && (a - b) ^ 2 <= (0.01 * b) ^ 2)}'
    done
    # a floating body (cu_body_forces): the box of cases/floating_box2d released off its
    # equilibrium, 0.2 s on each device; its heave then is a few cm, and the two runs' centres
    # must agree within 2 mm (a tenth of dp: different rounding, the same motion)
    "$BIN/vres-gencase" -q --dp 0.04 "$CASES/floating_box2d/floating_box2d_Def.xml" -o "$T/box.h5" ||
        notok "gencase the floating box"
    expect 0 "--device cuda: the floating box runs" "$RUN" --device cuda --tmax 0.2 --tout 0.2 "$T/box.h5" -o "$T/gb"
    check "--device cuda, floating box: one line says its code is new to a GPU" \
        [ "$(grep -c 'floating bodies: the CUDA backend.s code for them has not been run on a GPU before' "$ERR")" -eq 1 ]
    expect 0 "--device cpu: the same floating box" "$RUN" --device cpu --tmax 0.2 --tout 0.2 "$T/box.h5" -o "$T/cb"
    zg=$(attr /Bodies/B0/center "$T/gb/snap_00001.h5" | sed -n 3p)
    zc=$(attr /Bodies/B0/center "$T/cb/snap_00001.h5" | sed -n 3p)
    z0=$(attr /Bodies/B0/center "$T/box.h5" | sed -n 3p)
    check "--device cuda, floating box: moved ($z0 -> $zg m) as on the CPU ($zc m) within 2 mm" \
        awk -v g="$zg" -v c="$zc" -v z="$z0" 'BEGIN {exit !((g - c) ^ 2 <= 0.002 ^ 2 && (c - z) ^ 2 > 0.002 ^ 2)}'
fi
