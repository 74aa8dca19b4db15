#!/usr/bin/env bash
# pipelines/mutation.sh - the mutation check (issue 10, item 3): does the test suite fail when
# the solver is wrong? In a scratch clone of the committed tree (under /tmp, never the working
# tree) each mutant below puts one deliberate fault into the solver, builds, and runs
# `make check` stopping at the first failing test (VRES_FAIL_FAST=1, see tests/run); a mutant
# that survives (make check passes) is a hole in the suite. The tests that catch a mutant pass
# on the unmutated tree (every unit test runs there first; a catching script runs there last).
#
#   pipelines/mutation.sh [-o REPORT] [MUTANT...]     (default: every mutant; names below)
#
# The report (default pipelines/reports/mutation.txt) has one row per mutant: name, the test
# that caught it (or SURVIVED), its first failing check, build and test wall seconds. CPU
# heavy (a build per mutant, ccache when installed keeps it to the files the fault touches):
# it runs under nice -n 10, make -j2, one build at a time; the report is written as it goes.
# Exit 0 when every mutant was caught and the unit tests (and catching scripts) pass unmutated.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
REPORT=$ROOT/pipelines/reports/mutation.txt
if [ "${1:-}" = -o ]; then REPORT=$(realpath -m "$2"); shift 2; fi

