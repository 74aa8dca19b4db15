#!/usr/bin/env bash
# vres-run killed with SIGKILL at random moments (issue 10, item 2): after every kill each
# snapshot on disk is complete (equal to the uninterrupted run's) or absent, checkpoint.h5 is
# readable, and a chain of --restart's from the newest complete snapshot (every fourth from
# checkpoint.h5) ends with the uninterrupted run's snapshots and run.tsv, bit for bit. One kill
# in three lands at a random moment, one while a snapshot is being written (its temporary file
# is there), one while checkpoint.h5 is (checkpoints every 0.05 s of wall time).
# VRES_CRASH_SEED=N repeats a run's draws (printed first); VRES_CRASH_KILLS=N (default 24);
# VRES_CRASH_COUPLED=1 kills a coupled run instead (the tilted tank of test_vres_restart.sh, two
# domains; snapshots compared with their /Interfaces too, and ledger.tsv at the end): slower,
# not part of make check.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
seed=${VRES_CRASH_SEED:-$$}
RANDOM=$seed
KILLS=${VRES_CRASH_KILLS:-24}
echo "# seed $seed, $KILLS kills"
if [ "${VRES_CRASH_COUPLED:-0}" = 1 ]; then
    tilted_tank
    STORE=$T/parts.h5 groups=(/Domains /Interfaces) what="the tilted tank in two domains"
    opts=(--threads 1 --tmax 0.05 --tout 0.0025)
else
    STORE=$T/db.h5 groups=(/Domains) what="the dam break, 2545 particles"
    "$BIN/vres-gencase" -q --dp 0.03 "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" -o "$STORE" || notok "gencase the dam break"
    opts=(--threads 1 --tmax 0.03 --tout 0.0015)
fi
w0=$(date +%s.%N)
expect 0 "uninterrupted run: $what, 20 outputs" "$RUN" -q "${opts[@]}" "$STORE" -o "$T/ref"
# the kills' pauses scale with the run's wall time, so that on a loaded machine too the chain
# of restarts gets through the run: up to a sixth of it
wall=$(awk -v a="$w0" -v b="$(date +%s.%N)" 'BEGIN {printf "%.3f", b - a}')
nref=$(find "$T/ref" -name 'snap_*.h5' | wc -l)
check "the uninterrupted run wrote 21 snapshots ($nref)" [ "$nref" -eq 21 ]
last=$(printf 'snap_%05d.h5' $((nref - 1)))

R=$T/run
declare -A seen # snapshot name -> its inode, size and time when found equal to the reference
checked=0 bad=0 ck_checked=0 ck_bad=0 killed=0 midsnap=0 midck=0 from_ck=0

# same NAME: RUNDIR/NAME is readable by vres and its particles equal the uninterrupted run's
same() {
    local g
    "$BIN/vres-info" "$R/$1" >/dev/null 2>&1 || return 1
    for g in "${groups[@]}"; do h5diff -q "$T/ref/$1" "$R/$1" "$g" "$g" >/dev/null 2>&1 || return 1; done
}

# launch N: start cycle N's run in the background (pid in $pid): a new run when no snapshot is
# there, else a restart from the newest (every fourth cycle from checkpoint.h5 when there is one;
# from an earlier snapshot when the newest ends the run)
launch() {
    local src newest
    newest=$(find "$R" -name 'snap_*.h5' 2>/dev/null | sort | tail -1)
    if [ -z "$newest" ]; then
        rm -rf "$R"
        "$RUN" "${opts[@]}" --checkpoint 0.05 "$STORE" -o "$R" 2>>"$T/kill.err" &
        pid=$!
        return
    fi
    src=$newest
    if [ $(($1 % 4)) -eq 3 ] && [ -f "$R/checkpoint.h5" ]; then src=$R/checkpoint.h5; from_ck=$((from_ck + 1))
    elif [ "$(basename "$newest")" = "$last" ]; then src=$(printf '%s/snap_%05d.h5' "$R" $((RANDOM % (nref - 1)))); fi
    "$RUN" "${opts[@]}" --checkpoint 0.05 --restart "$src" 2>>"$T/kill.err" &
    pid=$!
}

# wait_for GLOB: return once a file matches RUNDIR/GLOB, or the run has ended
wait_for() {
    while kill -0 "$pid" 2>/dev/null; do compgen -G "$R/$1" >/dev/null && return; done
}

