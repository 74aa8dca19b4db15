#!/usr/bin/env bash
# vres-run --restart continues a run from any of its snapshots (or checkpoint.h5): with the
# Symplectic scheme the continued run equals the uninterrupted one bit for bit (DESIGN section
# 3: "each restartable; a restart continues to the same result"). Also: the run directory is
# trimmed of what the restart rewrites, SIGTERM leaves a checkpoint that restarts, and bad
# restarts (a store that is no snapshot, a corrupt file, nothing left to run, STORE and
# --restart together) are refused with nothing written.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml

"$BIN/vres-gencase" -q --dp 0.05 "$DB" -o "$T/db.h5" || notok "gencase the dam break"
expect 0 "uninterrupted run to 0.1 s, 5 outputs" "$RUN" -q --threads 2 --tmax 0.1 --tout 0.02 "$T/db.h5" -o "$T/a"
check "checkpoint.h5 written at the end" [ -f "$T/a/checkpoint.h5" ]
check "the run ended on snapshot 5: checkpoint.h5 is its copy, byte for byte" \
    cmp -s "$T/a/checkpoint.h5" "$T/a/snap_00005.h5"
expect 0 "a run that ends between outputs (every 0.03 s to 0.1 s)" \
    "$RUN" -q --threads 2 --tmax 0.1 --tout 0.03 "$T/db.h5" -o "$T/odd"
check "its checkpoint.h5 holds the final state, not the last snapshot's" \
    sh -c "! cmp -s '$T/odd/checkpoint.h5' '$T/odd/snap_00003.h5' && \
           h5diff -q '$T/odd/checkpoint.h5' '$T/a/checkpoint.h5' /Domains/D0/Position /Domains/D0/Position"

# restart in a copy of the run directory from snapshot 2
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00002.h5 in its own directory" "$RUN" --threads 2 --restart "$T/b/snap_00002.h5"
check "says it removed the snapshots it rewrites" grep -q 'removed snap_00003.h5 .. snap_00005.h5' "$ERR"
for k in 3 4 5; do
    for ds in Position Velocity Density Id; do
        check "snap $k $ds equal to the uninterrupted run's" \
            h5diff -q "$T/a/snap_0000$k.h5" "$T/b/snap_0000$k.h5" /Domains/D0/$ds /Domains/D0/$ds
    done
done
check "run.tsv: same times and steps as the uninterrupted run" \
    diff <(grep -v '^#' "$T/a/run.tsv" | cut -f1-9) <(grep -v '^#' "$T/b/run.tsv" | cut -f1-9)
check "history of the continued snapshot names the restart" \
    sh -c "h5dump -a /history '$T/b/snap_00005.h5' | grep -q -- '--restart'"

# restart into a new directory: numbering continues, same data
expect 0 "restart from snap_00003.h5 into a new -o" "$RUN" -q --threads 1 --restart "$T/a/snap_00003.h5" -o "$T/c"
check "new directory holds snapshots 4 and 5 only" [ ! -e "$T/c/snap_00003.h5" -a -f "$T/c/snap_00004.h5" -a -f "$T/c/snap_00005.h5" ]
check "snap 5 equal to the uninterrupted run's (other thread count too)" \
    h5diff -q "$T/a/snap_00005.h5" "$T/c/snap_00005.h5" /Domains/D0/Position /Domains/D0/Position
check "the new run.tsv has a header and two lines" [ "$(grep -c -v '^#' "$T/c/run.tsv")" -eq 2 ]

# a longer end time on restart
expect 0 "restart from the last snapshot with a later --tmax" "$RUN" -q --restart "$T/c/snap_00005.h5" --tmax 0.14
check "two more snapshots" [ -f "$T/c/snap_00007.h5" -a ! -e "$T/c/snap_00008.h5" ]

# SIGTERM: checkpoint written, exit 1 with the command to continue, and that command works
"$BIN/vres-gencase" -q --dp 0.02 "$DB" -o "$T/db2.h5" || notok "gencase at dp 0.02"
"$RUN" --threads 1 --tmax 5 --tout 1 "$T/db2.h5" -o "$T/s" 2>"$T/s.err" &
pid=$!
for i in $(seq 50); do [ -f "$T/s/snap_00000.h5" ] && break; sleep 0.2; done
sleep 1
kill -TERM $pid
wait $pid
rc=$?
check "SIGTERM: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "says how to continue" grep -q -E 'interrupted at t = .*checkpoint.h5; continue with vres-run --restart' "$T/s.err"
check "checkpoint.h5 written" [ -f "$T/s/checkpoint.h5" ]
tck=$("$BIN/vres-info" "$T/s/checkpoint.h5" | sed -n -E 's/^ *time +([0-9.e+-]+) s, step.*/\1/p')
expect 0 "the checkpoint (t = $tck s) restarts" "$RUN" -q --restart "$T/s/checkpoint.h5" \
    --tmax "$(awk -v t="$tck" 'BEGIN {print t + 0.005}')" --tout 1

# refused restarts: one message, exit 1, the run directory untouched
sum=$(cat "$T/a/run.tsv" "$T/a"/snap_*.h5 | md5sum)
expect_err 1 'no parameter run_t0: --restart needs a snapshot or checkpoint.h5 written by vres-run' \
    "a gencase store is no snapshot" "$ASAN/vres-run" --restart "$T/db.h5" -o "$T/a"
head -c 3000 "$T/a/snap_00004.h5" >"$T/trunc.h5"
expect_err 1 'trunc.h5' "a truncated snapshot" "$ASAN/vres-run" --restart "$T/trunc.h5" -o "$T/a"
expect_err 1 'at or past the end time 0.1 s: give a later --tmax' "nothing left to run" \
    "$ASAN/vres-run" --restart "$T/a/snap_00005.h5"
expect_err 2 'give STORE or --restart SNAP, not both' "STORE and --restart" \
    "$ASAN/vres-run" --restart "$T/a/snap_00001.h5" "$T/db.h5" -o "$T/a"
expect_err 2 'missing STORE' "neither STORE nor --restart" "$ASAN/vres-run" -o "$T/x"
check "the run directory is untouched" [ "$(cat "$T/a/run.tsv" "$T/a"/snap_*.h5 | md5sum)" = "$sum" ]
nothing_in "$T/x" "no run directory made"