# name | file | text | replacement | what the fault is. Every occurrence of text is replaced (at
# least one must be there: a mutant that changes nothing is an error of this script).
MUTANTS=(
    "pressure-sign|kernels/sph.h|(pa + |(pa - |pressure term: p_a - p_b instead of p_a + p_b (both interaction loops)"
    "no-density-diffusion|kernels/sph.h|diff += |diff += 0.0 * |density diffusion term dropped (both interaction loops)"
    "kernel-constant|kernels/wendland.h|7.0 / (4.0 * VRES_WENDLAND_PI|7.0 / (5.0 * VRES_WENDLAND_PI|Wendland C2 2D normalisation 7/(5 pi h^2) instead of 7/(4 pi h^2)"
    "cell-search-off-by-one|kernels/cells.h|for (int ox = -1; ox <= 1; ox++) {
                int kx|for (int ox = -1; ox < 1; ox++) {
                int kx|cell-wise search (vres_cells_rows, 2D and 3D) skips the column of cells to the right"
    "eos-offset|kernels/eos.h| - 1.0);|);|Tait equation without its -1: p = B (rho/rho0)^gamma (both forms, by products and by pow)"
    "coupling-interp-axis|kernels/interp_liu.h|e[i] = d[ax[i - 1]] * inv_h|e[i] = d[ax[0]] * inv_h|coupling's corrected kernel: every gradient column takes the x offset"
    "corrector-first-order|kernels/sph.h|pos0[3 * i + k] + 0.5 * dt * (vel0[3 * i + k] + v)|pos0[3 * i + k] + dt * v|Symplectic corrector moves particles with the end velocity only (first order)"
)
want=("$@")

S=$(mktemp -d /tmp/vres-mutation.XXXXXX)
trap 'rm -rf "$S"' EXIT
REV=$(git -C "$ROOT" rev-parse HEAD)
git clone -q "$ROOT" "$S/tree" && git -C "$S/tree" checkout -q --detach "$REV" || { echo "mutation.sh: cannot clone $ROOT" >&2; exit 1; }
cd "$S/tree" || exit 1
mk=(make -j2)
if command -v ccache >/dev/null; then
    # -g puts the directory into the objects, so ccache would hash it and miss for every fresh
    # scratch directory (the unmutated build took 1826 s so): the objects' directory is not needed
    export CCACHE_NOHASHDIR=1
    mk+=(CC="ccache gcc" CXX="ccache g++")
    nv=$(command -v nvcc || { [ -x /usr/local/cuda/bin/nvcc ] && echo /usr/local/cuda/bin/nvcc; })
    if [ -n "$nv" ]; then # nvcc through ccache, in a CUDA_HOME of links so the Makefile finds lib64
        cuda=${nv%/bin/nvcc}
        mkdir -p "$S/cuda/bin" && ln -s "$cuda/lib64" "$S/cuda/lib64" && ln -s "$cuda/include" "$S/cuda/include"
        printf '#!/bin/sh\nexec ccache %s "$@"\n' "$nv" >"$S/cuda/bin/nvcc" && chmod +x "$S/cuda/bin/nvcc"
        mk+=(NVCC="$S/cuda/bin/nvcc")
    fi
fi

# everything make check needs before it tests: the tools, their AddressSanitizer build, the unit tests
targets=(all asan $(for f in tests/lib/test_*.c; do t=${f#tests/lib/}; echo "build/tests/${t%.c}"; done))

# apply FILE TEXT NEW: replace every TEXT in FILE by NEW; prints how many, fails on none
apply() {
    python3 - "$@" <<'EOF'
import sys
path, old, new = sys.argv[1:4]
s = open(path).read()
n = s.count(old)
if n == 0:
    sys.exit(f"mutation.sh: {path}: text not found: {old!r}")
open(path, "w").write(s.replace(old, new))
print(n)
EOF
}

# A mutant's build recompiles what the fault touches for the CPU: the tools and unit tests that
# make check runs. The CUDA objects (no GPU runs them here) and the AddressSanitizer tools (the
# bad-input tests) keep the unmutated code (make -o), which halves a mutant's build on a loaded
# machine (a full one took 1116 s) and can only hide a fault, never make a test fail for it.
# MUTATION_FULL=1 rebuilds those too (a survivor should be tried so).
keep=()
if [ "${MUTATION_FULL:-0}" != 1 ]; then
    for f in lib/*.cu; do [ -e "$f" ] && keep+=(-o "build/obj/$(basename "$f").o"); done
    for f in lib/*.c lib/*.cc; do b=$(basename "$f"); keep+=(-o "build/asan/${b%.*}.o"); done
fi

echo "mutation.sh: building the unmutated tree at $REV in $S/tree" >&2
t0=$SECONDS
nice -n 10 "${mk[@]}" "${targets[@]}" >"$S/build0.log" 2>&1 || { tail -20 "$S/build0.log" >&2; echo "mutation.sh: the unmutated tree does not build" >&2; exit 1; }
base_s=$((SECONDS - t0))
# the unit tests on the unmutated tree (each must pass, so that a mutant's failure is the fault's)
base=()
for t in build/tests/test_*; do
    out=$(CK_FORK=yes CK_DEFAULT_TIMEOUT=60 nice -n 10 "$t" 2>&1) && v=passes || v=FAILS
    base+=("$t	$v	$(grep -E '^[0-9]+%: Checks' <<<"$out" | tail -1)")
done

mkdir -p "$(dirname "$REPORT")"
{
    echo "# mutation check of vres at $REV ($(date -u +%Y-%m-%d), $(nproc) cores, under nice -n 10 while other jobs ran):"
    echo "#   pipelines/mutation.sh${want[*]:+ ${want[*]}}   (MUTATION_FULL=${MUTATION_FULL:-0})"
    echo "# each mutant: one fault in a scratch clone, 'make -j2 all' and the unit tests (ccache: build_s is the"
    echo "# files the fault touches and the links; CUDA and AddressSanitizer objects kept unmutated unless"
    echo "# MUTATION_FULL=1), then 'VRES_FAIL_FAST=1 make check' (test_s: until the first failing test)."
    echo "# unmutated tree built in ${base_s} s. caught_by: the first test that failed; first_failure: its first failing line."
    echo "# unit tests on the unmutated tree (each must pass):"
    printf '#   %s\n' "${base[@]}"
    printf 'mutant\tcaught_by\tbuild_s\ttest_s\tfault\tfirst_failure\n'
} >"$REPORT"

catchers=() survived=0 nrun=0
for m in "${MUTANTS[@]}"; do
    IFS='|' read -r -d '' name file text new what <<<"$m"
    what=${what%$'\n'}
    if [ ${#want[@]} -gt 0 ] && [[ " ${want[*]} " != *" $name "* ]]; then continue; fi
    nrun=$((nrun + 1))
    n=$(apply "$file" "$text" "$new") || exit 1
    echo "mutation.sh: $name ($n place(s) in $file): $what" >&2
    t0=$SECONDS
    nice -n 10 "${mk[@]}" "${keep[@]}" "${targets[@]}" >"$S/build.log" 2>&1
    brc=$? build_s=$((SECONDS - t0))
    t0=$SECONDS
    if [ $brc -eq 0 ]; then VRES_FAIL_FAST=1 nice -n 10 "${mk[@]}" "${keep[@]}" check >"$S/check.log" 2>&1; crc=$?; else crc=2; fi
    test_s=$((SECONDS - t0))
    if [ $brc -ne 0 ]; then caught="(does not build)"; first=$(grep -m1 -E 'error' "$S/build.log")
    elif [ $crc -eq 0 ]; then caught=SURVIVED first="make check passed"; survived=$((survived + 1))
    else
        caught=$(sed -n 's/^failed: //p' "$S/check.log" | awk '{print $1}')
        [ -n "$caught" ] || caught="(make check exited $crc)"
        first=$(grep -m1 -E "^$caught: .*(not ok|:[0-9]+:F:|:[0-9]+:E:|exited)" "$S/check.log" | cut -c1-240)
        [ -n "$first" ] || first=$(grep -m1 -E "^$caught: " "$S/check.log" | cut -c1-240)
        catchers+=("$caught")
    fi
    echo "mutation.sh: $name: $caught (build ${build_s} s, tests ${test_s} s)" >&2
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$caught" "$build_s" "$test_s" "$what" "$first" >>"$REPORT"
    git checkout -q -- "$file"
done
[ "$nrun" -gt 0 ] || { echo "mutation.sh: no mutant named ${want[*]}" >&2; exit 2; }

# a catching script (not a unit test, run above) runs again on the unmutated tree
scripts=$(printf '%s\n' "${catchers[@]}" | grep -E '^tests/.*\.sh$' | sort -u)
if [ -n "$scripts" ]; then
    nice -n 10 "${mk[@]}" "${keep[@]}" "${targets[@]}" >"$S/build0.log" 2>&1 || { echo "mutation.sh: rebuilding the unmutated tree failed" >&2; exit 1; }
    for t in $scripts; do
        out=$(nice -n 10 bash "$t" 2>&1) && ! grep -q '^not ok ' <<<"$out" && v=passes || v=FAILS
        base+=("$t	$v	$(grep -c '^ok ' <<<"$out") ok, $(grep -c '^not ok ' <<<"$out") not ok")
    done
fi
{
    echo "#"
    echo "# on the unmutated tree (each must pass):"
    printf '#   %s\n' "${base[@]}" | grep '\.sh	' 
    echo "# $((nrun - survived)) of $nrun mutants caught, $survived survived."
} >>"$REPORT"
cat "$REPORT"
fails=$(printf '%s\n' "${base[@]}" | grep -c '	FAILS')
[ "$survived" -eq 0 ] && [ "$fails" -eq 0 ]
