#!/usr/bin/env bash
# tests/fuzz/run.sh NAME... - run the libFuzzer harnesses $VRES_BUILD/fuzz/fuzz_NAME (make fuzz
# builds them) one after the other, FUZZ_S seconds each (default 60), under nice -n 19, each from
# its committed corpus tests/fuzz/corpus/NAME plus the inputs it found before in
# $VRES_BUILD/fuzz/corpus/NAME (where new ones go). A crash, hang, leak or allocation over 2 GB
# stops that harness and leaves the input in $VRES_BUILD/fuzz/crash/NAME/. A hang is an input
# running FUZZ_TIMEOUT s (default 60) of wall-clock time: libFuzzer's timer is not CPU time, and
# at nice 19 on a loaded machine an input of 0.27 s CPU once took 14 s (replay a timeout with
# the harness and one input, "$VRES_BUILD/fuzz/fuzz_NAME FILE", before calling it a hang).
# Prints per harness its wall and CPU seconds (user + system: at nice 19 on a busy machine the
# fuzzer gets a fraction of a core), executions, coverage (cov: edges, ft: features) and corpus size, as
# libFuzzer's last status line gives them; the log is $VRES_BUILD/fuzz/NAME.log, and each run's line
# is added to $VRES_BUILD/fuzz/runs.txt with its date (the fuzzing ledger). Exit 1 when a harness failed.
# Extra libFuzzer options: FUZZ_OPTS (e.g. FUZZ_OPTS=-jobs=2).
cd "$(dirname "$0")/../.." || exit 1
B=${VRES_BUILD:-build}
S=${FUZZ_S:-60}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
fail=0
printf '%-8s %8s %8s %10s %8s %8s %7s  %s\n' harness seconds cpu_s execs cov ft corpus result
for name in "$@"; do
    bin=$B/fuzz/fuzz_$name
    [ -x "$bin" ] || { echo "$bin: missing (make $bin)"; fail=1; continue; }
    mkdir -p "$B/fuzz/corpus/$name" "$B/fuzz/crash/$name"
    dict=tests/fuzz/$name.dict
    t0=$(date +%s)
    rm -f "$B/fuzz/$name.cpu"
    timer=() # GNU time (package time) gives the CPU seconds where it is installed
    [ -x /usr/bin/time ] && timer=(/usr/bin/time -f '%U %S' -o "$B/fuzz/$name.cpu")
    "${timer[@]}" nice -n 19 "$bin" -max_total_time="$S" -timeout="${FUZZ_TIMEOUT:-60}" -rss_limit_mb=2048 -malloc_limit_mb=2048 \
        -close_fd_mask=3 -print_final_stats=1 -artifact_prefix="$B/fuzz/crash/$name/" \
        $([ -f "$dict" ] && echo "-dict=$dict") ${FUZZ_OPTS:-} \
        "$B/fuzz/corpus/$name" "tests/fuzz/corpus/$name" >"$B/fuzz/$name.log" 2>&1
    rc=$?
    t1=$(date +%s)
    last=$(grep -E '^#[0-9]+' "$B/fuzz/$name.log" | tail -1)
    execs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$B/fuzz/$name.log" | tail -1)
    cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
    ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
    corp=$(sed -nE 's/.* corp: ([0-9]+).*/\1/p' <<<"$last")
    res=ok
    if [ $rc -ne 0 ]; then
        res="FAILED (exit $rc): $(grep -m1 -E 'ERROR|runtime error|SUMMARY' "$B/fuzz/$name.log" | cut -c1-120)"
        fail=1
    fi
    cpu=$(awk 'NF == 2 && $1 ~ /^[0-9.]+$/ {printf "%.0f", $1 + $2}' "$B/fuzz/$name.cpu" 2>/dev/null)
    line=$(printf '%-8s %8s %8s %10s %8s %8s %7s  %s' "$name" $((t1 - t0)) "${cpu:-?}" "${execs:-?}" "${cov:-?}" \
        "${ft:-?}" "${corp:-?}" "$res")
    echo "$line"
    echo "$(date -u +%FT%TZ -d @"$t0") $line" >>"$B/fuzz/runs.txt"
done
exit $fail
