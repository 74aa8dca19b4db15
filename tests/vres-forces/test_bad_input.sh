#!/usr/bin/env bash
# vres-forces on bad input, under AddressSanitizer: one message naming the file or option and
# what is wrong, exit 1 (2 for usage errors), nothing on stdout, no -o file written, no
# sanitizer report.
source "$(dirname "$0")/../harness.sh"
FORCES=$ASAN/vres-forces

# a small run: the still-water tank at dp 0.05 m (all walls mkbound 0), three snapshots
"$BIN/vres-gencase" -q --dp 0.05 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5" &&
    "$BIN/vres-run" -q --threads 1 --tmax 0.01 --tout 0.005 "$T/tank.h5" -o "$T/run" ||
    { notok "make the test run"; exit 1; }
check "the test run has three snapshots" [ "$(ls "$T/run"/snap_*.h5 | wc -l)" -eq 3 ]
mkdir "$T/empty" "$T/broken" "$T/out"
cp "$T/run"/snap_0000[01].h5 "$T/broken/"
head -c 3000 "$T/run/snap_00002.h5" >"$T/broken/snap_00002.h5"
echo "<case>text, not HDF5</case>" >"$T/text.h5"

# bad STATUS NAME PATTERN ARGS...: exit STATUS, stderr one line matching PATTERN, stdout empty,
# and the -o file given (always $T/out/f.tsv) not written.
bad() {
    local want=$1 name=$2 pat=$3; shift 3
    expect_err "$want" "$pat" "$name" "$FORCES" "$@" -o "$T/out/f.tsv"
    check "$name: one message" [ "$(grep -vc "Try 'vres-forces --help'" "$ERR")" -eq 1 ]
    check "$name: nothing on stdout" [ ! -s "$OUT" ]
    nothing_in "$T/out" "$name: nothing written"
}

bad 1 "missing run directory or store" "nothere: cannot open" --mk 0 "$T/nothere"
bad 1 "directory without snapshots" "empty: no snapshots" --mk 0 "$T/empty"
bad 1 "a truncated snapshot" "broken/snap_00002\.h5: damaged or truncated" --mk 0 "$T/broken"
bad 1 "not a store" "text\.h5: not an HDF5 file" --mk 0 "$T/text.h5"
bad 1 "unknown mkbound: named, with the mkbounds there" \
    "snap_00000\.h5: no wall particles with mkbound 7; the mkbound values there \(type, particles\): 0 \(fixed, 110\)" \
    --mk 7 "$T/run"
bad 1 "the fluid's mk is not a wall" "no wall particles with mkbound 1;" --mk 1 "$T/tank.h5"
bad 1 "too short a signal for --spectrum" "fz: too short a signal for a spectrum: 3 samples" --mk 0 --spectrum fz "$T/run"
bad 1 "truncated store on stdin" "\(stdin\): damaged or truncated" --mk 0 - <"$T/broken/snap_00002.h5"
bad 2 "missing --mk" "missing --mk K" "$T/run"
bad 2 "--mk not an integer" "mk.*is not an integer" --mk bottom "$T/run"
bad 2 "malformed --coef" "--coef 1,2: must be U,L,RHO" --mk 0 --coef 1,2 "$T/run"
bad 2 "--coef with a zero" "--coef 1,0,1000: must be" --mk 0 --coef 1,0,1000 "$T/run"
bad 2 "--coef with text" "--coef 1,x,1000: must be" --mk 0 --coef 1,x,1000 "$T/run"
bad 2 "--coef with an area in 2D" "a 2D case takes U,L,RHO" --mk 0 --coef 1,0.1,1000,0.02 "$T/run"
bad 2 "malformed --centre" "--centre 0,0: must be three numbers" --mk 0 --centre 0,0 "$T/run"
bad 2 "unknown --spectrum column" "--spectrum lift: unknown column; one of fx fy fz mx my mz cd cl" \
    --mk 0 --spectrum lift "$T/run"
bad 2 "--spectrum cl without --coef" "--spectrum cl needs --coef" --mk 0 --spectrum cl "$T/run"
bad 2 "--spectrum of a motion column for a body that neither moves nor floats" \
    "--spectrum cz: mkbound 0 is neither a moving nor a floating body: it has no motion columns" --mk 0 --spectrum cz "$T/run"
bad 2 "--from without --spectrum" "--from applies to --spectrum only" --mk 0 --from 1 "$T/run"
bad 2 "two inputs" "" --mk 0 "$T/run" "$T/tank.h5"

expect_err 1 "nodir/f\.tsv" "-o in a missing directory" "$FORCES" --mk 0 "$T/run" -o "$T/nodir/f.tsv"
check "-o in a missing directory: nothing on stdout" [ ! -s "$OUT" ]
expect_err 2 "Try 'vres-forces --help'" "no argument is a usage error" "$FORCES"

# snap_last_good.h5 (written after a blow-up) and other files are not snapshots of the series
cp "$T/run/snap_00000.h5" "$T/run/snap_last_good.h5"
echo note >"$T/run/notes.txt"
expect 0 "run directory with snap_last_good.h5 and other files" "$FORCES" --mk 0 "$T/run"
check "no sanitizer report" bash -c "! grep -q -E 'Sanitizer|runtime error' '$ERR'"
check "only the three numbered snapshots are read" [ "$(grep -vc '^#' "$OUT")" -eq 3 ]
