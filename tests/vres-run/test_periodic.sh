#!/usr/bin/env bash
# vres-run with periodic boundaries in x and z (XZPeriodic): a 2-D box of water, 10 x 10
# particles, periodic both ways and without walls, falls under gravity (1, 0, -2) m/s^2. Every
# particle has the same neighbourhood through the periodic images, so nothing but gravity acts
# and each moves by g t^2/2 (the Symplectic step is exact for a constant acceleration): 0.125 m
# along x and -0.25 m along z by t = 0.5 s, more than the 0.1 m period, so every particle
# leaves through a side and comes back in through the opposite one. Reference: that uniform
# motion, wrapped into the period. Tolerance: velocities are stored in single precision, so
# each of the 1674 steps rounds v (about 1 m/s) by up to 2^-24 |v| = 7e-8 m/s: at most 1.2e-4
# m/s in all, and t times that, 6e-5 m, in position (measured 1.0e-5 m/s and 2.4e-6 m,
# 2026-11); a particle not wrapped, or wrapped by a wrong period, is off by a centimetre or
# leaves the domain (exit 3). That the images complete every neighbourhood is checked by
# tests/lib/test_solver.c (periodic_lattice_has_no_edges): here the density is uniform, so
# no pressure acts either way.
source "$(dirname "$0")/../harness.sh"
cat >"$T/box_Def.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<case>
    <casedef>
        <constantsdef>
            <gravity x="1" y="0" z="-2" />
            <rhop0 value="1000" /> <gamma value="7" /> <rhopgradient value="1" />
            <hswl value="0.1" auto="false" /> <speedsystem value="0" auto="true" />
            <coefsound value="20" /> <speedsound value="0" auto="true" />
            <coefh value="1.0" /> <cflnumber value="0.2" />
        </constantsdef>
        <mkconfig boundcount="240" fluidcount="9" />
        <geometry>
            <definition dp="0.01">
                <pointref x="0.005" y="0" z="0.005" />
                <pointmin x="-0.1" y="0" z="-0.1" /> <pointmax x="0.2" y="0" z="0.2" />
            </definition>
            <commands>
                <mainlist>
                    <setdrawmode mode="solid" />
                    <setmkfluid mk="0" />
                    <drawbox> <boxfill>solid</boxfill> <point x="0" y="0" z="0" /> <size x="0.1" y="0" z="0.1" /> </drawbox>
                </mainlist>
            </commands>
        </geometry>
    </casedef>
    <execution>
        <parameters>
            <parameter key="StepAlgorithm" value="2" /> <parameter key="Visco" value="0.01" />
            <parameter key="XZPeriodic" value="1" />
            <parameter key="TimeMax" value="0.5" /> <parameter key="TimeOut" value="0.5" />
        </parameters>
    </execution>
</case>
XML
expect 0 "gencase the periodic box" "$BIN/vres-gencase" "$T/box_Def.xml" -o "$T/box.h5"
expect 0 "run 0.5 s of free fall" "$BIN/vres-run" "$T/box.h5" -o "$T/run"
check "modules name periodic xz" grep -q 'periodic(xz)' "$ERR"
TSV=$T/run/run.tsv
check "fluid count and mass kept (100 particles, 10 kg)" awk -F'\t' '!/^#/ && ($4 != 100 || $6 != 10) {exit 1}' "$TSV"
t=$(awk 'END {print $1}' "$TSV")
last=$T/run/snap_00001.h5
# position by id at the start and at the end
paste <(values /Domains/D0/Id "$T/box.h5") <(values /Domains/D0/Position "$T/box.h5" | paste - - -) | sort -n >"$T/p0"
paste <(values /Domains/D0/Id "$last") <(values /Domains/D0/Position "$last" | paste - - -) \
      <(values /Domains/D0/Velocity "$last" | paste - - -) | sort -n >"$T/p1"