# verify N: after kill N, every snapshot not yet seen equal to the reference, checkpoint.h5 readable
verify() {
    local f b key
    for f in "$R"/snap_*.h5; do
        [ -e "$f" ] || continue
        b=$(basename "$f")
        key=$(stat -c '%i %s %Y' "$f")
        [ "${seen[$b]:-}" = "$key" ] && continue
        checked=$((checked + 1))
        if same "$b"; then seen[$b]=$key; else
            bad=$((bad + 1)); echo "# kill $1: $b unreadable or unlike the uninterrupted run's"; fi
    done
    if [ -f "$R/checkpoint.h5" ]; then
        ck_checked=$((ck_checked + 1))
        "$BIN/vres-info" "$R/checkpoint.h5" >/dev/null 2>&1 ||
            { ck_bad=$((ck_bad + 1)); echo "# kill $1: checkpoint.h5 unreadable"; }
    fi
}

for ((i = 1; killed < KILLS && i <= 2 * KILLS; i++)); do # a run that ended before its kill does not count
    launch "$i"
    pause=$(awk -v w="$wall" -v r=$RANDOM 'BEGIN {printf "%.3f", w / 6 * r / 32768}')
    sleep "$pause"
    case $((i % 3)) in
        1) wait_for '.snap_*.tmp.*' ;;
        2) wait_for '.checkpoint.h5.tmp.*' ;;
    esac
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    [ $? -eq 137 ] && killed=$((killed + 1))
    compgen -G "$R/.snap_*.tmp.*" >/dev/null && midsnap=$((midsnap + 1))
    compgen -G "$R/.checkpoint.h5.tmp.*" >/dev/null && midck=$((midck + 1))
    verify "$i"
done
reached=$(find "$R" -name 'snap_*.h5' | sort | tail -1)
echo "# pauses up to $wall / 6 s; $killed runs killed: $midsnap while writing a snapshot, $midck while writing checkpoint.h5; $from_ck restarts from checkpoint.h5; the killed runs reached ${reached##*/}"
check "$KILLS runs killed (at least 20), not finished ($killed in $((i - 1)) starts)" [ "$killed" -ge "$KILLS" -a "$killed" -ge 20 ]
check "kills landed while a snapshot was written ($midsnap) and while checkpoint.h5 was ($midck)" \
    [ "$midsnap" -ge 1 -a "$midck" -ge 1 ]
check "after every kill each snapshot is complete and equal to the uninterrupted run's ($bad bad of $checked)" \
    [ "$checked" -ge 5 -a "$bad" -eq 0 ]
check "after every kill checkpoint.h5 is readable ($ck_bad bad of $ck_checked)" [ "$ck_checked" -ge 1 -a "$ck_bad" -eq 0 ]

# the last restart, from the newest complete snapshot, runs to the end
newest=$(find "$R" -name 'snap_*.h5' | sort | tail -1)
[ -n "$newest" ] || newest=none
if [ "$(basename "$newest")" != "$last" ]; then
    expect 0 "restart from the newest snapshot ($(basename "$newest")) to the end" "$RUN" -q "${opts[@]}" --restart "$newest"
elif compgen -G "$R/.*.tmp.*" >/dev/null; then
    # the last kill came after the last snapshot (while checkpoint.h5 was written): the run is
    # whole, and the next restart in the directory sweeps the temporary file; make one
    prev=$(printf '%s/snap_%05d.h5' "$R" $((nref - 2)))
    expect 0 "restart from $(basename "$prev") to the end (a killed run's temporary file after the last snapshot)" \
        "$RUN" -q "${opts[@]}" --restart "$prev"
fi
n=0 nsame=0
for f in "$T"/ref/snap_*.h5; do
    n=$((n + 1))
    same "$(basename "$f")" && nsame=$((nsame + 1))
done
check "all $nref snapshots equal to the uninterrupted run's ($nsame)" [ "$n" -eq "$nref" -a "$nsame" -eq "$nref" ]
check "no other snapshot" [ "$(find "$R" -name 'snap_*.h5' | wc -l)" -eq "$nref" ]
check "run.tsv: the uninterrupted run's times, steps and figures" \
    diff <(grep -v '^#' "$T/ref/run.tsv" | cut -f1-9) <(grep -v '^#' "$R/run.tsv" | cut -f1-9)
if [ -f "$T/ref/ledger.tsv" ]; then
    check "ledger.tsv: the uninterrupted run's lines" diff "$T/ref/ledger.tsv" "$R/ledger.tsv"
fi
check "run.tsv has $nref lines" [ "$(grep -c -v '^#' "$R/run.tsv")" -eq "$nref" ]
check "no temporary file left (the restarts removed the killed runs')" [ -z "$(find "$R" -name '.*tmp*')" ]
check "the restarts said they removed what killed runs left" grep -q 'temporary file.* that a killed run left' "$T/kill.err"
