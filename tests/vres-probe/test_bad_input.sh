#!/usr/bin/env bash
# vres-probe on bad input, under AddressSanitizer: one clear message naming the culprit, exit 1
# (2 for usage errors), and nothing written (no -o file, not even a temporary; nothing on
# stdout).
source "$(dirname "$0")/../harness.sh"
PROBE=$ASAN/vres-probe

mkdir "$T/run" "$T/out" "$T/empty"
if ! "$BIN/vres-gencase" -q "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" --dp 0.04 -o "$T/good.h5"; then
    notok "vres-gencase makes the fixture"
    exit 1
fi
cp "$T/good.h5" "$T/run/snap_00000.h5"
printf '0.5 0 1\n' >"$T/pts.txt"

# fails NAME PATTERN ARGS...: exit 1, one message matching PATTERN, no output anywhere.
fails() {
    local name=$1 pat=$2; shift 2
    expect_err 1 "$pat" "$name" "$PROBE" "$@" -o "$T/out/p.tsv"
    check "$name: one message" [ "$(wc -l <"$ERR")" -eq 1 ]
    nothing_in "$T/out" "$name: nothing written"
    expect_err 1 "$pat" "$name (stdout)" "$PROBE" "$@"
    check "$name: nothing on stdout" [ ! -s "$OUT" ]
}
# usage NAME PATTERN ARGS...: exit 2, the message, nothing written.
usage() {
    local name=$1 pat=$2; shift 2
    expect_err 2 "$pat" "$name" "$PROBE" "$@" -o "$T/out/p.tsv"
    nothing_in "$T/out" "$name: nothing written"
}

# Inputs.
fails "missing run directory" 'nosuch: cannot open' --points "$T/pts.txt" "$T/nosuch"
fails "directory without snapshots" 'empty: no snap_NNNNN\.h5 snapshots' --points "$T/pts.txt" "$T/empty"
echo "not HDF5" >"$T/text.h5"
fails "text file as store" 'text\.h5: not an HDF5 file' --points "$T/pts.txt" "$T/text.h5"
mkdir "$T/bad"
cp "$T/good.h5" "$T/bad/snap_00000.h5"
head -c 3000 "$T/good.h5" >"$T/bad/snap_00001.h5"
cp "$T/good.h5" "$T/bad/snap_00002.h5"
fails "truncated snapshot in a run" 'snap_00001\.h5: ' --points "$T/pts.txt" "$T/bad"
h5copy -i "$T/good.h5" -o "$T/foreign0.h5" -s /Domains/D0 -d /Other
h5repack -L "$T/foreign0.h5" "$T/foreign.h5" # h5copy writes the oldest format, which is refused as such
mkdir "$T/foreign"
cp "$T/foreign.h5" "$T/foreign/snap_00007.h5"
fails "snapshot that is not a store" 'snap_00007\.h5: not a vres store' --points "$T/pts.txt" "$T/foreign"

# Points files.
printf '0.5 0 1\n0.5 0 1.2\n0.5 0\n' >"$T/short.txt"
fails "points file: a short line" 'short\.txt:3: 2 numbers, expected 3' --points "$T/short.txt" "$T/run"
printf '0.5 0 1\n0.5 zero 1\n' >"$T/word.txt"
fails "points file: not a number" "word\\.txt:2: 'zero' is not a number" --points "$T/word.txt" "$T/run"
printf '# only a comment\n\n' >"$T/none.txt"
fails "points file: no points" 'none\.txt: no points' --points "$T/none.txt" "$T/run"
fails "points file missing" 'nofile\.txt' --points "$T/nofile.txt" "$T/run"

# Reference files.
printf 'z_m,q\n0,1\n1,2\n' >"$T/noq.csv"
fails "reference without the column" "noq\\.csv: no column 'p_Pa' or 'p' \\(its columns: z_m, q\\)" \
    --points "$T/pts.txt" --ref "$T/noq.csv" "$T/run"
fails "--ref-col names a missing reference column" "noq\\.csv: no column 'pressure'" \
    --points "$T/pts.txt" --ref "$T/noq.csv" --ref-col p=pressure "$T/run"
