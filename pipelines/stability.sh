# pipelines/stability.sh - the verdict of a stability case (cases/stiff_*/check). Sourced
# after pipelines/vreslib.sh, never run.
#
# DESIGN section 7: a stiff or extreme case must run without NaN and keep its mass, or, when
# it goes unstable, stop with a clear diagnosis and a restartable last snapshot, never write
# garbage. Both outcomes are acceptable; what is judged is that the outcome is one of them:
#   exit 0  the run reached TimeMax; every snapshot's run.tsv line is finite, the fluid mass
#           is the first snapshot's (no particle lost), the largest speed stays below the
#           speed of sound cs0 (a WCSPH particle faster than sound is garbage), and the last
#           snapshot's positions, velocities, densities and pressures are all finite numbers;
#   exit 3  vres-run's diagnosis line names the step, the time, the particle (type, id,
#           position) and the quantity, or a time step below DtMin; snap_last_good.h5 exists,
#           vres-info reads it, its fields are finite and its fluid mass is the first
#           snapshot's;
#   other   a failure.
#
# A coupled run (a store of several domains /Domains/D<k>, vres-partition's; DESIGN section 5)
# exchanges mass between its domains, so "the fluid mass is the first snapshot's" does not hold
# there. Its verdict replaces that test with the ledger (RUNDIR/ledger.tsv, vres-run(1)) and
# reads every domain:
#   finite      run.tsv, ledger.tsv and the last (or last good) snapshot's positions,
#               velocities, densities and pressures of every domain are finite numbers;
#   drift       |total_mass_drift| at every output of ledger.tsv is at most B / M0, the bound
#               the run states itself (vres-run warns past it): one particle mass per
#               interface segment, B = sum over interfaces of count * mass of the receiving
#               domain (from the store: /Interfaces/I<f> count, receiving; /Domains/D<k> mass),
#               M0 the total fluid mass of the ledger's first line. This is the verdict's
#               error and tolerance. After exit 3 the last good snapshot's owned fluid mass
#               (each domain's fluid outside its children's boxes, lib/owner.c's rule) is held
#               to the same bound;
#   closed      the ledger's accounts close, exactly: per domain k and output, with Delta the
#               change since the ledger's first line,
#                   r_k = Delta(n_fluid + n_buffer) - Delta created + Delta(deleted_buffer
#                         + deleted_fluid + deleted_nosupport)
#               is 0, except for fluid excluded from the simulation domain (run.tsv's
#               n_excluded, which does not say which domain): every r_k <= 0 and
#               sum_k r_k = -Delta n_excluded. Type changes stay inside a domain and cancel.
#               Also the owned fluid mass recomputed from the first and last snapshots equals
#               the ledger's total_fluid_mass_kg there (relative 1e-9): the ledger reports
#               what the store holds;
#   no runaway  creation is bounded by what can flow: (a) per domain and output,
#               n_buffer_k <= 1.5 cap_k, cap_k the particles of spacing dp_k that fill its
#               buffer bands (its own band, buffer box minus fluid box, and its band in each
#               child's hole, hole minus inner box, both clipped to the root's box; walls
#               counted as water, so cap_k is an upper bound): buffer particles move with the
#               flow and leave the band, so a segment that keeps creating where nothing leaves
#               piles them up; the number density of fixed-mass particles is rho/m, at most
#               RhopOutMax/rhop0 = 1.3 times the lattice's before the run stops, and 1.5
#               leaves room for the disorder of a splash; (b) per domain and output,
#               n_fluid_k * m_k <= M0 + B: no domain holds more fluid than there is (with
#               overlappingh a parent's fluid inside a child's box counts too: still less than
#               all); (c) summed over domains, created minus deleted mass
#               sum_k (Delta created_kg - Delta deleted_kg) <= B + sum_k 1.5 cap_k m_k: mass
#               born on one side of an interface is what was deleted on the other side of it
#               (the same flow, seen by both domains), up to what the bands and segments hold
#               in transit. A runaway violates (a) within a few hundred steps (one particle per
#               segment per step) and (b), (c) soon after.
# A single-domain run is judged exactly as above (the fluid mass to 1e-12; with inlet/outlet
# zones, which exchange fluid, their books and fill instead: zones_books). Its error line is
# the largest speed over c0 (tolerance 1: the bound above), a quantity every run changes; the
# fluid mass of fixed-mass particles cannot change unless one is lost, so it is a condition
# (fluid_mass_change), not the error. Also reported: the largest density deviation
# |rho - rhop0|/rhop0 over run.tsv, with the RhopOutMin..RhopOutMax limits the run stops at.

