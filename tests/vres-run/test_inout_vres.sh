#!/usr/bin/env bash
# Inlet/outlet zones with variable resolution (issue 8 item 3): the uniform channel of
# cases/channel_inout2d (2 m x 0.4 m, free-slip mDBC walls, an inlet of 1 m/s with fixed
# density, an outlet extrapolating both, dp 0.04 m) with a refinement box (dpratio 2) over its
# middle, x 0.7..1.3 m, across both walls. The zones run in the root while the box's coupling
# runs beside them: the stream stays uniform in both domains (within the 1% of issue 8's
# uniform-stream check), the zones' and the coupling's books close together (within one root
# column in transit, exactly at 1 s), a restart continues bit for bit (both domains, the ledger), and a
# box that reaches a zone is refused naming the zone, its line and the domain.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/channel_inout2d/channel_inout2d_Def.xml
box() { # box X0 X1 OUT: the channel with a refinement box over x X0..X1 (m)
    sed "s|^    </casedef>|        <vres>\n            <bufferbox>\n                <point x=\"$1\" y=\"0\" z=\"-0.5\" />\n                <endpoint x=\"$2\" y=\"0\" z=\"0.9\" />\n                <dpratio v=\"2\" />\n            </bufferbox>\n        </vres>\n    </casedef>|" "$CASE" >"$3"
}
box 0.7 1.3 "$T/mid.xml"
check "the variant has its box" grep -q '<endpoint x="1.3" y="0" z="0.9" />' "$T/mid.xml"
expect 0 "vres-gencase" "$BIN/vres-gencase" -q "$T/mid.xml" -o "$T/case.h5"
expect 0 "vres-partition: two domains" "$BIN/vres-partition" -q "$T/case.h5" -o "$T/parts.h5"
PY=python3
python3 -c 'import h5py, numpy' 2>/dev/null || PY=/usr/bin/python3
expect 0 "the stream of 1 m/s in both domains (init_uniform.py)" $PY "$CASES/channel_uniform_vres2d/init_uniform.py" "$T/parts.h5"
expect 0 "vres-run to 1 s (two flow-throughs of the box)" "$BIN/vres-run" --threads 1 --tmax 1 --tout 0.5 "$T/parts.h5" -o "$T/a"
check "the modules name the zones" grep -q 'inout(2 zones)' "$ERR"
check "the coupling of the two domains is reported" grep -q 'coupling of the 2 domains' "$ERR"
L=$T/a/ledger.tsv
drift=$(awk -F'\t' '!/^#/ {d = $20; if (d < 0) d = -d; if (d > D) D = d; n++} END {print (n ? D : "none") ""}' "$L")
# the coupled books count the fluid each domain owns: a root column that has entered the box's
# band at an output is neither domain's fluid (10 particles of 1.6 kg, 0.02 of the 800 kg:
# -0.02 at 0.5 s, 0 at 1 s); the zones' exchange is exact
check "every ledger line's drift within one root column of 10 particles (largest $drift)" \
    awk -v d="$drift" 'BEGIN {exit !(d != "none" && d <= 0.02 + 1e-12)}'
check "the last output's books close to rounding" \
    awk -F'\t' '!/^#/ {d = $20} END {exit !(d != "" && d * d <= 1e-24)}' "$L"
check "no drift beyond one particle mass per segment said" bash -c "! grep -q 'more than one particle mass per interface segment' '$ERR'"
last() { awk -F'\t' -v z="$1" -v c="$2" '$3 == z {v = $c} END {print v + 0}' "$L"; }
check "the inlet gave the root fluid ($(last Z1 10) particles)" [ "$(last Z1 10)" -ge 200 ]
check "the outlet took the root's fluid ($(last Z2 11) particles)" [ "$(last Z2 11)" -ge 200 ]
check "the box's fluid crossed its interfaces ($(last 1 10) buffer to fluid)" [ "$(last 1 10)" -ge 200 ]
check "the box holds its 640 fluid particles ($(last 1 5))" [ "$(last 1 5)" -eq 640 ]
snap=$T/a/snap_00002.h5
for d in D0 D1; do
    dev=$(paste <(values /Domains/$d/Type "$snap") <(values /Domains/$d/Position "$snap" | paste - - -) \
              <(values /Domains/$d/Velocity "$snap" | paste - - -) |
          awk '$1 == 0 && $2 >= 0 && $2 <= 2 {a = $5 - 1; a = a < 0 ? -a : a; b = $7 < 0 ? -$7 : $7; if (a > A) A = a; if (b > B) B = b; n++}
               END {if (n) printf "%.3g %.3g %d\n", A, B, n; else print "nan nan 0"}')
    check "$d at 1 s: u within 1% of 1 m/s, |w| below 0.01 m/s (largest |u - 1|, |w|, count: $dev)" \
        awk -v s="$dev" 'BEGIN {split(s, v, " "); exit !(v[3] > 0 && v[1] <= 0.01 && v[2] <= 0.01)}'
done
rm -rf "$T/b" && cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00001.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/b/snap_00001.h5"
for d in D0 D1; do
    for ds in Position Velocity Density Type Id; do
        check "restart: snap 2 /Domains/$d/$ds equal to the uninterrupted run's" \
            h5diff -q "$T/a/snap_00002.h5" "$T/b/snap_00002.h5" /Domains/$d/$ds /Domains/$d/$ds
    done
done
check "restart: the ledger's last lines equal" [ "$(tail -4 "$T/a/ledger.tsv")" = "$(tail -4 "$T/b/ledger.tsv")" ]

box 0.1 0.5 "$T/near.xml"
line=$(grep -n '<inoutzone' "$T/near.xml" | head -1 | cut -d: -f1)
expect 0 "vres-gencase, a box within reach of the inlet" "$BIN/vres-gencase" -q "$T/near.xml" -o "$T/near.h5"
expect 0 "vres-partition it" "$BIN/vres-partition" -q "$T/near.h5" -o "$T/nearp.h5"
expect_err 1 "inlet/outlet zone 1 \(case line $line\): it reaches into domain D1's box and buffer band" \
    "vres-run refuses it, naming the zone, its line and the domain" "$BIN/vres-run" --threads 1 "$T/nearp.h5" -o "$T/near"
nothing_in "$T/near" "refused: nothing written"
