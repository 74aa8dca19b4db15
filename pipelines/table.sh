#!/usr/bin/env bash
# pipelines/table.sh - one error-against-cost table from the results of a case's check at
# several resolutions (the check protocol of pipelines/vreslib.sh: "key<TAB>value" lines).
#
#   pipelines/table.sh CASE COMMAND RESULT...
#
# Prints a TSV table: a # header naming the case, its reference and error, the command that
# made it, the machine and the build; a # column line; one row per RESULT file, coarsest dp
# first:
#   dp_m  particles  steps  run_time_s  error  verdict
# and a trailing comment with the observed order of convergence between successive
# resolutions, p = log(e_coarse / e_fine) / log(dp_coarse / dp_fine), and over the whole range
# (the least-squares slope of log error against log dp). A RESULT without an error (a run that
# failed) gets "nan" and a FAIL verdict and is left out of the orders.
set -u
[ $# -ge 3 ] || { echo "usage: pipelines/table.sh CASE COMMAND RESULT..." >&2; exit 2; }
case=$1 cmd=$2; shift 2
get() { awk -F'\t' -v k="$1" '$1 == k {v = $2} END {print (v == "" ? "nan" : v)}' "$2"; }

first=$1
printf '# %s: error against run time, single resolution (vres-run, CPU)\n' "$case"
printf '# reference: %s\n' "$(get reference "$first")"
printf '# error: %s\n' "$(get error_def "$first")"
printf '# tolerance of the check: %s\n' "$(get tolerance "$first")"
printf '# command: %s\n' "$cmd"
printf '# made: %s on %s (%s CPUs: %s), vres git %s\n' "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$(uname -n)" \
    "$(nproc)" "$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)" \
    "$(git -C "$(dirname "$0")/.." rev-parse --short HEAD 2>/dev/null || echo unknown)"
printf '# run_time_s is vres-run'"'"'s wall-clock time loop (run.tsv wall_s, snapshot writing included)\n'
printf '# dp_m\tparticles\tsteps\trun_time_s\terror\tverdict\n'
for r in "$@"; do
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(get dp_m "$r")" "$(get particles "$r")" "$(get steps "$r")" \
        "$(get run_time_s "$r")" "$(get error "$r")" "$(get verdict "$r" | sed 's/^nan$/FAIL/')"
done | sort -g -r -k1,1 >"${TMPDIR:-/tmp}/table.$$"
cat "${TMPDIR:-/tmp}/table.$$"
awk -F'\t' '
    $5 + 0 > 0 && $5 == $5 + 0 { n++; d[n] = $1; e[n] = $5 }
    END {
        if (n < 2) { print "# observed order: fewer than two resolutions with an error"; exit }
        s = "# observed order, successive resolutions:"
        for (i = 1; i < n; i++)
            s = s sprintf(" %g->%g: %.2f;", d[i], d[i + 1], log(e[i] / e[i + 1]) / log(d[i] / d[i + 1]))
        print s
        for (i = 1; i <= n; i++) { x = log(d[i]); y = log(e[i]); sx += x; sy += y; sxx += x * x; sxy += x * y }
        printf "# observed order, least-squares slope of log error against log dp over %d resolutions: %.2f\n",
            n, (n * sxy - sx * sy) / (n * sxx - sx * sx)
    }' "${TMPDIR:-/tmp}/table.$$"
rm -f "${TMPDIR:-/tmp}/table.$$"