# fluid_mass FILE: the total mass of the fluid particles (kg), from the Mass dataset.
fluid_mass() {
    paste <(values /Domains/D0/Type "$1") <(values /Domains/D0/Mass "$1") |
        awk '$1 == 0 {m += $2} END {printf "%.15g\n", m}'
}

# nonfinite FILE [ALL]: how many entries of Position, Velocity, Density and Pressure are not
# finite numbers (h5dump prints them as nan, -nan, inf or -inf): of D0, or with ALL = all of
# every domain.
nonfinite() {
    local d k n=1
    [ "${2:-}" = all ] && n=$(domains "$1")
    for ((k = 0; k < n; k++)); do
        for d in Position Velocity Density Pressure; do values "/Domains/D$k/$d" "$1"; done
    done | awk '!/^-?[0-9]/ || /n/ {n++} END {print n + 0}'
}

# tree_table FILE: one line per domain of a coupled store: k parent dp mass, then the x y z
# corners (min, max) of its fluid box, its buffer box, and of the hole and inner boxes it
# leaves in its parent (vres-store(5), kernels/region.h), 28 columns.
tree_table() {
    local f=$1 k n a
    n=$(domains "$f")
    for ((k = 0; k < n; k++)); do
        printf '%s' "$k"
        for a in parent dp mass; do printf ' %s' "$(attr "/Domains/D$k/$a" "$f")"; done
        for a in box_min box_max buffer_min buffer_max hole_min hole_max inner_min inner_max; do
            printf ' %s' "$(attrv "/Domains/D$k/$a" "$f" | tr '\n' ' ')"
        done
        printf '\n'
    done | awk '{$1 = $1; print}'
}

# segment_bound FILE: B (kg), one particle mass per interface segment, the bound of the total
# fluid mass drift that vres-run warns past: the sum over /Interfaces/I<f> of its count times
# the particle mass of its receiving domain.
segment_bound() {
    local f=$1 i n c r
    n=$(h5ls "$f/Interfaces" 2>/dev/null | grep -c '^I[0-9]')
    for ((i = 0; i < n; i++)); do
        c=$(attr "/Interfaces/I$i/count" "$f") r=$(attr "/Interfaces/I$i/receiving" "$f")
        echo "$c $(attr "/Domains/D$r/mass" "$f")"
    done | awk '{b += $1 * $2} END {printf "%.9g\n", b + 0}'
}

# band_capacity TREE DIM: per domain "k cap_k": the particles of spacing dp_k that fill its
# buffer bands (own band: buffer box minus fluid box; in each child j: j's hole minus j's inner
# box), every box clipped to the root's box, from a tree_table TREE of a DIM-dimensional store.
band_capacity() {
    awk -v dim="$2" '
        function vol(lo1, lo2, lo3, hi1, hi2, hi3,    v, a, l, h) {
            v = 1
            for (a = 1; a <= 3; a++) {
                if (dim == 2 && a == 2) continue
                l = (a == 1 ? lo1 : a == 2 ? lo2 : lo3); h = (a == 1 ? hi1 : a == 2 ? hi2 : hi3)
                if (l < R[a]) l = R[a]; if (h > R[a + 3]) h = R[a + 3]
                if (h <= l) return 0
                v *= h - l
            }
            return v
        }
        { for (c = 1; c <= NF; c++) t[NR, c] = $c; n = NR }
        END {
            for (c = 1; c <= 6; c++) R[c] = t[1, 4 + c]
            for (r = 1; r <= n; r++) V[r] = 0
            for (r = 2; r <= n; r++) {
                V[r] += vol(t[r,11], t[r,12], t[r,13], t[r,14], t[r,15], t[r,16]) - vol(t[r,5], t[r,6], t[r,7], t[r,8], t[r,9], t[r,10])
                p = t[r, 2] + 1
                V[p] += vol(t[r,17], t[r,18], t[r,19], t[r,20], t[r,21], t[r,22]) - vol(t[r,23], t[r,24], t[r,25], t[r,26], t[r,27], t[r,28])
            }
            for (r = 1; r <= n; r++) printf "%d %.6g\n", r - 1, V[r] / t[r, 3] ^ dim
        }' "$1"
}

