#!/usr/bin/env bash
# vres-vtk on good input: a store to a .vtu file and to a directory, stdin, several inputs,
# --no-buffer and --fields, a run directory to a .pvd time series, and a generated case end to
# end. Expected counts come from the store itself, read with h5ls/h5dump (not with vres).
# (--help against the man page is checked for every tool by tests/man/test_synopsis.sh.)
source "$(dirname "$0")/../harness.sh"
VTK=$BIN/vres-vtk

# The store: the synthetic two-domain store of tests/lib/test_vtkio.c (buffer particles in
# both domains, wall normals), written by that test binary.
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
expect 0 "store to .vtu" "$VTK" "$T/syn.h5" -o "$T/one.vtu"
check "one.vtu is a VTK unstructured grid" grep -a -q '<VTKFile type="UnstructuredGrid"' "$T/one.vtu"
check "one.vtu holds every particle" [ "$(vtu_points "$T/one.vtu")" = "$N" ]
ok_arrays=1
for a in Domain Type Mk Id Velocity Density Pressure Mass Dp Normal; do has_array "$T/one.vtu" $a || ok_arrays=0; done
check "one.vtu has every point array" [ $ok_arrays = 1 ]
check "one.vtu has the Type legend" grep -a -q 'Name="TypeNames"' "$T/one.vtu"
check "one.vtu has the time" grep -a -q 'Name="TimeValue"' "$T/one.vtu"
check "no temporary left" [ -z "$(ls -A "$T" | grep '^\.')" ]
check "silent on success" [ ! -s "$ERR" ]

# To a directory (created), named after the input.
expect 0 "store to new directory" "$VTK" "$T/syn.h5" -o "$T/dir/sub"
check "directory holds syn.vtu" [ "$(ls -A "$T/dir/sub")" = "syn.vtu" ]
cmp -s "$T/one.vtu" "$T/dir/sub/syn.vtu"; check "same content either way" [ $? = 0 ]

# From stdin: named after the case name recorded in the store.
run "$VTK" -v - -o "$T/stdin" <"$T/syn.h5"
check "stdin store exported" [ "$STATUS" = 0 -a "$(vtu_points "$T/stdin/synthetic.vtu")" = "$N" ]
check "-v names the file and its points" grep -q "synthetic.vtu: $N points" "$ERR"

# Several inputs into one directory.
cp "$T/syn.h5" "$T/a.h5"
cp "$T/syn.h5" "$T/b.h5"
expect 0 "two stores" "$VTK" "$T/a.h5" "$T/b.h5" -o "$T/two"
check "one .vtu per input" [ "$(ls "$T/two" | tr '\n' ' ')" = "a.vtu b.vtu " ]

# --no-buffer drops exactly the buffer particles.
expect 0 "--no-buffer" "$VTK" --no-buffer "$T/syn.h5" -o "$T/nobuf.vtu"
check "--no-buffer count = all - buffers" [ "$(vtu_points "$T/nobuf.vtu")" = $((N - NBUF)) ]

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

# End to end from a case, when vres-gencase is there.
if [ -x "$BIN/vres-gencase" ] && [ -f "$CASES/dambreak2d/dambreak2d_Def.xml" ]; then
    expect 0 "gencase dambreak2d" "$BIN/vres-gencase" "$CASES/dambreak2d/dambreak2d_Def.xml" -o "$T/db.h5"
    if [ "$STATUS" = 0 ]; then
        expect 0 "dambreak2d to vtk" "$VTK" "$T/db.h5" -o "$T/db"
        check "dambreak2d .vtu holds every particle" [ "$(vtu_points "$T/db/db.vtu")" = "$(store_count "$T/db.h5")" ]
    fi
fi
