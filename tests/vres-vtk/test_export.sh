#!/usr/bin/env bash
# vres-vtk on good input: a store to a .vtu file and to a directory, stdin, several inputs,
# buffers left out by default and --buffers, --fields, a run directory to a .pvd time series,
# a two-domain store counted by domain and type under each selection (--buffers, --domain),
# and a generated case end to end. Expected counts come from the store itself, read with
# h5ls/h5dump (not with vres), or from the construction of the two-domain store.
# (--help against the man page is checked for every tool by tests/man/test_synopsis.sh.)
source "$(dirname "$0")/../harness.sh"
VTK=$BIN/vres-vtk

# The store: the synthetic two-domain store of tests/lib/test_vtkio.c (buffer particles in
# both domains, wall normals, each particle where its domain owns), written by that test
# binary.
MAKER=$ROOT/$VRES_BUILD/tests/test_vtkio
if ! VRES_TEST_STORE_OUT=$T/syn.h5 "$MAKER" >/dev/null 2>&1; then
    notok "make the test store with $MAKER (build it: make $VRES_BUILD/tests/test_vtkio)"
    exit 1
fi

# Particles in a store: the sum of the Id dataset sizes over its domains.
store_count() {
    h5ls -r "$1" | awk '/^\/Domains\/D[0-9]+\/Id / { sub(/.*\{/, ""); n += $0 + 0 } END { print n + 0 }'
}
# Buffer particles (Type 1) in a store.
buffer_count() {
    local f=$1 n=0 k d
    for d in $(h5ls "$f/Domains" | awk '{ print $1 }'); do
        h5dump -y -w 0 -o "$T/type.txt" -d "/Domains/$d/Type" "$f" >/dev/null
        k=$(tr -s ', ' '\n\n' <"$T/type.txt" | grep -cx 1)
        n=$((n + k))
    done
    echo "$n"
}
# NumberOfPoints declared in a .vtu.
vtu_points() { grep -a -o 'NumberOfPoints="[0-9]*"' "$1" | grep -o '[0-9][0-9]*'; }
# True when the .vtu holds a point array of that name; lacks_array: the opposite.
has_array() { grep -a -q "<DataArray [^>]*Name=\"$2\"" "$1"; }
lacks_array() { ! has_array "$@"; }

N=$(store_count "$T/syn.h5")
NBUF=$(buffer_count "$T/syn.h5")
check "test store has particles and buffers" [ "$N" -gt 0 -a "$NBUF" -gt 0 ]

# One store to a named .vtu.
expect 0 "store to .vtu" "$VTK" --buffers "$T/syn.h5" -o "$T/one.vtu"
check "one.vtu is a VTK unstructured grid" grep -a -q '<VTKFile type="UnstructuredGrid"' "$T/one.vtu"
check "--buffers: one.vtu holds every particle" [ "$(vtu_points "$T/one.vtu")" = "$N" ]
ok_arrays=1
for a in Domain Type Mk Id Velocity Density Pressure Mass Dp Normal; do has_array "$T/one.vtu" $a || ok_arrays=0; done
check "one.vtu has every point array" [ $ok_arrays = 1 ]
check "one.vtu has the Type legend" grep -a -q 'Name="TypeNames"' "$T/one.vtu"
check "one.vtu has the time" grep -a -q 'Name="TimeValue"' "$T/one.vtu"
check "no temporary left" [ -z "$(ls -A "$T" | grep '^\.')" ]
check "silent on success" [ ! -s "$ERR" ]

# To a directory (created), named after the input.
expect 0 "store to new directory" "$VTK" --buffers "$T/syn.h5" -o "$T/dir/sub"
check "directory holds syn.vtu" [ "$(ls -A "$T/dir/sub")" = "syn.vtu" ]
cmp -s "$T/one.vtu" "$T/dir/sub/syn.vtu"; check "same content either way" [ $? = 0 ]

# From stdin: named after the case name recorded in the store.
run "$VTK" -v --buffers - -o "$T/stdin" <"$T/syn.h5"
check "stdin store exported" [ "$STATUS" = 0 -a "$(vtu_points "$T/stdin/synthetic.vtu")" = "$N" ]
check "-v names the file and its points" grep -q "synthetic.vtu: $N points" "$ERR"
check "-v counts each domain's particles by type" grep -q "D1 (dp 0.005 m): 1 fluid, 2 buffer, 1 moving" "$ERR"

# Several inputs into one directory.
cp "$T/syn.h5" "$T/a.h5"
cp "$T/syn.h5" "$T/b.h5"
expect 0 "two stores" "$VTK" "$T/a.h5" "$T/b.h5" -o "$T/two"
check "one .vtu per input" [ "$(ls "$T/two" | tr '\n' ' ')" = "a.vtu b.vtu " ]

# By default exactly the buffer particles are left out (every other one lies where its domain
# owns in this store).
expect 0 "default selection" "$VTK" "$T/syn.h5" -o "$T/nobuf.vtu"
check "default count = all - buffers" [ "$(vtu_points "$T/nobuf.vtu")" = $((N - NBUF)) ]

