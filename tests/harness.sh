# tests/harness.sh - sourced by every tool behaviour test (tests/<tool>/test_*.sh).
# Each check prints one TAP line ("ok - name" / "not ok - name"); tests/run counts them.
# Tools under test: $BIN/vres-* (the normal build) and $ASAN/vres-* (AddressSanitizer build,
# used for bad-input tests so that a crash or memory error fails the test).
set -u
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${VRES_BIN:-$ROOT/bin}          # make check B=... BINDIR=... tests another build's tools
export VRES_BIN=$BIN               # and the pipelines' scripts (pipelines/vreslib.sh) use the same
VRES_BUILD=${VRES_BUILD:-build}
ASAN=$ROOT/$VRES_BUILD/asan/bin
CASES=$ROOT/cases
T=$(mktemp -d "${TMPDIR:-/tmp}/vres-test.XXXXXX")
trap 'rm -rf "$T"' EXIT
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$ROOT/tests/lsan.supp:print_suppressions=0
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
# a test machine is often busier than its cores: threads that spin-wait would only steal time
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
OUT=$T/stdout
ERR=$T/stderr
STATUS=0

ok() { echo "ok - $*"; }

# values DATASET FILE: a store dataset's numbers, one per line, at full double precision, read
# with h5dump (not with vres, so a test does not trust the code it tests to read its output).
values() {
    h5dump -m '%.17g' -y -w 1 -d "$1" "$2" |
        awk '/DATA \{/ {on = 1; next} on && /^ *[-0-9.eE+]+,?$/ {gsub(/[ ,]/, ""); print}'
}
notok() { echo "not ok - $*"; }

# run CMD...: run a command, keeping stdout in $OUT, stderr in $ERR and the exit code in $STATUS.
run() { "$@" >"$OUT" 2>"$ERR"; STATUS=$?; }

# expect STATUS NAME CMD...: run CMD and check its exit status; on failure show stderr.
expect() {
    local want=$1 name=$2; shift 2
    run "$@"
    if [ "$STATUS" -eq "$want" ]; then ok "$name"; else
        notok "$name (exit $STATUS, wanted $want)"; sed 's/^/#   /' "$ERR" | head -20; fi
}

# expect_err STATUS PATTERN NAME CMD...: CMD exits STATUS, stderr matches PATTERN (grep -E),
# and AddressSanitizer/UBSan reported nothing.
expect_err() {
    local want=$1 pat=$2 name=$3; shift 3
    run "$@"
    if [ "$STATUS" -ne "$want" ]; then
        notok "$name (exit $STATUS, wanted $want)"; sed 's/^/#   /' "$ERR" | head -20
    elif grep -q -E 'Sanitizer|runtime error' "$ERR"; then
        notok "$name (sanitizer report)"; sed 's/^/#   /' "$ERR" | head -30
    elif ! grep -q -E -- "$pat" "$ERR"; then
        notok "$name (stderr lacks /$pat/)"; sed 's/^/#   /' "$ERR" | head -20
    else ok "$name"; fi
}

# attr PATH FILE: an HDF5 attribute's numbers (any shape), one per line, at full precision, read
# with h5dump; comp PATH FILE I: its I-th number (1-based).
attr() {
    h5dump -m '%.17g' -a "$1" "$2" | awk '/DATA \{/ {on = 1; next} on && /\}/ {exit}
        on {sub(/^ *(\([0-9,]+\): *)?/, ""); n = split($0, v, /, */); for (i = 1; i <= n; i++) if (v[i] != "") print v[i]}'
}
comp() { attr "$1" "$2" | sed -n "$3p"; }

# ledger_within_bound SNAP RUNDIR LINES: a two-domain coupled run's ledger.tsv has LINES lines
# and its largest |total mass drift| stays within vres-run's bound, one particle mass per
# segment: (count(I0) m(D1) + count(I1) m(D0)) / the start's fluid mass, from snapshot SNAP.
ledger_within_bound() {
    local f=$1 bound drift
    bound=$(awk -v a="$(attr /Interfaces/I0/count "$f")" -v ma="$(attr /Domains/D1/mass "$f")" \
                -v b="$(attr /Interfaces/I1/count "$f")" -v mb="$(attr /Domains/D0/mass "$f")" \
                -v m0="$(grep -v '^#' "$2/ledger.tsv" | head -1 | cut -f19)" 'BEGIN {printf "%.6g", (a * ma + b * mb) / m0}')
    drift=$(awk -F'\t' '!/^#/ {d = $20 < 0 ? -$20 : $20; if (d > m) m = d; n++} END {printf "%.4g %d", m, n}' "$2/ledger.tsv")
    echo "# ledger: largest |total mass drift| $drift lines; the run's bound (one particle mass per segment) $bound"
    check "ledger: |drift| within the bound on all $3 lines" \
        awk -v d="${drift% *}" -v n="${drift#* }" -v b="$bound" -v want="$3" 'BEGIN {exit !(n == want && d <= b && b > 0)}'
}

# check NAME CONDITION...: a plain assertion, e.g. check "count" [ "$n" -eq 3 ].
check() {
    local name=$1; shift
    if "$@"; then ok "$name"; else notok "$name"; fi
}

# same_after_restart NAME RUNDIR FROM CMP...: copy run RUNDIR (vres-run, one domain) to RUNDIR.r,
# restart the copy from its snap_FROM.h5 and check that each snap_CMP.h5's positions,
# velocities and densities equal the uninterrupted run's (bit for bit: h5diff).
same_after_restart() {
    local name=$1 dir=$2 from=$3 cmp ds
    shift 3
    rm -rf "$dir.r" && cp -r "$dir" "$dir.r"
    expect 0 "$name: restart from snap_$from.h5" "$BIN/vres-run" -q --threads 1 --restart "$dir.r/snap_$from.h5"
    for cmp in "$@"; do
        for ds in Position Velocity Density; do
            check "$name: snap $cmp $ds equal to the uninterrupted run's" \
                h5diff -q "$dir/snap_$cmp.h5" "$dir.r/snap_$cmp.h5" /Domains/D0/$ds /Domains/D0/$ds
        done
    done
}

# nothing_in DIR NAME: the directory holds no files (nothing half-written).
nothing_in() {
    if [ -z "$(ls -A "$1" 2>/dev/null)" ]; then ok "$2"; else notok "$2 (found: $(ls -A "$1" | tr '\n' ' '))"; fi
}

# tilted_tank: cases/hydrostatic_vres2d under a sideways gravity of 3 m/s^2 (water crosses its
# interface within 0.1 s), generated as $T/tilt.h5 and partitioned as $T/parts.h5.
tilted_tank() {
    sed 's/<gravity x="0"/<gravity x="3"/' "$CASES/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml" >"$T/tilt.xml"
    grep -q '<gravity x="3"' "$T/tilt.xml" || notok "the sideways gravity is in the case"
    "$BIN/vres-gencase" -q "$T/tilt.xml" -o "$T/tilt.h5" || notok "gencase the tilted tank"
    "$BIN/vres-partition" -q "$T/tilt.h5" -o "$T/parts.h5" || notok "partition the tilted tank"
}
