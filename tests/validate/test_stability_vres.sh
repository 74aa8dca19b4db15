#!/usr/bin/env bash
# The stability verdict of a coupled run (pipelines/stability.sh on several domains; DESIGN
# section 7, issue 7 item 7): a quick run of cases/stiff_vres_front2d (the dam-break front into
# a refinement box in mid-tank) to 0.3 s, through the front's entry into the box, passes with
# the ledger's drift within one particle mass per segment, its accounts closed and no runaway;
# then the verdict on doctored copies of its ledger.tsv, which it must reject: a particle that
# appears outside the ledger's accounts, a drift past the bound, a band holding far more buffer
# particles than it can, a NaN; and a single-domain run is still judged by its fluid mass
# (the ledger's tests are not asked of it).
source "$(dirname "$0")/../harness.sh"
VRES_ME=test_stability_vres
source "$ROOT/pipelines/vreslib.sh"
source "$ROOT/pipelines/stability.sh"
# verdict_of RUNDIR STATUS LOG: the verdict line of stability_verdict (it exits, so a subshell)
verdict_of() { (stability_verdict "$@" 2>/dev/null) | awk -F'\t' '$1 == "verdict" {print $2}'; }
# key FILE KEY: the value of a result line
key() { awk -F'\t' -v k="$2" '$1 == k {print $2}' "$1"; }

expect 0 "stiff_vres_front2d: check passes to 0.3 s" \
    "$CASES/stiff_vres_front2d/check" --threads 1 --tmax 0.3 -o "$T/fr"
cp "$OUT" "$T/fr.result"
check "the run completed" grep -q -P '^outcome\tcompleted$' "$T/fr.result"
check "two domains" grep -q -P '^domains\t2$' "$T/fr.result"
check "no non-finite value in either domain" grep -q -P '^nonfinite_values\t0$' "$T/fr.result"
# one particle mass per segment: 32 root segments of 0.4 kg and 136 of the child of 0.1 kg
check "segment bound 26.4 kg (32 x 0.4 + 136 x 0.1)" grep -q -P '^segment_bound_kg\t26.4$' "$T/fr.result"
check "the front entered the box: D1 created particles" \
    awk -v v="$(key "$T/fr.result" ledger_D1)" 'BEGIN {split(v, w, " "); exit !(w[2] > 50)}'
# from 0.22 s the thin front leaves buffer particles of the box without support, which the
# exchange deletes: vres-run stops with an internal error if a domain's cells then stay stale
# (before 567f60a they did, for the next step's forces and the next domain's interpolation)
check "buffer particles deleted for want of support (ledger.tsv's deleted_nosupport)" \
    awk -F'\t' 'NR > 1 && !/^#/ && $16 > 0 {n++} END {exit !(n > 0)}' "$T/fr/ledger.tsv"
check "drift within the bound" awk -v e="$(key "$T/fr.result" error)" -v t="$(key "$T/fr.result" tolerance)" 'BEGIN {exit !(e <= t)}'

# doctored ledgers: the last line of D1 (the file's last line)
cp -r "$T/fr" "$T/gain"; awk -F'\t' -v OFS='\t' 'NR > 1 && !/^#/ {l = $0} {a[NR] = $0} END {for (i = 1; i < NR; i++) print a[i]; $0 = a[NR]; $5 += 1; print}' "$T/fr/ledger.tsv" >"$T/gain/ledger.tsv"
check "verdict with a fluid particle the ledger does not explain: FAIL" [ "$(verdict_of "$T/gain" 0 /dev/null)" = FAIL ]
cp -r "$T/fr" "$T/drift"; sed -i '$ s/\t[^\t]*$/\t0.5/' "$T/drift/ledger.tsv"
check "verdict with a drift of 0.5 (bound 0.165): FAIL" [ "$(verdict_of "$T/drift" 0 /dev/null)" = FAIL ]
cp -r "$T/fr" "$T/pile"; awk -F'\t' -v OFS='\t' '{a[NR] = $0} END {for (i = 1; i < NR; i++) print a[i]; $0 = a[NR]; $6 += 5000; $8 += 5000; $9 += 500; print}' "$T/fr/ledger.tsv" >"$T/pile/ledger.tsv"
check "verdict with 5000 buffer particles created in D1's bands: FAIL" [ "$(verdict_of "$T/pile" 0 /dev/null)" = FAIL ]
cp -r "$T/fr" "$T/nan"; sed -i '$ s/\t[^\t]*$/\tnan/' "$T/nan/ledger.tsv"
check "verdict with a NaN in ledger.tsv: FAIL" [ "$(verdict_of "$T/nan" 0 /dev/null)" = FAIL ]
cp -r "$T/fr" "$T/noledger"; rm "$T/noledger/ledger.tsv"
check "verdict on a coupled run without ledger.tsv: FAIL" [ "$(verdict_of "$T/noledger" 0 /dev/null)" = FAIL ]
check "the untouched run: pass" [ "$(verdict_of "$T/fr" 0 /dev/null)" = pass ]

# one domain: the single-resolution verdict (no fluid mass lost; the error the largest speed
# over c0, tolerance 1)
expect 0 "stiff_vres_front2d --single: check passes to 0.1 s" \
    "$CASES/stiff_vres_front2d/check" --threads 1 --single --tmax 0.1 -o "$T/single"
check "single resolution: no fluid mass lost (fluid_mass_change 0), no ledger" \
    [ "$(key "$OUT" fluid_mass_change)/$(key "$OUT" domains)" = "0/" ]
check "single resolution: error the largest speed over c0 ($(key "$OUT" error)), tolerance 1" \
    awk -v e="$(key "$OUT" error)" -v t="$(key "$OUT" tolerance)" 'BEGIN {exit !(t == 1 && e > 0 && e < 1)}'
