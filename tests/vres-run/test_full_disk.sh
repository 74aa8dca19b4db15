#!/usr/bin/env bash
# vres-run on a full disk (issue 10, item 2): on a 1 MiB tmpfs the run stops when a snapshot no
# longer fits, with exit 1 and one message naming the file and the command that continues the
# run; the earlier snapshots are intact (equal to those of a run with room), no partial snapshot
# is left under its name nor any temporary, run.tsv has one line per snapshot; after making room
# the command given continues the run to the result of the run with room, bit for bit. Mounting
# needs root: without it the test says SKIP.
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
FS=$T/fs
mkdir -p "$FS"
if ! mount -t tmpfs -o size=1m tmpfs "$FS" 2>/dev/null; then
    echo "ok - # SKIP cannot mount a tmpfs here (needs root and the permission to mount)"
    exit 0
fi
trap 'umount "$FS" 2>/dev/null; rm -rf "$T"' EXIT
"$BIN/vres-gencase" -q --dp 0.03 "$CASES/dsph_dambreak2d/dambreak2d_Def.xml" -o "$T/db.h5" || notok "gencase the dam break"
opts=(-q --threads 1 --tmax 0.05 --tout 0.0025)
expect 0 "the run with room: 21 snapshots" "$RUN" "${opts[@]}" "$T/db.h5" -o "$T/ref"
nref=$(find "$T/ref" -name 'snap_*.h5' | wc -l)
check "the run with room wrote 21 snapshots ($nref)" [ "$nref" -eq 21 ]

expect_err 1 'run/snap_000[0-9][0-9].h5: cannot write store: No space left on device: the run stops at t = .* s, step [0-9]+, its snapshots intact up to .*: make room and continue it with vres-run --restart .*/run/snap_000[0-9][0-9].h5$' \
    "full disk: exit 1, the snapshot and the command that continues named" "$RUN" "${opts[@]}" "$T/db.h5" -o "$FS/run"
check "one message" [ "$(wc -l <"$ERR")" -eq 1 ]
failed=$(sed -n -E 's|.*/(snap_[0-9]+\.h5): cannot write.*|\1|p' "$ERR")
resume=$(sed -n -E 's/.*continue it with (vres-run --restart .*)$/\1/p' "$ERR")
from=${resume#vres-run --restart }
nsnap=$(find "$FS/run" -name 'snap_*.h5' | wc -l)
echo "# $nsnap snapshots fitted; $failed did not; the message says: $resume"
check "the snapshot that did not fit ($failed) is not there" [ -n "$failed" -a ! -e "$FS/run/$failed" ]
check "the command continues from the newest snapshot there" [ "$from" = "$(find "$FS/run" -name 'snap_*.h5' | sort | tail -1)" ]
check "no temporary file left" [ -z "$(find "$FS/run" -name '.*tmp*')" ]
good=0
for f in "$FS"/run/snap_*.h5; do
    b=$(basename "$f")
    "$BIN/vres-info" "$f" >/dev/null && h5diff -q "$T/ref/$b" "$f" /Domains /Domains && good=$((good + 1))
done
check "the $nsnap snapshots written (at least 2) are intact: readable and equal to the run with room's ($good)" \
    [ "$nsnap" -ge 2 -a "$good" -eq "$nsnap" -a "$nsnap" -lt "$nref" ]
check "run.tsv: one line per snapshot written, the last one the newest snapshot's step" \
    [ "$(grep -c -v '^#' "$FS/run/run.tsv")" -eq "$nsnap" -a \
      "$(tail -1 "$FS/run/run.tsv" | cut -f2)" = "$("$BIN/vres-info" "$from" | sed -n -E 's/^ *time .*, step ([0-9]+)$/\1/p')" ]

# make room, then the command the message gave
mount -o remount,size=16m "$FS" || notok "remount the tmpfs larger"
if [ -n "$resume" ]; then
    read -r -a cmd <<<"$resume"
    expect 0 "after making room, '$resume' continues the run" "$BIN/${cmd[0]}" -q --threads 1 "${cmd[@]:1}"
else notok "after making room, the command given continues the run (no command given)"; fi
good=0
for f in "$T"/ref/snap_*.h5; do
    h5diff -q "$f" "$FS/run/$(basename "$f")" /Domains /Domains && good=$((good + 1))
done
check "all $nref snapshots equal to the run with room's ($good)" [ "$good" -eq "$nref" ]
check "run.tsv: the run with room's times, steps and figures" \
    diff <(grep -v '^#' "$T/ref/run.tsv" | cut -f1-9) <(grep -v '^#' "$FS/run/run.tsv" | cut -f1-9)

# the same failure under AddressSanitizer: the stop path is clean
rm -rf "${FS:?}"/*
mount -o remount,size=1m "$FS" || notok "remount the tmpfs small"
expect_err 1 'No space left on device: the run stops at .* continue it with vres-run --restart' \
    "full disk under AddressSanitizer: the same message, no sanitizer report" "$ASAN/vres-run" "${opts[@]}" "$T/db.h5" -o "$FS/run"
check "no temporary file left (AddressSanitizer run)" [ -z "$(find "$FS/run" -name '.*tmp*')" ]
