#!/usr/bin/env bash
# Smoke test of the dam-break validation (cases/dambreak_front2d, the short version of what
# `make validate` runs): the column (a = 1 m, H = 2 m) at dp 0.04 m (1250 fluid particles) for
# 0.3 s, T = t sqrt(2g/a) up to 1.33. Properties any correct run has, whatever the resolution:
#  * the surge front advances monotonically (no particle of a collapsing column moves back
#    from the front before it reaches the far wall);
#  * it stays behind Ritter's shallow-water front Z = 1 + 2T (refdata/dambreak_ritter_dry_bed.csv),
#    an upper bound: the real front, slowed by the vertical acceleration of the column, is
#    behind it (Z = 1.5 at T = 1.15 in the experiments, against Ritter's 3.3);
#  * it has left the column (Z > 1.3 at T = 1.33: the experiments have Z = 1.5 at T = 1.2);
#  * the fluid mass is conserved exactly (no particle is ever removed);
#  * cases/dambreak_front2d/check accepts the run (RMS distance to the experimental fronts
#    below its tolerance 0.35 a over the 7 reference points with T <= 1.33).
source "$(dirname "$0")/../harness.sh"
DIR=$CASES/dambreak_front2d

expect 0 "gencase the dam break at dp 0.04" "$BIN/vres-gencase" -q --dp 0.04 "$DIR/dambreak_front2d_Def.xml" -o "$T/db.h5"
expect 0 "run it to 0.3 s" "$BIN/vres-run" -q --threads 1 --tmax 0.3 --tout 0.02 "$T/db.h5" -o "$T/run"
expect 0 "pipelines/front.sh reads the snapshots" "$ROOT/pipelines/front.sh" "$T/run"
cp "$OUT" "$T/front.tsv"
nsnap=$(grep -vc '^#' "$T/front.tsv")
check "one front per snapshot ($nsnap)" [ "$nsnap" -eq "$(ls "$T/run"/snap_[0-9]*.h5 | wc -l)" ] 
# Z = (x_front - x_left(0)) / a, T = t sqrt(g H)/a with a, H from the first row
awk -F'\t' '!/^#/ { if (!n++) { x0 = $2; a = $3 - $2; H = $5 - $4 }
                    printf "%.6f %.6f\n", $1 * sqrt(9.81 * H) / a, ($3 - x0) / a }' "$T/front.tsv" >"$T/TZ"
check "first snapshot: Z = 1 at T = 0" awk 'NR == 1 {exit !($1 == 0 && $2 == 1)}' "$T/TZ"
back=$(awk 'NR > 1 && $2 < z {n++} {z = $2} END {print n + 0}' "$T/TZ")
check "front advances monotonically ($back steps back)" [ "$back" -eq 0 ]
over=$(awk '$2 > 1 + 2 * $1 + 1e-9 {n++} END {print n + 0}' "$T/TZ")
check "front behind Ritter's bound Z = 1 + 2T in every snapshot ($over above)" [ "$over" -eq 0 ]
zend=$(awk 'END {print $2}' "$T/TZ")
check "front has left the column: Z = $zend > 1.3 at T = 1.33" awk -v z="$zend" 'BEGIN {exit !(z > 1.3)}'
check "fluid mass conserved exactly" awk -F'\t' '!/^#/ {if (n++ && $6 != m) exit 1; m = $6}' "$T/run/run.tsv"
expect 0 "cases/dambreak_front2d/check accepts the run" "$DIR/check" "$T/run"
grep -E '^(error|reference_points|bias)	' "$OUT" | sed 's/^/# /'
