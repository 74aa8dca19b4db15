#!/usr/bin/env bash
# vres-info on good input: the report, the -t table, -q, stdin, -o and run directories.
# The store comes from the store unit test binary (its sample(): 3 domains; D0 holds 40000
# particles cycling through the 6 types and mk -1..5; D1 5 buffer particles of mk 0; D2 none).
source "$(dirname "$0")/../harness.sh"
INFO=$BIN/vres-info

MAKER=$ROOT/$VRES_BUILD/tests/test_store
if ! VRES_TEST_STORE_OUT=$T/s.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_store)"
    exit 1
fi

# The report.
expect 0 "report exits 0" "$INFO" "$T/s.h5"
cp "$OUT" "$T/report.txt"
check "report names the file" grep -q "^$T/s.h5: vres store" "$OUT"
check "report gives the case name" grep -q "case  *sample-case" "$OUT"
check "report lists three domains" [ "$(grep -c '^domain D[0-9]' "$OUT")" -eq 3 ]
check "report gives D1's parent" grep -q '^domain D1 (in D0): 5 particles' "$OUT"
check "parameter with values, unit and origin" grep -q -E '^  gravity +0 0 -9\.81 +m/s\^2 +\(xml\)$' "$OUT"
order=$(sed -n '/^parameters:/,/^$/p' "$OUT" | awk 'NR > 1 && NF {print $1}' | tr '\n' ' ')
check "parameters in recorded order, not sorted ($order)" [ "$order" = "rhop0 gravity StepAlgorithm dp " ]
first=$(sed -n '/^history/{n;p;q}' "$OUT")
check "history newest first ($first)" eval '[[ "$first" =~ ^\ \ 20[0-9-]+T[0-9:]+Z\ test_store\ fixture$ ]]'
check "floating body listed" grep -q 'B0 mkbound 3, floating, mass 12.5 kg' "$OUT"

# The table: the type counts must agree with an independent reading of the Type dataset.
expect 0 "-t exits 0" "$INFO" -t "$T/s.h5"
cp "$OUT" "$T/table.tsv"
check "-t header names the columns" [ "$(head -1 "$T/table.tsv")" = "$(printf '# domain\ttype\tmk\tcount')" ]
check "-t rows have 4 tab-separated fields" awk -F'\t' 'NR > 1 && NF != 4 {exit 1}' "$T/table.tsv"
d0=$(awk -F'\t' '$1 == "0" {s += $4} END {print s}' "$T/table.tsv")
check "-t D0 counts sum to 40000 ($d0)" [ "$d0" = 40000 ]
check "-t D0 has 6 types x 7 mk rows" [ "$(grep -c '^0	' "$T/table.tsv")" -eq 42 ]
check "-t D1 is 5 buffer particles of mk 0" [ "$(grep '^1	' "$T/table.tsv")" = "$(printf '1\tbuffer\t0\t5')" ]
check "-t empty D2 has no rows" [ "$(grep -c '^2	' "$T/table.tsv")" -eq 0 ]
fluid=$(awk -F'\t' '$1 == "0" && $2 == "fluid" {s += $4} END {print s}' "$T/table.tsv")
h5fluid=$(h5dump -w 1 -y -d /Domains/D0/Type "$T/s.h5" | grep -c -E '^ *0,?$')
check "-t fluid count $fluid equals h5dump's count of Type 0 ($h5fluid)" [ "$fluid" = "$h5fluid" ]

# -q: header and one line per domain only.
expect 0 "-q exits 0" "$INFO" -q "$T/s.h5"
check "-q has one line per domain" [ "$(grep -c '^  D[0-9] (' "$OUT")" -eq 3 ]
check "-q has no parameters or history" [ "$(grep -c -E '^(parameters|history)' "$OUT")" -eq 0 ]

# -v adds the motion segments.
expect 0 "-v exits 0" "$INFO" -v "$T/s.h5"
check "-v lists motion segments" [ "$(grep -c '^    segment ' "$OUT")" -eq 2 ]

# stdin gives the same report but for the name.
run "$INFO" - <"$T/s.h5"
check "stdin exits 0" [ "$STATUS" -eq 0 ]
check "stdin report equals the file's but for the name" \
    diff <(sed 1d "$OUT") <(sed 1d "$T/report.txt")
check "stdin report calls it (stdin)" grep -q '^(stdin): vres store' "$OUT"

# -o writes the same text to a file and nothing to stdout.
expect 0 "-o exits 0" "$INFO" -t -o "$T/out.tsv" "$T/s.h5"
check "-o file equals stdout table" cmp -s "$T/out.tsv" "$T/table.tsv"
check "-o prints nothing on stdout" [ ! -s "$OUT" ]

# A run directory: one row per snapshot, in name order.
mkdir "$T/run"
cp "$T/s.h5" "$T/run/snap_00001.h5"
cp "$T/s.h5" "$T/run/snap_00000.h5"
echo "not a snapshot" >"$T/run/run.tsv"
expect 0 "run directory exits 0" "$INFO" -t "$T/run"
check "run -t header" [ "$(head -1 "$OUT")" = "$(printf '# file\ttime_s\tstep\tdomains\tparticles')" ]
check "run -t lists both snapshots in order" \
    [ "$(cut -f1 "$OUT" | sed 1d | tr '\n' ' ')" = "snap_00000.h5 snap_00001.h5 " ]
check "run -t row values" [ "$(sed -n 2p "$OUT")" = "$(printf 'snap_00000.h5\t1.25\t1234567890123\t3\t40005')" ]
expect 0 "run directory report exits 0" "$INFO" "$T/run"
check "run report counts snapshots" grep -q 'run directory, 2 snapshots' "$OUT"

# A pipe that is not stdin (process substitution) is read like stdin.
run "$INFO" -q <(cat "$T/s.h5")
check "store from a pipe path" [ "$STATUS" -eq 0 ]
check "pipe report counts particles" grep -q 'particles   40005 in 3 domains' "$OUT"

# A store made by vres-gencase (DualSPHysics' 2D dam break): the -t counts per type agree
# with h5dump's reading of the Type dataset, and the pipeline form gives the same table.
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml
expect 0 "vres-gencase makes the dam break" "$BIN/vres-gencase" -q "$DB" -o "$T/db.h5"
expect 0 "-t on the gencase store" "$INFO" -t "$T/db.h5"
cp "$OUT" "$T/db.tsv"
for ty in 0:fluid 2:fixed; do
    n=$(awk -F'\t' -v t="${ty#*:}" '$2 == t {s += $4} END {print s + 0}' "$T/db.tsv")
    h=$(h5dump -w 1 -y -d /Domains/D0/Type "$T/db.h5" | grep -c -E "^ *${ty%:*},?$")
    check "gencase store: ${ty#*:} count $n equals h5dump's ($h)" [ "$n" = "$h" ]
done
"$BIN/vres-gencase" -q "$DB" | "$INFO" -t - >"$T/pipe.tsv"
check "gencase | vres-info -t - gives the same table" cmp -s "$T/pipe.tsv" "$T/db.tsv"
expect 0 "report on the gencase store" "$INFO" "$T/db.h5"
check "history holds the gencase command line" grep -q -E '^  [0-9T:-]+Z vres-gencase -q .*dambreak2d_Def\.xml -o ' "$OUT"
