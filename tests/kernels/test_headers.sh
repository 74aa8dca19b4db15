#!/usr/bin/env bash
# kernels/ is physics written once for the CPU and CUDA (DESIGN section 6): it must know
# nothing of lib/'s internals. Each header compiles on its own as C11 with kernels/ as the only
# include directory (so nothing from lib/ can creep in, even through another header), with
# warnings as errors, and names no lib/ file in an #include.
source "$(dirname "$0")/../harness.sh"

for h in "$ROOT"/kernels/*.h; do
    name=kernels/$(basename "$h")
    if grep -E -q '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]*lib/' "$h"; then
        notok "$name includes nothing from lib/ ($(grep -E '#[[:space:]]*include[[:space:]]*"[^"]*lib/' "$h" | head -1))"
    else ok "$name includes nothing from lib/"; fi
    if (cd "$T" && gcc -std=c11 -Wall -Wextra -Werror -fopenmp -fsyntax-only -I "$ROOT/kernels" -x c "$h") 2>"$T/err"; then
        ok "$name compiles alone with kernels/ as its include path"
    else notok "$name compiles alone with kernels/ as its include path"; sed 's/^/#   /' "$T/err" | head -10; fi
done
