#!/usr/bin/env bash
# vres-gencase writes the store to stdout with no -o, so it pipes into the other tools:
# vres-gencase case.xml | vres-info - shows the dam break's particles.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/dsph_dambreak2d/dambreak2d_Def.xml

if [ ! -x "$BIN/vres-info" ]; then
    ok "pipe into vres-info # SKIP vres-info is not built"
    exit 0
fi
"$BIN/vres-gencase" -q "$CASE" | "$BIN/vres-info" - >"$OUT" 2>"$ERR"
check "the pipe succeeds" [ "${PIPESTATUS[0]}${PIPESTATUS[1]}" = "00" ]
check "vres-info sees 21001 particles" grep -qE "particles +21001" "$OUT"
check "vres-info sees 20000 fluid" grep -qE "fluid +20000" "$OUT"
check "the history names vres-gencase" grep -q "vres-gencase -q" "$OUT"
