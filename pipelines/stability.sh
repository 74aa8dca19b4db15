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

# fluid_mass FILE: the total mass of the fluid particles (kg), from the Mass dataset.
fluid_mass() {
    paste <(values /Domains/D0/Type "$1") <(values /Domains/D0/Mass "$1") |
        awk '$1 == 0 {m += $2} END {printf "%.15g\n", m}'
}

# nonfinite FILE: how many entries of Position, Velocity, Density and Pressure are not finite
# numbers (h5dump prints them as nan, -nan, inf or -inf).
nonfinite() {
    local d
    for d in Position Velocity Density Pressure; do values "/Domains/D0/$d" "$1"; done |
        awk '!/^-?[0-9]/ || /n/ {n++} END {print n + 0}'
}

# stability_verdict RUNDIR STATUS LOG: report the outcome of a stability run (exit STATUS of
# vres-run, its stderr in LOG) with the lines of the check protocol: outcome, diagnosis,
# mass_rel_change (the error: |m - m0| / m0 of the fluid mass, 0 when no particle is lost),
# max_speed_over_c0, nonfinite_values, tolerance and verdict. Exits 0 when the outcome is
# acceptable, 1 otherwise.
stability_verdict() {
    local d=$1 status=$2 log=$3 first last m0 m1 c0 vmax bad diag ok=1
    first=$(snapshots "$d" | head -1)
    [ -n "$first" ] || { note "$d: no snapshots"; report verdict FAIL; exit 1; }
    m0=$(fluid_mass "$first")
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
    if [ -n "$last" ]; then
        bad=$(nonfinite "$last")
        report nonfinite_values "$bad"
        [ "$bad" -eq 0 ] || { note "$last: $bad values are not finite"; ok=0; }
        m1=$(fluid_mass "$last")
        report error_def "relative change of the fluid mass, first snapshot to $(basename "$last")"
        report error "$(awk -v a="$m0" -v b="$m1" 'BEGIN {d = (b - a) / a; printf "%.3g", d < 0 ? -d : d}')"
    fi
    report tolerance 1e-12
    if [ "$ok" = 1 ] && [ -n "$last" ] && awk -v a="$m0" -v b="$m1" 'BEGIN {d = (b - a) / a; exit !(d < 1e-12 && d > -1e-12)}'; then
        report verdict pass; return 0
    fi
    report verdict FAIL; exit 1
}
