#!/usr/bin/env bash
# pipelines/vres_compare.sh - variable against single resolution on one case (issue 7 item 6):
# the case's check run three times, single resolution at the coarse dp, single resolution at the
# fine dp (coarse / dpratio), and variable resolution (the case's refinement box at that fine
# dp, through vres-partition), then one table and two plots:
#
#   pipelines/vres_compare.sh CASE DP_COARSE [DPRATIO] [THREADS]
#
#   pipelines/reports/CASE/vres_compare.tsv   variant, dp, particles, steps, run time, error,
#                                             the check's verdict, and vres-run's CPU time when
#                                             the check reports one (cpu_time_s; "-" if not);
#                                             the criterion in its footer
#   pipelines/reports/CASE/vres_compare.png   error against run time, the three variants
#   pipelines/reports/CASE/vres_profile.png   the compared quantity (the check's profile.tsv:
#                                             x, value, reference) of each variant
# The criterion (issue 7): error_vres <= error_fine + 0.25 (error_coarse - error_fine), and
# run time_vres <= 1.2 time_fine (particle-steps_vres / particle-steps_fine). The run times are
# compared in the same minutes: the three variants run ROUNDS times in turn (default 3: coarse,
# fine, variable, coarse, ...) and each variant's run time is the median of its rounds (this
# machine's speed moves by up to 38% between identical runs minutes apart, so one run each
# decides nothing near the bound); the error is the first round's, and every later round must
# repeat it (one thread: the runs are bit for bit the same).
# SEEDS="S1 S2 ..." (a case whose check reads VRES_SEED: taylor_green_vres2d) makes the rounds an
# ensemble instead: round k runs every variant with VRES_SEED=Sk (the check perturbs its initial
# state by about one float32 ulp, seed 0 not at all), and each variant's error is the mean over
# the rounds, their spread in the footer: where an error is chaotic in the particles' disorder
# (the Taylor-Green vortex's is: one ulp moves it by a quarter), one run's error is one sample.
# VRES_RUN_ARGS="..." passes vres-run options to every run (pipelines/vreslib.sh), e.g.
# "--vres-order 1" (it changes only the variable run); the table's first line then names them.
# REPORT=NAME writes NAME.tsv, NAME.png and NAME_profile.png instead (a variant's table beside
# the default's).
# The runs stay in build/runs/vres_compare/CASE/ (RUNS=DIR to change). Exit 0 when the criterion
# holds.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CASE=${1:?usage: vres_compare.sh CASE DP_COARSE [DPRATIO] [THREADS]}
DPC=${2:?usage: vres_compare.sh CASE DP_COARSE [DPRATIO] [THREADS]}
R=${3:-2}
THREADS=${4:-1}
SEEDS=${SEEDS:-}
ROUNDS=${ROUNDS:-3}
[ -n "$SEEDS" ] && ROUNDS=$(echo $SEEDS | wc -w)
RUNS=${RUNS:-$ROOT/build/runs/vres_compare/$CASE}
REP=$ROOT/pipelines/reports/$CASE
NAME=${REPORT:-vres_compare}                                     # the report's files' names
PROF=$([ "$NAME" = vres_compare ] && echo vres_profile || echo "${NAME}_profile")
CHECK=$ROOT/cases/$CASE/check
[ -x "$CHECK" ] || { echo "vres_compare: $CHECK: no check" >&2; exit 2; }
mkdir -p "$RUNS" "$REP"
DPF=$(awk -v d="$DPC" -v r="$R" 'BEGIN {printf "%.10g", d / r}')
export OMP_WAIT_POLICY=passive
XLABEL=${XLABEL:-position (m)} YLABEL=${YLABEL:-value}
get() { awk -F'\t' -v k="$2" '$1 == k {print $2}' "$RUNS/$1.result"; }
run() { # NAME DP MODE ROUND: round 1 keeps its run and result; later rounds add their run time (and error)
    local dir=$RUNS/$1 res=$RUNS/$1.result
    [ "$4" -gt 1 ] && dir=$RUNS/$1.round && res=$RUNS/$1.round.result
    rm -rf "$dir"
    local seed=
    [ -n "$SEEDS" ] && seed=$(echo $SEEDS | awk -v k="$4" '{print $k}')
    VRES_SEED=$seed "$CHECK" --threads "$THREADS" --dp "$2" "--$3" -o "$dir" >"$res" 2>"$RUNS/$1.log"
    local e t
    e=$(awk -F'\t' '$1 == "error" {print $2}' "$res") t=$(awk -F'\t' '$1 == "run_time_s" {print $2}' "$res")
    [ -n "$e" ] && [ -n "$t" ] || { echo "vres_compare: $1 round $4: no error or run time (see $RUNS/$1.log)" >&2; exit 2; }
    [ "$4" -gt 1 ] && rm -rf "$dir"
    if [ "$4" -eq 1 ]; then
        echo "$t" >"$RUNS/$1.times"
        echo "$e" >"$RUNS/$1.errors"
    elif [ -n "$SEEDS" ] || [ "$e" = "$(get "$1" error)" ]; then
        echo "$t" >>"$RUNS/$1.times"
        echo "$e" >>"$RUNS/$1.errors"
    else
        echo "vres_compare: $1 round $4: error $e, not round 1's $(get "$1" error): the runs must repeat" >&2
        exit 2
    fi
    echo "vres_compare: $1 (dp $2, $3) round $4${seed:+ (seed $seed)}: error $e, run time $t s" >&2
}
for round in $(seq "$ROUNDS"); do
    run single_coarse "$DPC" single "$round"
    run single_fine "$DPF" single "$round"
    run vres "$DPC" vres "$round"