# --fields writes those arrays only (names case-insensitive).
expect 0 "--fields" "$VTK" --fields velocity,Mk "$T/syn.h5" -o "$T/sel.vtu"
check "--fields keeps Velocity" has_array "$T/sel.vtu" Velocity
check "--fields keeps Mk" has_array "$T/sel.vtu" Mk
check "--fields drops Density" lacks_array "$T/sel.vtu" Density
check "--fields drops Domain" lacks_array "$T/sel.vtu" Domain

# A run directory: snapshots out of order on disk, one with more digits.
mkdir "$T/run"
for k in 00010 00002 00000 100000; do cp "$T/syn.h5" "$T/run/snap_$k.h5"; done
echo "# run.tsv is not a snapshot" >"$T/run/run.tsv"
cp "$T/syn.h5" "$T/run/checkpoint.h5"
expect 0 "run directory" "$VTK" "$T/run/" -o "$T/vtk"
check "one .vtu per snapshot and a .pvd" \
    [ "$(ls "$T/vtk" | tr '\n' ' ')" = "run.pvd run_00000.vtu run_00002.vtu run_00010.vtu run_100000.vtu " ]
files=$(grep -o 'file="[^"]*"' "$T/vtk/run.pvd" | sed 's/file="//; s/"$//' | tr '\n' ' ')
check "pvd lists the snapshots in step order" [ "$files" = "run_00000.vtu run_00002.vtu run_00010.vtu run_100000.vtu " ]
all=1
for f in $files; do [ -f "$T/vtk/$f" ] || all=0; done
check "every file the pvd lists exists" [ $all = 1 ]
# The time is the store's root attribute "time" as h5dump prints it.
t=$(h5dump -y -w 0 -a /time "$T/syn.h5" | sed -n '/DATA {/,/}/p' | grep -o '[-0-9.e+]*' | head -1)
check "pvd times are the snapshots' times" [ "$(grep -c "timestep=\"$t\"" "$T/vtk/run.pvd")" = 4 ]
check "pvd collection is VTK XML" grep -q '<VTKFile type="Collection"' "$T/vtk/run.pvd"

# The two-domain tank of tests/lib/test_vtkio.c (two_domains(): buffers on both sides of the
# refinement box, the root's overlap fluid and wall inside it, the child's wall outside): the
# test binary writes it with the counts each selection must give, and counts a .vtu by Domain
# and Type with VTK's own reader.
VRES_TEST_DOMAINS_OUT=$T/tank2.h5 "$MAKER" >"$T/want.txt"
check "two-domain store written" [ -s "$T/tank2.h5" ]
# counts SEL: the expected "DOMAIN TYPE COUNT" lines of selection SEL (non-zero ones)
counts() { awk -v s="$1" '$1 == s && $4 > 0 {print $2, $3, $4}' "$T/want.txt"; }
# vtu_counts FILE: what the .vtu holds, by domain and type
vtu_counts() { VRES_TEST_VTU_COUNT=$1 "$MAKER"; }
for sel in default buffers domain1 domain1+buffers; do
    opts=()
    case $sel in buffers) opts=(--buffers) ;; domain1) opts=(--domain 1) ;; domain1+buffers) opts=(--domain 1 --buffers) ;; esac
    expect 0 "two domains, $sel" "$VTK" "${opts[@]}" "$T/tank2.h5" -o "$T/tank_$sel.vtu"
    check "two domains, $sel: counts by domain and type" diff <(counts $sel) <(vtu_counts "$T/tank_$sel.vtu")
done
# root: 50 x 20 fluid less the 10 x 15 in the box, 3 wall rows outside its 10 columns; child:
# its 20 x 30 fluid, 3 wall rows under the box
check "default: one fluid and one wall layer per point, no buffer" \
    [ "$(counts default | tr '\n' ' ')" = "0 fluid 850 0 fixed 120 1 fluid 600 1 fixed 60 " ]
check "--buffers: every particle of both domains" \
    [ "$(vtu_points "$T/tank_buffers.vtu")" = "$(awk '$1 == "buffers" {n += $4} END {print n}' "$T/want.txt")" ]
expect 0 "--domain 0 -v" "$VTK" -v --domain 0 "$T/tank2.h5" -o "$T/tank_d0.vtu"
check "--domain 0: the root's share" diff <(counts default | grep '^0 ') <(vtu_counts "$T/tank_d0.vtu")
check "-v lists only the domain written" [ "$(grep -c '  D[0-9]' "$ERR")" = 1 ]

# End to end from a case, when vres-gencase is there.
if [ -x "$BIN/vres-gencase" ] && [ -f "$CASES/dambreak2d/dambreak2d_Def.xml" ]; then
    expect 0 "gencase dambreak2d" "$BIN/vres-gencase" "$CASES/dambreak2d/dambreak2d_Def.xml" -o "$T/db.h5"
    if [ "$STATUS" = 0 ]; then
        expect 0 "dambreak2d to vtk" "$VTK" "$T/db.h5" -o "$T/db"
        check "dambreak2d .vtu holds every particle" [ "$(vtu_points "$T/db/db.vtu")" = "$(store_count "$T/db.h5")" ]
    fi
fi
