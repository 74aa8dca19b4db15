#!/usr/bin/env bash
# vres-run --restart with several domains continues the coupled run bit for bit (DESIGN 3: "a
# restart continues to the same result"; vres-run(1), Restart): the particles of every domain,
# the interface segments' accumulated masses, run.tsv's times and steps and ledger.tsv's lines
# after the restart are those of the uninterrupted run, whichever snapshot it starts from.
#
# The case is cases/hydrostatic_vres2d under a sideways gravity of 3 m/s^2 (the tank as if
# tilted), so that in 0.1 s the water crosses the interface: buffer particles turn fluid, fluid
# turns buffer, segments create particles and buffer particles past the band's edge are
# deleted, in the part of the run that the restart continues (checked below, so that the test
# still covers them if the physics changes). At rest nothing of that happens in a short run.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
tilted_tank

# The uninterrupted run: 5 outputs after the start (about 1600 steps).
expect 0 "uninterrupted coupled run to 0.1 s, 5 outputs" "$RUN" -q --tmax 0.1 --tout 0.02 "$T/parts.h5" -o "$T/a"
check "snapshots 0 to 5 written" [ -f "$T/a/snap_00005.h5" -a ! -e "$T/a/snap_00006.h5" ]

# The default segment flux (capped, vres-run(1)) never creates more than the donor's particles
# carried across: on every interface of every snapshot the crossing count left after creations
# (Crossed) is at least the interpolated mass left (Mass); and the count is not all zero.
# sum_ds FILE DATASET: the sum of a dataset's values, at full precision
sum_ds() { h5dump -m '%.17g' -y -w 0 -d "$2" "$1" | sed -n '/DATA {/,/}/p' | tr -c '0-9eE.+\n-' ' ' |
    awk '{for (i = 1; i <= NF; i++) s += $i} END {printf "%.17g\n", s}'; }
capped_bad= capped_any=0
for k in 1 2 3 4 5; do
    f=$T/a/$(printf 'snap_%05d.h5' $k)
    for i in $(h5ls "$f/Interfaces" | awk '{print $1}'); do
        cr=$(sum_ds "$f" "/Interfaces/$i/Crossed") ms=$(sum_ds "$f" "/Interfaces/$i/Mass")
        awk -v c="$cr" -v m="$ms" 'BEGIN {exit !(c != 0)}' && capped_any=1
        awk -v c="$cr" -v m="$ms" 'BEGIN {exit !(c >= m - 1e-9)}' || capped_bad="$capped_bad snap $k $i: Crossed $cr < Mass $ms;"
    done
done
check "the crossing count is kept in the snapshots (not all zero)" [ "$capped_any" = 1 ]
check "capped flux: Crossed >= Mass on every interface of snapshots 1-5${capped_bad:+ ($capped_bad)}" [ -z "$capped_bad" ]

