#!/usr/bin/env bash
# pipelines/selfconv.sh - observed order of convergence of a case against itself.
#
#   pipelines/selfconv.sh 'SERIES COMMAND' RUNDIR:DP RUNDIR:DP RUNDIR:DP...
#
# Where the reference is an experiment, the error against it stops falling once the numerics
# are finer than the difference between the model and the experiment (a 2-D inviscid front has
# no floor friction, no gate, no surface tension), so its observed order says little about the
# numerics. The runs at successive resolutions measure those: SERIES COMMAND, given a run
# directory as its last argument, prints a series "x<TAB>y" (for the dam break,
# `pipelines/front.sh --dimensionless`: T, Z); for each pair of successive resolutions
# (coarse to fine after sorting by dp), the RMS of y_coarse - y_fine over the fine run's x
# points inside the coarse run's range (y_coarse interpolated linearly in x) is d_k, and
# with three or more runs the observed order between successive pairs is
#   p = log(d_k / d_k+1) / log(r),  r = dp_coarse / dp_fine of the pair.
# Prints those lines as # comments, to append to a table of pipelines/table.sh.
set -u
[ $# -ge 3 ] || { echo "usage: pipelines/selfconv.sh 'SERIES COMMAND' RUNDIR:DP RUNDIR:DP..." >&2; exit 2; }
cmd=$1; shift
T=$(mktemp -d "${TMPDIR:-/tmp}/selfconv.XXXXXX") && trap 'rm -rf "$T"' EXIT
k=0
for rd in $(printf '%s\n' "$@" | sort -t: -k2,2 -g -r); do
    dir=${rd%:*} dp=${rd##*:}
    [ -f "$dir/run.tsv" ] || { echo "# self-convergence: dp $dp: no run in $dir"; continue; }
    $cmd "$dir" | grep -v '^#' >"$T/$k" || { echo "# self-convergence: dp $dp: series failed"; continue; }
    echo "$dp" >"$T/$k.dp"; k=$((k + 1))
done
[ "$k" -ge 2 ] || { echo "# self-convergence: fewer than two runs"; exit 0; }
echo "# self-convergence (pipelines/selfconv.sh, series: $cmd): RMS difference d between successive resolutions"
prev=""
for ((i = 0; i + 1 < k; i++)); do
    d=$(awk -F'\t' 'BEGIN { n = 0 } FNR == 1 { f++ }
        f == 1 { x[n] = $1; y[n] = $2; n++; next }
        f == 2 && $1 >= x[0] && $1 <= x[n - 1] {
            for (j = 1; j < n - 1 && x[j] < $1; j++) ;
            yc = (x[j] == x[j - 1]) ? y[j] : y[j - 1] + (y[j] - y[j - 1]) * ($1 - x[j - 1]) / (x[j] - x[j - 1])
            s += (yc - $2) ^ 2; m++ }
        END { if (m) printf "%.6g", sqrt(s / m); else printf "nan" }' "$T/$i" "$T/$((i + 1))")
    a=$(cat "$T/$i.dp") b=$(cat "$T/$((i + 1)).dp")
    line="# d(dp $a, dp $b) = $d"
    if [ -n "$prev" ]; then
        line="$line; observed order $(awk -v d0="$prev" -v d1="$d" -v r="$(awk -v a="$a" -v b="$b" 'BEGIN {print a / b}')" \
            'BEGIN {if (d0 > 0 && d1 > 0) printf "%.2f", log(d0 / d1) / log(r); else printf "nan"}')"
    fi
    echo "$line"
    prev=$d
done
