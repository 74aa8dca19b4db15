#!/usr/bin/env bash
# Every tool has a man page whose SYNOPSIS equals its --help output, and answers --version.
# The SYNOPSIS is the .nf/.fi block after ".SH SYNOPSIS", with font escapes removed and "\-" as "-".
source "$(dirname "$0")/../harness.sh"

synopsis() {
    awk '/^\.SH +"?SYNOPSIS/ {s=1; next} s && /^\.SH/ {exit} s && /^\.nf/ {on=1; next} s && /^\.fi/ {on=0; next} on' "$1" |
        sed -e 's/\\f[BIRP]//g' -e 's/\\-/-/g' -e 's/\\e/\\/g'
}

n=0
for src in "$ROOT"/tools/vres-*.c; do
    tool=$(basename "$src" .c)
    page=$ROOT/man/man1/$tool.1
    n=$((n + 1))
    if [ ! -f "$page" ]; then notok "$tool has a man page"; continue; fi
    ok "$tool has a man page"
    synopsis "$page" >"$T/man.txt"
    "$BIN/$tool" --help >"$T/help.txt" 2>&1
    if [ -s "$T/man.txt" ] && diff -u "$T/man.txt" "$T/help.txt" >"$T/diff.txt"; then
        ok "$tool --help equals its man page SYNOPSIS"
    else
        notok "$tool --help equals its man page SYNOPSIS"; sed 's/^/#   /' "$T/diff.txt"
    fi
    expect 0 "$tool --version exits 0" "$BIN/$tool" --version
    check "$tool --version names the tool" grep -q "^$tool " "$OUT"
    expect_err 2 "Try '$tool --help'" "$tool: unknown option is a usage error (exit 2)" "$ASAN/$tool" --no-such-option
done
check "at least one tool checked" [ "$n" -gt 0 ]
for page in "$ROOT"/man/man1/*.1 "$ROOT"/man/man5/*.5 "$ROOT"/man/man7/*.7; do
    [ -f "$page" ] || continue
    # groff's own warnings (-ww) about the page's markup fail the test
    if command -v groff >/dev/null; then
        if groff -man -Tutf8 -ww -z "$page" 2>"$T/groff.txt" && [ ! -s "$T/groff.txt" ]; then
            ok "$(basename "$page") formats without warnings"
        else
            notok "$(basename "$page") formats without warnings"; sed 's/^/#   /' "$T/groff.txt" | head
        fi
    fi
done
