#!/usr/bin/env bash
# vres-run's options and run directory: a store from stdin, --tmax/--tout recorded as
# overrides, the module list printed and recorded, provenance, particle ids kept through the
# cell sorting, -q silence, the snapshots' times on the --tout grid, and VRES_LOOP=general
# giving the specialised loop's results.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run


"$BIN/vres-gencase" -q --dp 0.04 "$CASES/hydrostatic2d/hydrostatic2d_Def.xml" -o "$T/tank.h5" || notok "gencase"

expect 0 "store from stdin, 2 threads" bash -c "'$RUN' --threads 2 --tmax 0.05 --tout 0.01 - -o '$T/run' <'$T/tank.h5'"
check "modules printed" grep -q -E 'modules: wcsph-2d wendland-c2 .*dbc-walls.*ddt-fourtakas\(delta=0\.1\) symplectic cpu-openmp\(2 threads\)' "$ERR"
check "six snapshots for 0.05 s every 0.01 s" [ "$(ls "$T/run"/snap_*.h5 | wc -l)" -eq 6 ]
# an output is written at the first step at or past each multiple of --tout: within one dt
# (about 0.2 h / c0 = 1.3e-4 s here) after it
check "snapshot times on the 0.01 s grid" awk -F'\t' '!/^#/ {k = NR - 2; if ($1 < 0.01 * k || $1 > 0.01 * k + 5e-4) exit 1}' "$T/run/run.tsv"
expect 0 "vres-info reads the last snapshot" "$BIN/vres-info" "$T/run/snap_00005.h5"
check "TimeMax recorded as an override" grep -q -E '^  TimeMax +0\.05 +s +\(set\)$' "$OUT"
check "TimeOut recorded as an override" grep -q -E '^  TimeOut +0\.01 +s +\(set\)$' "$OUT"
check "modules recorded" grep -q -E '^  modules +wcsph-2d .*\(run\)$' "$OUT"
check "history: vres-run above vres-gencase" bash -c "sed -n '/^history/,\$p' '$OUT' | sed -n '2p;3p' | tr '\n' ' ' | grep -q -E 'vres-run .*vres-gencase'"
check "time and step recorded" grep -q -E '^  time +0\.05[0-9]* s, step [1-9][0-9]*$' "$OUT"
# the cell sort reorders particles every step: the ids must travel with them
values /Domains/D0/Id "$T/tank.h5" | sort -n >"$T/id0"
values /Domains/D0/Id "$T/run/snap_00005.h5" | sort -n >"$T/id5"
check "same particle ids after the run" cmp -s "$T/id0" "$T/id5"
ids_moved=$(paste <(values /Domains/D0/Id "$T/tank.h5") <(values /Domains/D0/Id "$T/run/snap_00005.h5") | awk '$1 != $2' | wc -l)
check "particles were reordered by cell ($ids_moved moved)" [ "$ids_moved" -gt 0 ]
# walls stay where they were drawn (DBC): compare positions by id
paste <(values /Domains/D0/Id "$T/tank.h5") <(values /Domains/D0/Type "$T/tank.h5") \
      <(values /Domains/D0/Position "$T/tank.h5" | paste - - -) | sort -n >"$T/p0"
paste <(values /Domains/D0/Id "$T/run/snap_00005.h5") <(values /Domains/D0/Type "$T/run/snap_00005.h5") \
      <(values /Domains/D0/Position "$T/run/snap_00005.h5" | paste - - -) | sort -n >"$T/p5"
check "wall particles did not move" bash -c "cmp -s <(awk '\$2 != 0' '$T/p0') <(awk '\$2 != 0' '$T/p5')"

expect 0 "-q is quiet" "$RUN" -q --tmax 0.01 "$T/tank.h5" -o "$T/quiet"
check "-q: nothing on stderr" [ ! -s "$ERR" ]
expect 0 "--help exits 0" "$RUN" --help
check "--help shows the synopsis" grep -q '^vres-run \[-v|-q\] \[--tmax T\]' "$OUT"

# VRES_LOOP=general (a benchmarking aid, vres-run(1) ENVIRONMENT): the general interaction loop
# adds the same terms in the same order as the scene's specialised one, so the state after the
# run is the same bit for bit (tolerance 0); an unknown value is said, not ignored
expect 0 "VRES_LOOP=general runs" env VRES_LOOP=general "$RUN" --tmax 0.01 "$T/tank.h5" -o "$T/general"
check "VRES_LOOP=general says which loop" grep -q 'VRES_LOOP=general: the general interaction loop' "$ERR"
for ds in Position Velocity Density Id; do
    check "general loop: same $ds as the specialised one" \
        h5diff -q "$T/quiet/snap_00001.h5" "$T/general/snap_00001.h5" "/Domains/D0/$ds" "/Domains/D0/$ds"
done
expect 0 "VRES_LOOP=fancy runs" env VRES_LOOP=fancy "$RUN" --tmax 0.002 "$T/tank.h5" -o "$T/fancy"
check "VRES_LOOP=fancy: warned" grep -q 'VRES_LOOP=fancy not known' "$ERR"

# --profile: the time per phase of the step, printed and written to phases.tsv; the phases and
# the rest add up to the loop's time (each row rounded to 4 digits: within 0.5%), the forces
# took a share (they are most of any run), and the run's state is the same as without it (the
# clocks always run; the option only reports them)
expect 0 "--profile runs" "$RUN" --profile --tmax 0.01 "$T/tank.h5" -o "$T/prof"
check "--profile: the table printed" grep -q -E 'vres-run:   forces +[0-9.e+-]+ s +[0-9.]+%' "$ERR"
check "--profile: phases.tsv has the eight phases, other and total" \
    awk -F'\t' '$1 ~ /^(sort|forces|integrate|walls|mdbc|check|coupling|output|other|total)$/ && NF == 4 {n++}
        END {exit n != 10}' "$T/prof/phases.tsv"
check "--profile: the rows add up to the total" awk -F'\t' '!/^#/ && $1 != "total" {s += $2} $1 == "total" {t = $2}
    END {exit !(t > 0 && s > 0.995 * t && s < 1.005 * t)}' "$T/prof/phases.tsv"
check "--profile: the forces took time" awk -F'\t' '$1 == "forces" {exit !($2 > 0 && $3 > 1)}' "$T/prof/phases.tsv"
check "--profile: no other file than without it" bash -c "diff <(ls '$T/quiet') <(ls '$T/prof' | grep -v '^phases.tsv$')"
check "--profile: same state as without it" h5diff -q "$T/quiet/snap_00001.h5" "$T/prof/snap_00001.h5" /Domains /Domains
check "without --profile: no phases.tsv" [ ! -e "$T/quiet/phases.tsv" ]