# owned_mass FILE TREE: the total fluid mass (kg) the domains own (lib/owner.c): each domain's
# fluid particles outside the fluid boxes of its children, from a tree_table TREE.
owned_mass() {
    local f=$1 k n
    n=$(domains "$f")
    for ((k = 0; k < n; k++)); do
        paste <(values /Domains/D$k/Type "$f") <(values /Domains/D$k/Mass "$f") \
              <(values /Domains/D$k/Position "$f" | paste - - -) |
            awk -v k="$k" -v dim="$(param dim "$f")" '
                FNR == NR { if ($2 == k) { nc++; for (a = 1; a <= 6; a++) B[nc, a] = $(4 + a) } ; next }
                $1 == 0 {
                    x[1] = $3; x[2] = $4; x[3] = $5; inside = 0
                    for (c = 1; c <= nc && !inside; c++) {
                        inside = 1
                        for (a = 1; a <= 3; a++)
                            if (!(dim == 2 && a == 2) && !(x[a] >= B[c, a] && x[a] <= B[c, a + 3])) inside = 0
                    }
                    if (!inside) m += $2
                }
                END {printf "%.15g\n", m + 0}' "$2" -
    done | awk '{m += $1} END {printf "%.15g\n", m + 0}'
}

# ledger_verdict RUNDIR FIRST LAST: the coupled run's checks of the header above (drift,
# closed, no runaway) on RUNDIR/ledger.tsv, the store FIRST (its first snapshot) and LAST (the
# last or last good snapshot, or empty); reports their lines and sets LEDGER_OK (1 or 0),
# DRIFT_MAX and DRIFT_TOL.
ledger_verdict() {
    local d=$1 first=$2 last=$3 L=$1/ledger.tsv tree B M0 dim caps bad mo ml
    LEDGER_OK=1 DRIFT_MAX=nan DRIFT_TOL=0
    [ -f "$L" ] || { note "$d: no ledger.tsv (a coupled run writes one)"; LEDGER_OK=0; return; }
    if grep -v '^#' "$L" | grep -q -i -E 'nan|inf'; then note "ledger.tsv holds a value that is not finite"; LEDGER_OK=0; fi
    tree=$WORK_STAB/tree; tree_table "$first" >"$tree"
    dim=$(param dim "$first")
    B=$(segment_bound "$first")
    M0=$(awk -F'\t' '!/^#/ {print $19; exit}' "$L")
    DRIFT_TOL=$(awk -v b="$B" -v m="$M0" 'BEGIN {printf "%.4g", (m > 0 ? b / m : 0)}')
    report domains "$(domains "$first")"
    report segment_bound_kg "$B"
    report fluid_mass0_kg "$M0"
    band_capacity "$tree" "$dim" >"$WORK_STAB/caps"
    report band_capacity "$(awk '{printf "%sD%s %d", (NR > 1 ? ", " : ""), $1, $2}' "$WORK_STAB/caps")"
    # every output: drift, closure (with run.tsv's exclusions by step), runaway tests (a), (b), (c)
    awk -F'\t' -v B="$B" -v M0="$M0" -v tree="$tree" -v caps="$WORK_STAB/caps" -v tol="$DRIFT_TOL" '
        FILENAME == tree { split($0, w, " "); mass[w[1]] = w[4]; next }
        FILENAME == caps { split($0, w, " "); cap[w[1]] = w[2]; next }
        FILENAME ~ /run\.tsv$/ { if (!/^#/) excl[$2] = $12; next }
        /^#/ { next }
        {
            s = $2; k = $3; N = $5 + $6; del = $12 + $14 + $16; delkg = $13 + $15 + $17
            if (!(k in N0)) { N0[k] = N; C0[k] = $8; D0[k] = del; CK0[k] = $9; DK0[k] = delkg; if (x0 == "") x0 = excl[s] + 0 }
            r = (N - N0[k]) - ($8 - C0[k]) + (del - D0[k])
            if (r > 0) { printf "closed: D%d at t = %s s: r = %d > 0 (particles appeared outside the ledger)\n", k, $1, r; bad++ }
            R[s] += r; T[s] = $1; net[s] += ($9 - CK0[k]) - (delkg - DK0[k])
            if ($6 > 1.5 * cap[k]) { printf "runaway (a): D%d at t = %s s: %d buffer particles, over 1.5 x %d that fill its bands\n", k, $1, $6, cap[k]; bad++ }
            if ($5 * mass[k] > M0 + B) { printf "runaway (b): D%d at t = %s s: %d fluid particles, %.6g kg, over M0 + B = %.6g kg\n", k, $1, $5, $5 * mass[k], M0 + B; bad++ }
            dr = $20 < 0 ? -$20 : $20
            if (dr > dmax) { dmax = dr; tmax = $1 }
            if (dr > tol) nover++
            cr[k] = $8; dl[k] = del; crk[k] = $9; dlk[k] = delkg
            if (!(s in seen)) { seen[s] = 1; order[++no] = s }
        }
        END {
            for (k in cap) hold += 1.5 * cap[k] * mass[k]
            for (i = 1; i <= no; i++) {
                s = order[i]; dx = (s in excl ? excl[s] : x0) - x0
                if (R[s] != -dx) { printf "closed: at t = %s s the domains count %d particles fewer than the ledger explains (run.tsv: %d excluded)\n", T[s], -R[s], dx; bad++ }
                if (net[s] > B + hold) { printf "runaway (c): at t = %s s created minus deleted is %.6g kg, over B + the bands hold (%.6g kg)\n", T[s], net[s], B + hold; bad++ }
                if (net[s] > nmax) nmax = net[s]
            }
            printf "@ drift_max %.4g %s\n@ net_created_max_kg %.6g %.6g\n@ outputs_over_bound %d\n", dmax, tmax, nmax, B + hold, nover
            for (k = 0; k in cr; k++) printf "@ ledger_D%d created %d (%.6g kg), deleted %d (%.6g kg)\n", k, cr[k], crk[k], dl[k], dlk[k]
            exit bad > 0
        }' "$tree" "$WORK_STAB/caps" "$d/run.tsv" "$L" >"$WORK_STAB/ledger.out" || LEDGER_OK=0
    grep -v '^@' "$WORK_STAB/ledger.out" | while read -r l; do note "$l"; done
    DRIFT_MAX=$(awk '$2 == "drift_max" {print $3}' "$WORK_STAB/ledger.out")
    report max_drift "$DRIFT_MAX at t = $(awk '$2 == "drift_max" {print $4}' "$WORK_STAB/ledger.out") s"
    report drift_bound "$DRIFT_TOL (B / M0: one particle mass per segment, vres-run's warning)"
    report net_created_max_kg "$(awk '$2 == "net_created_max_kg" {print $3 " (bound " $4 ")"}' "$WORK_STAB/ledger.out")"
    awk '$2 ~ /^ledger_D/ {k = $2; sub(/^ledger_/, "", k); $1 = $2 = ""; sub(/^ */, ""); print k "\t" $0}' "$WORK_STAB/ledger.out" |
        while IFS=$'\t' read -r k v; do report "ledger_$k" "$v"; done
    awk '$2 == "outputs_over_bound" {exit !($3 == 0)}' "$WORK_STAB/ledger.out" ||
        { note "the total mass drift passed B / M0 = $DRIFT_TOL at some output (max $DRIFT_MAX)"; LEDGER_OK=0; }
    # the ledger reports what the store holds: owned fluid mass of the first and last snapshot
    mo=$(owned_mass "$first" "$tree")
    awk -v a="$mo" -v b="$M0" 'BEGIN {d = a - b; exit !(d <= 1e-9 * b && d >= -1e-9 * b)}' ||
        { note "$first: owned fluid mass $mo kg, the ledger says $M0 kg"; LEDGER_OK=0; }
    if [ -n "$last" ]; then
        ml=$(owned_mass "$last" "$tree")
        report owned_fluid_mass_last_kg "$ml"
        if [ "$(basename "$last")" = snap_last_good.h5 ]; then
            awk -v a="$ml" -v m="$M0" -v b="$B" 'BEGIN {d = a - m; exit !(d <= b && d >= -b)}' ||
                { note "$last: owned fluid mass $ml kg drifted more than B = $B kg from $M0 kg"; LEDGER_OK=0; }
        else
            awk -F'\t' -v a="$ml" '!/^#/ {m = $19} END {d = a - m; exit !(d <= 1e-9 * m && d >= -1e-9 * m)}' "$L" ||
                { note "$last: owned fluid mass $ml kg, the ledger's last line says otherwise"; LEDGER_OK=0; }
        fi
    fi
}

# coupled_verdict RUNDIR FIRST LAST OK: the end of stability_verdict for a coupled run (see the
# header): the non-finite values of every domain of LAST (the last or last good snapshot; empty
# when there is none), then ledger_verdict; error and tolerance are the largest |drift| and
# B / M0. OK is 0 when an earlier test failed. Returns 0 on pass, exits 1 on FAIL.
coupled_verdict() {
    local d=$1 first=$2 last=$3 ok=$4 bad
    WORK_STAB=$(mktemp -d "${TMPDIR:-/tmp}/vres-stab.XXXXXX") || die "cannot make a temporary directory"
    if [ -n "$last" ]; then
        bad=$(nonfinite "$last" all)
        report nonfinite_values "$bad"
        [ "$bad" -eq 0 ] || { note "$last: $bad values are not finite"; ok=0; }
    else
        ok=0
    fi
    ledger_verdict "$d" "$first" "$last"
    rm -rf "$WORK_STAB"
    [ "$LEDGER_OK" = 1 ] || ok=0
    report error_def "largest |total_mass_drift| of ledger.tsv over the outputs (relative, all domains' owned fluid)"
    report error "$DRIFT_MAX"
    report tolerance "$DRIFT_TOL"
    if [ "$ok" = 1 ]; then report verdict pass; return 0; fi
    report verdict FAIL; exit 1
}

# stability_verdict RUNDIR STATUS LOG: report the outcome of a stability run (exit STATUS of
# vres-run, its stderr in LOG) with the lines of the check protocol: outcome, diagnosis,
# mass_rel_change (the error: |m - m0| / m0 of the fluid mass, 0 when no particle is lost),
# max_speed_over_c0, nonfinite_values, tolerance and verdict. Exits 0 when the outcome is
# acceptable, 1 otherwise. A coupled run (several domains) ends in coupled_verdict: the
# ledger's drift, closure and runaway tests instead of the fluid mass.
# zones_books RUNDIR FIRST: a single-domain run with inlet/outlet zones (the store's parameter
# inout_zones) exchanges fluid through them, so its fluid mass is not the first snapshot's.
# Instead its books must close and its zones must not pile particles up: |total_mass_drift| of
# every ledger.tsv line (the fluid's mass against its start plus what the zones gave it) at
# most 1e-9, and each zone's inlet particles (ledger.tsv's n_buffer on its Z<k> lines) at most
# 1.5 times its capacity, layers times segments (one per dp of its face): the number density of
# fixed-mass particles is rho/m, at most 1.3 times the lattice's before RhopOutMax stops the
# run, and 1.5 leaves room for disorder. Reports zones_ledger_drift and zones_fill (the largest
# count over capacity). 0, or 1 after saying why.
zones_books() {
    local d=$1 first=$2 nz k dp cap caps="" drift fill
    nz=$(param inout_zones "$first")
    dp=$(attr /Domains/D0/dp "$first")
    for ((k = 1; k <= nz; k++)); do
        cap=$(awk -v l="$(param "inout_Z${k}_options" "$first")" -v e="$(attrv "/Parameters/inout_Z${k}_extent" "$first" | paste -s -d ' ')" \
            -v dp="$dp" -v dim="$(attr /dim "$first")" 'BEGIN {split(e, x, " "); n = int(x[1] / dp + 0.5); if (n < 1) n = 1
                if (dim == 3) {m = int(x[2] / dp + 0.5); n *= m < 1 ? 1 : m}; print l * n}')
        caps="$caps Z$k=$cap"
    done
    drift=$(awk -F'\t' '!/^#/ {v = $20; if (v < 0) v = -v; if (v > D) D = v; n++} END {if (n) printf "%.3g\n", D; else print "none"}' "$d/ledger.tsv" 2>/dev/null)
    fill=$(awk -F'\t' -v caps="$caps" 'BEGIN {n = split(caps, c, " "); for (i = 1; i <= n; i++) {split(c[i], kv, "="); cap[kv[1]] = kv[2]}}
        !/^#/ && ($3 in cap) {f = $6 / cap[$3]; if (f > F) F = f; m++} END {if (m) printf "%.3g\n", F; else print "none"}' "$d/ledger.tsv" 2>/dev/null)
    report zones_ledger_drift "${drift:-none}"
    report zones_fill "${fill:-none}"
    [ "${drift:-none}" != none ] && [ "${fill:-none}" != none ] ||
        { note "ledger.tsv has no zone lines: the zones' books cannot be read"; return 1; }
    awk -v d="$drift" 'BEGIN {exit !(d <= 1e-9)}' || { note "the zones' books do not close: drift $drift"; return 1; }
    awk -v f="$fill" 'BEGIN {exit !(f <= 1.5)}' || { note "a zone holds $fill times its capacity: particles pile up"; return 1; }
    return 0
}

stability_verdict() {
    local d=$1 status=$2 log=$3 first last m0 m1 c0 vmax bad diag ok=1 nd
    first=$(snapshots "$d" | head -1)
    [ -n "$first" ] || { note "$d: no snapshots"; report verdict FAIL; exit 1; }
    nd=$(domains "$first")
    [ "$nd" -gt 1 ] || m0=$(fluid_mass "$first")
    c0=$(param cs0 "$first")
    vmax=$(awk -F'\t' '!/^#/ && $7 > v {v = $7} END {print v + 0}' "$d/run.tsv")
    report max_speed_m_s "$vmax"
    report max_speed_over_c0 "$(awk -v v="$vmax" -v c="$c0" 'BEGIN {printf "%.4f", v / c}')"
    if grep -v '^#' "$d/run.tsv" | grep -q -i -E 'nan|inf'; then
        note "run.tsv holds a value that is not finite"; ok=0
    fi
    awk -v v="$vmax" -v c="$c0" 'BEGIN {exit !(v < c)}' ||
        { note "a particle moved faster than the speed of sound ($vmax >= $c0 m/s)"; ok=0; }
    case $status in
        0)
            report outcome "completed"
            run_complete "$d" || ok=0
            last=$(snapshots "$d" | tail -1) ;;
        3)
            report outcome "stopped (exit 3)"
            diag=$(grep -m1 -E 'unstable at step' "$log")
            report diagnosis "${diag#vres-run: }"
            if ! grep -q -E 'unstable at step [0-9]+, t = [0-9.e+-]+ s: ([a-z]+ particle id [0-9]+ at \(|time step .* below DtMin)' <<<"$diag"; then
                note "the diagnosis does not name the step, time and particle: '$diag'"; ok=0
            fi
            last=$d/snap_last_good.h5
            if [ ! -f "$last" ] || ! "$VRES_BIN/vres-info" -q "$last" >/dev/null 2>&1; then
                note "no readable snap_last_good.h5 after exit 3"; ok=0; last=""
            fi ;;
        *)
            report outcome "failed (exit $status)"; note "vres-run exited $status"; ok=0; last="" ;;
    esac
    if [ "$nd" -gt 1 ]; then
        coupled_verdict "$d" "$first" "$last" "$ok"
        return
    fi
    # the largest density deviation over the run (run.tsv's fluid rho_min, rho_max against
    # rhop0): reported, with the limits RhopOutMin..RhopOutMax the run stops at
    local rho0 dev
    rho0=$(param rhop0 "$first")
    dev=$(awk -F'\t' -v r="$rho0" '!/^#/ {n++; a = ($8 - r) / r; b = ($9 - r) / r; a = a < 0 ? -a : a; b = b < 0 ? -b : b
                                    if (a > d) d = a; if (b > d) d = b} END {if (n) printf "%.4g", d; else print "none"}' "$d/run.tsv")
    report max_density_deviation "$dev"
    report density_limits_kg_m3 "$(param RhopOutMin "$first" 2>/dev/null || echo 700)-$(param RhopOutMax "$first" 2>/dev/null || echo 1300)"
    [ "$dev" != none ] || { note "run.tsv has no rows"; ok=0; }
    if [ -n "$last" ]; then
        bad=$(nonfinite "$last")
        report nonfinite_values "$bad"
        [ "$bad" -eq 0 ] || { note "$last: $bad values are not finite"; ok=0; }
        if [ "$(param inout_zones "$first" 2>/dev/null || echo 0)" -gt 0 ] 2>/dev/null; then
            zones_books "$d" "$first" || ok=0
        else
            m1=$(fluid_mass "$last")
            # no particle may be lost: fixed masses make any other change a lost or excluded particle
            report fluid_mass_change "$(awk -v a="$m0" -v b="$m1" 'BEGIN {d = (b - a) / a; printf "%.3g", d < 0 ? -d : d}')"
            awk -v a="$m0" -v b="$m1" 'BEGIN {d = (b - a) / a; exit !(d < 1e-12 && d > -1e-12)}' ||
                { note "the fluid mass changed from $m0 to $m1 kg: particles were lost"; ok=0; }
        fi
    fi
    # the error: the largest speed against its bound, the speed of sound (a quantity every run
    # changes, where the fluid mass cannot change without a particle lost)
    report error_def "largest speed over the speed of sound c0 (run.tsv), bound 1"
    report error "$(awk -v v="$vmax" -v c="$c0" 'BEGIN {printf "%.4g", v / c}')"
    report tolerance 1
    if [ "$ok" = 1 ] && [ -n "$last" ]; then
        report verdict pass; return 0
    fi
    report verdict FAIL; exit 1
}