res=$(join "$T/p0" "$T/p1" | awk -v t="$t" '
    function wrap(u) { u = u - 0.0 ; while (u < 0) u += 0.1; while (u >= 0.1) u -= 0.1; return u }
    { ex = wrap($2 + 0.5 * t * t) ; ez = wrap($4 - t * t)
      dx = $5 - ex; if (dx > 0.05) dx -= 0.1; if (dx < -0.05) dx += 0.1
      dz = $7 - ez; if (dz > 0.05) dz -= 0.1; if (dz < -0.05) dz += 0.1
      e = dx * dx + dz * dz; if (e > emax) emax = e
      if ($5 < 0 || $5 >= 0.1 || $7 < 0 || $7 >= 0.1) out++
      dv = ($8 - t) * ($8 - t) + ($10 + 2 * t) * ($10 + 2 * t); if (dv > vmax) vmax = dv; n++ }
    END { printf "%d %d %.3g %.3g", n, out, sqrt(emax), sqrt(vmax) }')
set -- $res
echo "# t = $t s: $1 particles, $2 outside the period, position error $3 m, velocity error $4 m/s"
check "every particle found by id ($1)" [ "$1" -eq 100 ]
check "every particle inside the period [0, 0.1) m ($2 outside)" [ "$2" -eq 0 ]
check "positions are the wrapped uniform fall (error $3 m)" awk -v e="$3" 'BEGIN {exit !(e < 6e-5)}'
check "velocities are g t (error $4 m/s)" awk -v e="$4" 'BEGIN {exit !(e < 1.2e-4)}'

# The same box periodic along x only (XPeriodicIncZ 0), falling along x (gravity (1, 0, 0)),
# with a <simulationdomain> given in part, as DualSPHysics' examples write it (x "default", z
# "default + 50%"): along x the domain is still the particles' extent, so the period is that
# extent plus dp, 0.1 m (examples/main/11_Floating/CaseFloatingSphereVal2D: its floor reaches
# both periodic ends). Taking the given domain's 0.09 m instead put the last column on the
# domain's edge: the run stopped before its first step.
sed -e 's|<gravity x="1" y="0" z="-2" />|<gravity x="1" y="0" z="0" />|' \
    -e 's|<parameter key="XZPeriodic" value="1" />|<parameter key="XPeriodicIncZ" value="0" />\n            <simulationdomain> <posmin x="default" y="default" z="default" /> <posmax x="default" y="default" z="default + 50%" /> </simulationdomain>|' \
    "$T/box_Def.xml" >"$T/boxx_Def.xml"
expect 0 "gencase the box periodic in x, its domain given in part" "$BIN/vres-gencase" "$T/boxx_Def.xml" -o "$T/boxx.h5"
check "the store flags x as spanning the particles (domain_default)" \
    [ "$(attr /Parameters/domain_default "$T/boxx.h5" | head -1)" = 1 ]
expect 0 "run 0.5 s of fall along x" "$BIN/vres-run" "$T/boxx.h5" -o "$T/runx"
check "modules name periodic x" grep -q 'periodic(x)' "$ERR"
t=$(awk 'END {print $1}' "$T/runx/run.tsv")
paste <(values /Domains/D0/Id "$T/runx/snap_00001.h5") <(values /Domains/D0/Position "$T/runx/snap_00001.h5" | paste - - -) |
    sort -n >"$T/px"
res=$(join "$T/p0" "$T/px" | awk -v t="$t" '
    function wrap(u) { while (u < 0) u += 0.1; while (u >= 0.1) u -= 0.1; return u }
    { dx = $5 - wrap($2 + 0.5 * t * t); if (dx > 0.05) dx -= 0.1; if (dx < -0.05) dx += 0.1
      dz = $7 - $4; e = dx * dx + dz * dz; if (e > emax) emax = e; n++ }
    END { printf "%d %.3g", n, sqrt(emax) }')
set -- $res
check "x-periodic: every particle found ($1) and the wrapped uniform fall, period 0.1 m (error $2 m)" \
    awk -v n="$1" -v e="$2" 'BEGIN {exit !(n == 100 && e < 6e-5)}'