fails "--ref-x names a missing column" "noq\\.csv: no column 'height' for the abscissa" \
    --points "$T/pts.txt" --ref "$T/noq.csv" --ref-x height --ref-col p=q "$T/run"
printf 'depth,p\n0,1\n1,2\n' >"$T/depth.csv"
fails "unknown abscissa" "depth\\.csv: abscissa column 'depth' is not one vres-probe knows" \
    --points "$T/pts.txt" --ref "$T/depth.csv" "$T/run"
printf 'z,p\n0,1\n1,x2\n' >"$T/badnum.csv"
fails "reference: not a number" "badnum\\.csv:3: column 'p': 'x2' is not a number" \
    --points "$T/pts.txt" --ref "$T/badnum.csv" "$T/run"
printf 'z,p\n5,1\n6,2\n' >"$T/far.csv"
fails "reference: nothing to compare" "far\\.csv: no sample to compare: 0 rows outside the fluid \\(nan\\), 1 outside" \
    --points "$T/pts.txt" --ref "$T/far.csv" "$T/run"
printf 'dist,p\n0,1\n1,2\n' >"$T/dist.csv"
fails "distance abscissa with --points" "dist\\.csv: abscissa 'dist' is the distance along a line" \
    --points "$T/pts.txt" --ref "$T/dist.csv" "$T/run"
fails "surface against a profile" "surface elevations are compared over time" \
    --surface --line 0.5,0,0:0.5,0,3:31 --ref "$T/noq.csv" --ref-col z=q "$T/run"

# Gauges.
fails "no gauges in the case" 'has no <gauges>' --gauges "$T/run"
sed 's|<parameters>|<special><gauges><force name="Force1"><target mkbound="0"/></force></gauges></special><parameters>|' \
    "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" >"$T/force_Def.xml"
"$BIN/vres-gencase" -q "$T/force_Def.xml" --dp 0.04 -o "$T/force.h5"
fails "unsupported gauge" "gauge 'Force1': <force> gauges are not supported .*vres-forces" --gauges "$T/force.h5"

# Output.
expect_err 1 'nodir/p\.tsv: cannot write' "-o in a missing directory" "$PROBE" --points "$T/pts.txt" "$T/run" -o "$T/nodir/p.tsv"
check "missing directory not created" [ ! -e "$T/nodir" ]
echo "keep me" >"$T/out/keep.tsv"
expect_err 1 'short\.txt:3' "failure keeps an existing output" "$PROBE" --points "$T/short.txt" "$T/run" -o "$T/out/keep.tsv"
check "existing output unchanged" [ "$(cat "$T/out/keep.tsv")" = "keep me" ]
check "no temporary left" [ "$(ls -A "$T/out")" = keep.tsv ]
rm "$T/out/keep.tsv"

# Usage errors: exit 2.
usage "line with one point" "N = 1 \\(a line needs 2 to" --line 0.5,0,0:0.5,0,1:1 "$T/run"
usage "malformed line" "--line '0.5,0:0.5,0,1:3': the start point" --line 0.5,0:0.5,0,1:3 "$T/run"
usage "unknown variable" "unknown variable 'temperature' \\(valid: p, rho, vx, vy, vz, speed\\)" \
    --points "$T/pts.txt" --vars p,temperature "$T/run"
usage "nothing to probe" "nothing to probe" "$T/run"
usage "--surface with --points" "--surface searches along lines" --surface --points "$T/pts.txt" "$T/run"
usage "--gauges with --line" "--gauges takes its points from the case" --gauges --line 0,0,0:1,1,1:3 "$T/run"
usage "--ref-col without --ref" "--ref-col goes with --ref" --points "$T/pts.txt" --ref-col p "$T/run"
usage "--ref-col not a variable" "--ref-col 'rho': not one of the table's variables \\(p_Pa\\)" \
    --points "$T/pts.txt" --vars p --ref "$T/noq.csv" --ref-col rho "$T/run"
usage "--colour-limit without --surface" "--colour-limit goes with --surface" --points "$T/pts.txt" --colour-limit 0.4 "$T/run"
usage "stdin twice" "standard input .* only once" --points - -
usage "no input" "missing argument" --points "$T/pts.txt"
usage "two inputs" "too many arguments" --points "$T/pts.txt" "$T/run" "$T/run"