done
median() { sort -g "$RUNS/$1.times" | awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# the variant's error: the first round's, or with SEEDS the mean over the rounds
error_of() {
    if [ -z "$SEEDS" ]; then get "$1" error; else awk '{s += $1; n++} END {printf "%.5f", s / n}' "$RUNS/$1.errors"; fi
}
{
    printf '# %s: variable against single resolution (%s%s pipelines/vres_compare.sh %s %s %s %s)\n' "$CASE" \
        "${REPORT:+REPORT=$REPORT }${VRES_RUN_ARGS:+VRES_RUN_ARGS=\"$VRES_RUN_ARGS\" }" \
        "$([ -n "$SEEDS" ] && echo "SEEDS=\"$SEEDS\"" || echo "ROUNDS=$ROUNDS")" "$CASE" "$DPC" "$R" "$THREADS"
    printf '# made: %s on %s (%s CPUs), vres git %s; error: %s\n' "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$(uname -n)" "$(nproc)" \
        "$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null)" "$(get vres error_def)"
    printf '# run_time_s: the median of %s interleaved rounds; each round'"'"'s run times (s):' "$ROUNDS"
    for v in single_coarse single_fine vres; do printf ' %s %s;' "$v" "$(tr '\n' ' ' <"$RUNS/$v.times" | sed 's/ $//')"; done
    if [ -n "$SEEDS" ]; then
        printf '\n# error: the mean over the seeds %s (one run each); each seed'"'"'s error, then mean and sample standard deviation:' "$SEEDS"
        for v in single_coarse single_fine vres; do
            printf ' %s %s (%s);' "$v" "$(tr '\n' ' ' <"$RUNS/$v.errors" | sed 's/ $//')" \
                "$(awk '{s += $1; q += $1 * $1; n++} END {m = s / n; sd = n > 1 ? sqrt((q - n * m * m) / (n - 1)) : 0; printf "%.5f +- %.5f", m, sd}' "$RUNS/$v.errors")"
        done
    fi
    printf '\n# variant\tdp_m\tparticles\tsteps\trun_time_s\terror\tverdict\tcpu_time_s\n'
    for v in single_coarse single_fine vres; do
        dp=$DPC; [ "$v" = single_fine ] && dp=$DPF
        cpu=$(get $v cpu_time_s)
        printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$v" "$dp" "$(get $v particles)" "$(get $v steps)" "$(median $v)" \
            "$(error_of $v)" "$(get $v verdict)" "${cpu:--}"
    done
} >"$REP/$NAME.tsv.tmp"
awk -F'\t' '!/^#/ {n[$1] = $3 * $4; t[$1] = $5; e[$1] = $6; c[$1] = $8}
    END {
        bound = e["single_fine"] + 0.25 * (e["single_coarse"] - e["single_fine"])
        tbound = 1.2 * t["single_fine"] * n["vres"] / n["single_fine"]
        ok = (e["vres"] == e["vres"] + 0 && e["vres"] <= bound) && (t["vres"] <= tbound)
        printf "# criterion: error_vres %g <= error_fine + 0.25 (error_coarse - error_fine) = %g: %s\n", e["vres"], bound, e["vres"] <= bound ? "yes" : "NO"
        printf "# criterion: run time %g s <= 1.2 time_fine x particle-steps ratio = %g s: %s\n", t["vres"], tbound, t["vres"] <= tbound ? "yes" : "NO"
        if (c["vres"] != "" && c["vres"] != "-" && c["single_fine"] + 0 > 0) {
            cbound = 1.2 * c["single_fine"] * n["vres"] / n["single_fine"]
            printf "# the same on CPU time (not judged; steadier than wall time on a loaded machine): %g s <= %g s: %s\n", c["vres"], cbound, c["vres"] <= cbound ? "yes" : "NO"
        }
        printf "# verdict\t%s\n", ok ? "pass" : "FAIL"
    }' "$REP/$NAME.tsv.tmp" >>"$REP/$NAME.tsv.tmp"
mv "$REP/$NAME.tsv.tmp" "$REP/$NAME.tsv"
cat "$REP/$NAME.tsv"
if command -v gnuplot >/dev/null; then
    gnuplot -e "t='$REP/$NAME.tsv'; set terminal pngcairo size 800,560 noenhanced font ',11'; set output '$REP/$NAME.png';
        set datafile separator '\t'; set logscale xy; set grid; set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1;
        set title '$CASE: error against run time'; set xlabel 'vres-run wall-clock time (s)'; set ylabel 'error';
        plot t using 5:6:(sprintf('%s\ndp %g, %d particles', stringcolumn(1), \$2, \$3)) with labels point pointtype 7 offset char 1,char 1 left notitle"
    [ -f "$RUNS/vres/profile.tsv" ] && gnuplot -e "set terminal pngcairo size 800,560 noenhanced font ',11'; set output '$REP/$PROF.png'; set grid;
        set title '$CASE: compared quantity against its reference'; set xlabel '$XLABEL'; set ylabel '$YLABEL';
        plot '$RUNS/single_coarse/profile.tsv' using 1:3 with lines lw 2 title 'reference',
             '$RUNS/single_coarse/profile.tsv' using 1:2 with points pt 6 title 'single, dp $DPC',
             '$RUNS/single_fine/profile.tsv' using 1:2 with points pt 4 title 'single, dp $DPF',
             '$RUNS/vres/profile.tsv' using 1:2 with points pt 7 title 'variable, dp $DPC / $DPF'"
fi
grep -q '^# verdict.pass' "$REP/$NAME.tsv"
