#!/usr/bin/env bash
# pipelines/mutation.sh - the mutation check (issue 10, item 3): does the test suite fail when
# the solver is wrong? In a scratch clone of the committed tree (under /tmp, never the working
# tree) each mutant below puts one deliberate fault into the solver, builds, and runs
# `make check` stopping at the first failing test (VRES_FAIL_FAST=1, see tests/run); a mutant
# that survives (make check passes) is a hole in the suite. At the end the tests that caught a
# mutant run again on the unmutated tree, where they must pass (so they failed for the fault).
#
#   pipelines/mutation.sh [-o REPORT] [MUTANT...]     (default: every mutant; names below)
#
# The report (default pipelines/reports/mutation.txt) has one row per mutant: name, the test
# that caught it (or SURVIVED), its first failing check, build and test wall seconds. CPU
# heavy (a build per mutant, ccache when installed keeps it to the files the fault touches):
# it runs under nice -n 10, make -j2, one build at a time. Exit 0 when every mutant was caught.
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
            int kx|2D cell search (vres_cells_rows2d) skips the column of cells to the right"
    "eos-offset|kernels/eos.h|pow(rho / rho0, gamma) - 1.0)|pow(rho / rho0, gamma))|Tait equation without its -1: p = B (rho/rho0)^gamma"
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

echo "mutation.sh: building the unmutated tree at $REV in $S/tree" >&2
t0=$SECONDS
nice -n 10 "${mk[@]}" "${targets[@]}" >"$S/build0.log" 2>&1 || { tail -20 "$S/build0.log" >&2; echo "mutation.sh: the unmutated tree does not build" >&2; exit 1; }
base_s=$((SECONDS - t0))

rows=() catchers=() survived=0 nrun=0
for m in "${MUTANTS[@]}"; do
    IFS='|' read -r -d '' name file text new what <<<"$m"
    what=${what%$'\n'}
    if [ ${#want[@]} -gt 0 ] && [[ " ${want[*]} " != *" $name "* ]]; then continue; fi
    nrun=$((nrun + 1))
    n=$(apply "$file" "$text" "$new") || exit 1
    echo "mutation.sh: $name ($n place(s) in $file): $what" >&2
    t0=$SECONDS
    nice -n 10 "${mk[@]}" "${targets[@]}" >"$S/build.log" 2>&1
    brc=$? build_s=$((SECONDS - t0))
    t0=$SECONDS
    if [ $brc -eq 0 ]; then VRES_FAIL_FAST=1 nice -n 10 "${mk[@]}" check >"$S/check.log" 2>&1; crc=$?; else crc=2; fi
    test_s=$((SECONDS - t0))
    if [ $brc -ne 0 ]; then caught="(does not build)"; first=$(grep -m1 -E 'error' "$S/build.log")
    elif [ $crc -eq 0 ]; then caught=SURVIVED first="make check passed"; survived=$((survived + 1))
    else
        caught=$(sed -n 's/^failed: //p' "$S/check.log" | awk '{print $1}')
        [ -n "$caught" ] || caught="(make check exited $crc)"
        first=$(grep -m1 -E "^$caught: .*(not ok|Assertion|Failures|failed|:[0-9]+:F:|:[0-9]+:E:)" "$S/check.log" | cut -c1-240)
        [ -n "$first" ] || first=$(grep -m1 -E "^$caught: " "$S/check.log" | cut -c1-240)
        catchers+=("$caught")
    fi
    echo "mutation.sh: $name: $caught (build ${build_s} s, tests ${test_s} s)" >&2
    rows+=("$name	$caught	${build_s}	${test_s}	$what	$first")
    git checkout -q -- "$file"
done
[ "$nrun" -gt 0 ] || { echo "mutation.sh: no mutant named ${want[*]}" >&2; exit 2; }

# the catching tests pass on the unmutated tree (rebuilt from ccache)
nice -n 10 "${mk[@]}" "${targets[@]}" >"$S/build0.log" 2>&1 || { echo "mutation.sh: rebuilding the unmutated tree failed" >&2; exit 1; }
base=()
for t in $(printf '%s\n' "${catchers[@]}" | sort -u); do
    case $t in
        */tests/test_*) out=$(CK_FORK=yes CK_DEFAULT_TIMEOUT=60 nice -n 10 "$t" 2>&1); rc=$?
            r=$(grep -E '^[0-9]+%: Checks' <<<"$out" | tail -1) ;;
        tests/*.sh) out=$(nice -n 10 bash "$t" 2>&1); rc=$?
            r="$(grep -c '^ok ' <<<"$out") ok, $(grep -c '^not ok ' <<<"$out") not ok" ;;
        *) continue ;;
    esac
    [ $rc -eq 0 ] && ! grep -q '^not ok ' <<<"$out" && v=passes || v=FAILS
    base+=("$t	$v	$r")
done

mkdir -p "$(dirname "$REPORT")"
{
    echo "# mutation check of vres at $REV ($(date -u +%Y-%m-%d), $(nproc) cores, under nice -n 10 while other jobs ran):"
    echo "#   pipelines/mutation.sh${want[*]:+ ${want[*]}}"
    echo "# each mutant: one fault in a scratch clone, 'make -j2 all asan' and the unit tests (ccache: build_s is the files"
    echo "# the fault touches), then 'VRES_FAIL_FAST=1 make check' (test_s: until the first failing test)."
    echo "# unmutated tree built in ${base_s} s. caught_by: the first test that failed; first_failure: its first failing line."
    printf 'mutant\tcaught_by\tbuild_s\ttest_s\tfault\tfirst_failure\n'
    printf '%s\n' "${rows[@]}"
    echo "#"
    echo "# the catching tests on the unmutated tree (each must pass):"
    printf '#   %s\n' "${base[@]}"
    echo "# $((nrun - survived)) of $nrun mutants caught, $survived survived."
} >"$REPORT"
cat "$REPORT"
fails=$(printf '%s\n' "${base[@]}" | grep -c '	FAILS	')
[ "$survived" -eq 0 ] && [ "$fails" -eq 0 ]