# ledger.tsv column COL (1-based, ledger.tsv's header) summed over domains on the lines of step
# STEP, from run directory DIR
ledger_sum() { awk -F'\t' -v c="$3" -v s="$2" '!/^#/ && $2 == s {n += $c} END {print n + 0}' "$1/ledger.tsv"; }
# the step of output K (0-based) in run.tsv
out_step() { grep -v '^#' "$1/run.tsv" | sed -n "$(($2 + 1))p" | cut -f2; }
s2=$(out_step "$T/a" 2)
s5=$(out_step "$T/a" 5)
# columns: 8 created, 10 buffer_to_fluid, 11 fluid_to_buffer, 12 deleted_buffer (cumulative)
for ev in 8:created 10:buffer_to_fluid 11:fluid_to_buffer 12:deleted_buffer; do
    c=${ev%%:*} name=${ev#*:}
    check "the continued part (steps $s2..$s5) has $name events" \
        [ "$(ledger_sum "$T/a" "$s5" "$c")" -gt "$(ledger_sum "$T/a" "$s2" "$c")" ]
done

# same_snaps A B K[:L]...: snapshot K of run directory A and snapshot L (default K) of B hold
# the same datasets, bit for bit (h5diff without a tolerance compares exactly): every dataset
# of every domain and the mass and crossing count of every interface, listed from A's snapshot with h5ls.
same_snaps() {
    local a=$1 b=$2 k fa fb d ds i bad; shift 2
    for k in "$@"; do
        fa=$a/$(printf 'snap_%05d.h5' "${k%%:*}") fb=$b/$(printf 'snap_%05d.h5' "${k#*:}")
        bad=
        for d in $(h5ls "$fa/Domains" | awk '{print $1}'); do
            for ds in Position Velocity Density Pressure Mass Type Mk Id; do
                h5diff -q "$fa" "$fb" "/Domains/$d/$ds" "/Domains/$d/$ds" >/dev/null || bad="$bad $d/$ds"
            done
        done
        for i in $(h5ls "$fa/Interfaces" | awk '{print $1}'); do
            for ds in Mass Crossed; do
                h5diff -q "$fa" "$fb" "/Interfaces/$i/$ds" "/Interfaces/$i/$ds" >/dev/null || bad="$bad $i/$ds"
            done
        done
        if [ -z "$bad" ] && [ -n "$(h5ls "$fa/Interfaces")" ]; then ok "${fb#$T/}: every domain and interface equal"
        else notok "${fb#$T/}: differs from ${fa#$T/} in$bad"; fi
    done
}
check "the uninterrupted run has two domains and two interfaces" \
    [ "$(h5ls "$T/a/snap_00005.h5/Domains" | wc -l)" -eq 2 -a "$(h5ls "$T/a/snap_00005.h5/Interfaces" | wc -l)" -eq 2 ]

# 1. In a copy of the run directory from snapshot 2, in its own directory (the default).
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00002.h5 in its own directory" "$RUN" --threads 1 --restart "$T/b/snap_00002.h5"
check "says it removed the snapshots it rewrites" grep -q 'removed snap_00003.h5 .. snap_00005.h5' "$ERR"
same_snaps "$T/a" "$T/b" 3 4 5
check "run.tsv: same times, steps, counts, masses, speeds and densities" \
    diff <(grep -v '^#' "$T/a/run.tsv" | cut -f1-9) <(grep -v '^#' "$T/b/run.tsv" | cut -f1-9)
check "ledger.tsv: the same file (earlier lines kept, later ones rewritten alike)" cmp -s "$T/a/ledger.tsv" "$T/b/ledger.tsv"

# 2. From snapshot 4, into a new directory: its ledger.tsv has a header and the last output's
# lines, equal to the uninterrupted run's.
expect 0 "restart from snap_00004.h5 into a new -o" "$RUN" -q --restart "$T/a/snap_00004.h5" -o "$T/c"
same_snaps "$T/a" "$T/c" 5
check "the new ledger.tsv has the header and one line per domain" \
    [ "$(head -1 "$T/c/ledger.tsv")" = "$(head -1 "$T/a/ledger.tsv")" -a "$(grep -c -v '^#' "$T/c/ledger.tsv")" -eq 2 ]
check "its lines are the uninterrupted run's last ones" \
    diff <(grep -v '^#' "$T/c/ledger.tsv") <(grep -v '^#' "$T/a/ledger.tsv" | tail -2)

# 3. From the starting snapshot, with one output at 0.06 s (a new --tout restarts the schedule
# at the snapshot's time; outputs change nothing of the state): the ledger's drift refers to
# the total fluid mass at the run's start (run_mass0 in every snapshot), not at the restart's
# first output, by which the water has crossed the interface and the total has changed.
t3=$(grep -v '^#' "$T/a/run.tsv" | sed -n 4p | cut -f1)
check "the total fluid mass changed by output 3 (t = $t3 s)" \
    [ "$(ledger_sum "$T/a" "$(out_step "$T/a" 3)" 7)" != "$(ledger_sum "$T/a" 0 7)" ]
expect 0 "restart from snap_00000.h5 with --tmax 0.06 --tout 0.06 into a new -o" \
    "$RUN" -q --restart "$T/a/snap_00000.h5" --tmax 0.06 --tout 0.06 -o "$T/z"
same_snaps "$T/a" "$T/z" 3:1
check "its ledger.tsv lines, drift included, are the uninterrupted run's at output 3" \
    diff <(grep -v '^#' "$T/z/ledger.tsv") <(grep -v '^#' "$T/a/ledger.tsv" | sed -n 7,8p)
# the ledger prints 9 significant digits: the stored value must agree to that
m0=$(grep -v '^#' "$T/a/ledger.tsv" | head -1 | cut -f19)
for k in 0 5; do
    f=$(printf 'snap_%05d.h5' $k)
    v=$(h5dump -m '%.17g' -a /Parameters/run_mass0 "$T/a/$f" | sed -n 's/^ *(0): //p')
    check "$f: run_mass0 ($v kg) is the total fluid mass at the start ($m0 kg)" \
        awk -v a="$v" -v b="$m0" 'BEGIN {exit !(a - b <= 1e-8 * b && b - a <= 1e-8 * b)}'
done

# ---- the coupling's options kept by a restart
# option_kept OPTION VALUE PARAM RECORDED BAD MESSAGE: a coupled run to 0.04 s with --OPTION VALUE
# records PARAM = RECORDED in its snapshots; a restart from its snap_00001.h5 without the option
# continues with it, bit for bit; the option changes the flow against the default run's at 0.04 s;
# --OPTION BAD is refused (exit 2, MESSAGE) with nothing written
option_kept() {
    local opt=$1 val=$2 par=$3 rec=$4 bad=$5 msg=$6 d="$T/$1-$2" v
    expect 0 "coupled run with --$opt $val to 0.04 s" "$RUN" -q "--$opt" "$val" --tmax 0.04 --tout 0.02 "$T/parts.h5" -o "$d"
    v=$(h5dump -a "/Parameters/$par" "$d/snap_00001.h5" | sed -n 's/^ *(0): //p')
    check "snap_00001.h5 records $par $rec ($v)" [ "$v" = "$rec" ]
    expect 0 "restart from its snap_00001.h5 without --$opt" "$RUN" -q --restart "$d/snap_00001.h5" -o "$d-r"
    same_snaps "$d" "$d-r" 2:2
    check "the run with --$opt $val differs from the default run at 0.04 s" \
        sh -c "! h5diff -q '$T/a/snap_00002.h5' '$d/snap_00002.h5' /Domains/D1/Velocity /Domains/D1/Velocity >/dev/null"
    expect_err 2 "$msg" "--$opt $bad refused (exit 2) with its message" "$RUN" "--$opt" "$bad" "$T/parts.h5" -o "$T/$opt-bad"
    check "nothing written for it" [ ! -e "$T/$opt-bad" ]
}
# the interpolation order: first order against the default auto
option_kept vres-order 1 run_vres_order 1 3 "--vres-order 3: must be 1, 2 or auto"
# the second order's condition limit: 50 (below the top row of a surface's 134..180,
# kernels/interp_liu.h) against the default 1000, which the default run records
option_kept vres-cond2 50 run_vres_cond2 50 0.5 "--vres-cond2 0.5: must be at least 1"
v=$(h5dump -a /Parameters/run_vres_cond2 "$T/a/snap_00001.h5" | sed -n 's/^ *(0): //p')
check "the default run records run_vres_cond2 1000 ($v)" [ "$v" = 1000 ]

# ---- the segments' flux (--vres-flux): kept in the snapshots (run_vres_flux, kernels/couple.h's
# code: balanced 0), and a restart without the option (nor VRES_FLUX) continues with the run's
# flux, bit for bit; the flux changes the flow once the tilted water creates particles
expect 0 "coupled run with --vres-flux balanced to 0.06 s" env -u VRES_FLUX "$RUN" -q --vres-flux balanced --tmax 0.06 --tout 0.02 "$T/parts.h5" -o "$T/fb"
v=$(h5dump -a /Parameters/run_vres_flux "$T/fb/snap_00002.h5" | sed -n 's/^ *(0): //p')
check "snap_00002.h5 records run_vres_flux 0, balanced ($v)" [ "$v" = 0 ]
expect 0 "restart from its snap_00001.h5 without --vres-flux" env -u VRES_FLUX "$RUN" -q --restart "$T/fb/snap_00001.h5" -o "$T/fbr"
same_snaps "$T/fb" "$T/fbr" 2 3
check "the balanced run differs from the default run at 0.06 s" \
    sh -c "! h5diff -q '$T/a/snap_00003.h5' '$T/fb/snap_00003.h5' /Interfaces/I0/Mass /Interfaces/I0/Mass >/dev/null"
expect_err 2 "--vres-flux both: must be capped, interp, balanced or crossing" "--vres-flux both refused (exit 2) with its message" \
    "$RUN" --vres-flux both "$T/parts.h5" -o "$T/fx"
check "nothing written for it" [ ! -e "$T/fx" ]
