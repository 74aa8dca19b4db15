#!/usr/bin/env bash
# Replays every committed fuzzing input (tests/fuzz/corpus/NAME: seeds and what the fuzzers
# kept; tests/fuzz/regress/NAME: inputs that once crashed, hung or allocated without bound)
# through each harness tests/fuzz/fuzz_NAME.c built without libFuzzer, against the
# AddressSanitizer/UBSan build ($VRES_BUILD/fuzz/replay_NAME, made by make check): each input
# must come back (no crash, sanitizer report or leak) within the time limit.
source "$(dirname "$0")/../harness.sh"
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:allocator_may_return_null=1
for src in "$ROOT"/tests/fuzz/fuzz_*.c; do
    name=$(basename "$src" .c); name=${name#fuzz_}
    bin=$ROOT/$VRES_BUILD/fuzz/replay_$name
    if [ ! -x "$bin" ]; then
        notok "$name: $bin missing (make $VRES_BUILD/fuzz/replay_$name)"
        continue
    fi
    dirs=()
    for d in corpus regress; do
        [ -n "$(ls -A "$ROOT/tests/fuzz/$d/$name" 2>/dev/null)" ] && dirs+=("$ROOT/tests/fuzz/$d/$name")
    done
    n=$(find "${dirs[@]}" -type f ! -name '.*' 2>/dev/null | wc -l)
    run timeout 300 "$bin" "${dirs[@]}"
    if [ "$STATUS" -ne 0 ]; then
        notok "$name: replay of $n inputs exited $STATUS"; grep -v '^vres\|^fuzz' "$ERR" | head -30 | sed 's/^/#   /'
    elif grep -q -E 'Sanitizer|runtime error' "$ERR"; then
        notok "$name: sanitizer report"; grep -A20 -E 'Sanitizer|runtime error' "$ERR" | head -30 | sed 's/^/#   /'
    elif ! grep -q "^replayed $n inputs$" "$OUT"; then
        notok "$name: replayed $(cat "$OUT"), expected $n inputs"
    else
        ok "$name: $n inputs replayed"
    fi
done
