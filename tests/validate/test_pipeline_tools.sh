#!/usr/bin/env bash
# The sweep's helpers on inputs whose answers are known by hand: pipelines/table.sh (rows
# sorted coarse to fine, observed order p = log(e1/e2)/log(dp1/dp2) and the least-squares
# slope), pipelines/selfconv.sh (RMS differences of series between successive resolutions and
# their order), the checks' common options (usage errors exit 2, a missing run exits 1), and
# pipelines/sweep.mk / validate.mk as make sees them (dry runs).
source "$(dirname "$0")/../harness.sh"
P=$ROOT/pipelines

# three resolutions with errors falling as dp^2 (0.04, 0.01, 0.0025) and one failed run
mk() { printf 'case\tx\nreference\tref\nerror_def\tdef\ndp_m\t%s\nparticles\t%s\nsteps\t%s\nrun_time_s\t%s\nerror\t%s\ntolerance\t0.1\nverdict\t%s\n' "$@"; }
mk 0.1 100 10 1.0 0.0025 pass >"$T/r3"; mk 0.4 10 2 0.1 0.04 pass >"$T/r1"; mk 0.2 40 5 0.3 0.01 pass >"$T/r2"
printf 'case\tx\ndp_m\t0.05\n' >"$T/r4"
expect 0 "table.sh writes a table" "$P/table.sh" x "make sweep" "$T/r3" "$T/r1" "$T/r4" "$T/r2"
cp "$OUT" "$T/table"
check "rows sorted by dp, coarse first" [ "$(grep -v '^#' "$T/table" | cut -f1 | tr '\n' ' ')" = "0.4 0.2 0.1 0.05 " ]
check "the run without an error gets nan and FAIL" grep -q -P '^0\.05\tnan\tnan\tnan\tnan\tFAIL$' "$T/table"
check "observed orders 2.00 and 2.00" grep -q '^# observed order, successive resolutions: 0.4->0.2: 2.00; 0.2->0.1: 2.00;' "$T/table"
check "least-squares order 2.00 over 3 resolutions" grep -q 'slope of log error against log dp over 3 resolutions: 2.00' "$T/table"
check "the command is in the header" grep -q '^# command: make sweep$' "$T/table"

# selfconv: series y = 1 + dp * x over x in [0,1]: d(dp1, dp2) = |dp1 - dp2| * rms(x) -> order 1
series() { awk -v dp="$(cat "$1/dp")" 'BEGIN {for (i = 0; i <= 20; i++) printf "%g\t%.10g\n", i / 20, 1 + dp * i / 20}'; }
export -f series
for dp in 0.4 0.2 0.1; do mkdir -p "$T/s$dp"; echo "$dp" >"$T/s$dp/dp"; : >"$T/s$dp/run.tsv"; done
expect 0 "selfconv.sh compares the series" "$P/selfconv.sh" series "$T/s0.1:0.1" "$T/s0.4:0.4" "$T/s0.2:0.2"
check "two differences, observed order 1.00" grep -q -E '^# d\(dp 0.2, dp 0.1\) = [0-9.e-]+; observed order 1.00$' "$OUT"

# the checks' common options
expect_err 2 'usage: check' "a check with an unknown option: exit 2" "$CASES/hydrostatic_profile2d/check" --bogus
expect_err 2 'usage: check' "a check with two run directories: exit 2" "$CASES/poiseuille2d/check" "$T/a" "$T/b"
expect_err 1 'no run.tsv, not a vres-run directory' "a check of a missing run directory: exit 1, nothing run" \
    "$CASES/hydrostatic_profile2d/check" "$T/missing"
check "... and nothing made there" [ ! -e "$T/missing" ]
mkdir -p "$T/empty"; : >"$T/empty/run.tsv"
expect_err 1 'no snapshots' "a check of a directory without snapshots: exit 1" "$CASES/dambreak_front2d/check" "$T/empty"
expect 0 "a check's --help: exit 0" "$CASES/couette2d/check" --help
expect 2 "front.sh without a run directory: exit 2" "$P/front.sh"

# the pipelines as make reads them (dry runs: nothing is run)
expect 0 "sweep.mk: dry run" make -n -f "$P/sweep.mk" -C "$ROOT" RUNS="$T/runs" REPORTS="$T/rep"
check "sweep.mk runs each default case with GNU parallel -j2" \
    [ "$(grep -c -E '^parallel -j2 .*cases/(dambreak_front2d|hydrostatic_profile2d)/check --threads 1 --dp' "$OUT")" -eq 2 ]
expect 0 "validate.mk: dry run" make -n -f "$P/validate.mk" -C "$ROOT" RUNS="$T/runs" REPORTS="$T/rep"
check "validate.mk runs the dam break at dp 0.02 and 0.01" \
    [ "$(grep -c -E 'cases/dambreak_front2d/check --threads 1 --dp 0\.0[12] ' "$OUT")" -eq 2 ]
check "validate.mk runs the five stiff_<word> stability cases (stiff_sps2d among them)" [ "$(grep -c -E 'cases/stiff_[a-z0-9]+/check --threads 1 +-o' "$OUT")" -eq 5 ]
check "validate.mk runs the five coupled stability cases" [ "$(grep -c -E 'cases/stiff_vres_[a-z0-9_]+/check --threads 1 +-o' "$OUT")" -eq 5 ]
