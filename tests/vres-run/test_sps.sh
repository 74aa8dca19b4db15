#!/usr/bin/env bash
# vres-run with laminar+SPS viscosity (ViscoTreatment=2, kernels/sps.h): the module list names
# it; the sub-particle stress acts (the dam break with SPS differs from the laminar run with
# the same Visco, which it would not if the stress were left out); a run restarts from a
# snapshot bit for bit (tau is computed from the state the snapshot holds, not carried from the
# previous step as DualSPHysics does), in 2D and 3D; and cases/floating_box2d with SPS restarts
# bit for bit too, particles and /Bodies (the stress is summed into the body's force).
source "$(dirname "$0")/../harness.sh"
RUN=$BIN/vres-run
DB=$CASES/dsph_dambreak2d/dambreak2d_Def.xml

"$BIN/vres-gencase" -q --dp 0.05 --set ViscoTreatment=2 --set Visco=1e-6 "$DB" -o "$T/sps.h5" || notok "gencase SPS"
"$BIN/vres-gencase" -q --dp 0.05 --set ViscoTreatment=3 --set Visco=1e-6 "$DB" -o "$T/lam.h5" || notok "gencase laminar"
expect 0 "dam break with laminar+SPS to 0.1 s" "$RUN" --threads 2 --tmax 0.1 --tout 0.02 "$T/sps.h5" -o "$T/a"
check "the module list names laminar+SPS" grep -q 'laminar-sps-viscosity(nu=1e-06 m^2/s, cs=0.12, ci=0.0066)' "$ERR"
expect 0 "the same with laminar viscosity" "$RUN" -q --threads 2 --tmax 0.1 --tout 0.02 "$T/lam.h5" -o "$T/l"
check "the SPS stress changes the flow (positions at 0.1 s differ from the laminar run's)" \
    sh -c "! h5diff -q '$T/a/snap_00005.h5' '$T/l/snap_00005.h5' /Domains/D0/Position /Domains/D0/Position"

same_after_restart "2D dam break" "$T/a" 00002 00003 00005

# 3D (the CPU's 3D cell-wise variants): a coarse 3D dam break restarts bit for bit
"$BIN/vres-gencase" -q --dp 0.05 --set ViscoTreatment=2 --set Visco=1e-6 "$CASES/bench_dambreak3d/bench_dambreak3d_Def.xml" \
    -o "$T/db3.h5" || notok "gencase the 3D dam break with SPS"
expect 0 "3D dam break with SPS to 0.03 s" "$RUN" --threads 2 --tmax 0.03 --tout 0.01 "$T/db3.h5" -o "$T/d3a"
check "3D: the module list names laminar+SPS" grep -q 'wcsph-3d .*laminar-sps-viscosity' "$ERR"
same_after_restart "3D dam break" "$T/d3a" 00001 00003

# a floating body with SPS: restarts bit for bit, body state included
"$BIN/vres-gencase" -q --dp 0.04 --set ViscoTreatment=2 --set Visco=1e-6 "$CASES/floating_box2d/floating_box2d_Def.xml" \
    -o "$T/box.h5" || notok "gencase the floating box with SPS"
expect 0 "floating box with SPS to 0.06 s" "$RUN" -q --threads 1 --tmax 0.06 --tout 0.01 "$T/box.h5" -o "$T/fa"
same_after_restart "floating box" "$T/fa" 00003 00006
# the attribute's dump without its first line (which names the file); empty when it is missing
body_attr() { h5dump -m '%.17g' -a "/Bodies/B0/$1" "$2" 2>/dev/null | sed 1d; }
for at in center quat vel omega force; do
    a=$(body_attr $at "$T/fa/snap_00006.h5") b=$(body_attr $at "$T/fa.r/snap_00006.h5")
    check "box snap 6 /Bodies/B0 $at equal" [ -n "$a" -a "$a" = "$b" ]
done
