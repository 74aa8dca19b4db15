#!/usr/bin/env bash
# A refinement box that follows a floating body (<tracking mkbound="1"/> of a <floating>,
# lib/track.h; vres-run(1), Variable resolution): cases/floating_box2d's box (density 500,
# released 0.06 m above its equilibrium) at dp 0.025 m, with a dpratio-2 box around it that
# the free surface crosses, through vres-gencase | vres-partition | vres-run to 0.3 s (the
# body sinks about 0.05 m). Checked from the files with h5dump and awk:
#   - vres-partition: the box's domain gets every wall of the tank (its path is not known) and
#     the root keeps all of its own; track_until is infinite;
#   - the box's motion in every snapshot (track_shift) is the body's displacement (/Bodies
#     center), to 1e-12 m;
#   - D1's fluid inside the moved box and its buffer inside the moved band;
#   - the ledger within the run's bound (one particle mass per segment);
#   - a restart from a snapshot continues bit for bit (particles, segments, the box, the body);
#   - a box that follows a floating body out of its parent's box stops the run, naming it.
source "$(dirname "$0")/../harness.sh"
XML=$CASES/floating_box2d/floating_box2d_Def.xml
snap() { printf '%s/snap_%05d.h5' "$1" "$2"; }
box='<bufferbox> <point x="0.3" y="0" z="0.25" /> <size x="0.4" y="0" z="0.6" /> <dpratio v="2" /> <tracking mkbound="1" /> </bufferbox>'
sed -e "s#</geometry>#</geometry> <vres active=\"true\"> $box </vres>#" \
    -e 's|key="TimeMax" value="2.5"|key="TimeMax" value="0.3"|' "$XML" >"$T/tf_Def.xml"
check "the case has a box that follows mkbound 1" grep -q '<tracking mkbound="1" />' "$T/tf_Def.xml"
expect 0 "vres-gencase | vres-partition at dp 0.025" \
    sh -c "'$BIN/vres-gencase' -q --dp 0.025 '$T/tf_Def.xml' -o '$T/case.h5' && '$BIN/vres-partition' -q '$T/case.h5' -o '$T/parts.h5'"
check "D1 follows mkbound 1 for as long as the run goes (track_until inf)" \
    [ "$(attr /Domains/D1/tracking_mk "$T/parts.h5")" = 1 -a "$(attr /Domains/D1/track_until "$T/parts.h5")" = inf ]
span() { # DOMAIN FILE: the extent in x and z of the domain's fixed walls (type 2) and their count
    paste <(values "/Domains/$1/Type" "$2") <(values "/Domains/$1/Position" "$2" | paste - - -) |
        awk '$1 == 2 {n++; if (n == 1 || $2 < a) a = $2; if (n == 1 || $2 > b) b = $2; if (n == 1 || $4 < c) c = $4}
             END {print n + 0, a, b, c}'
}
read -r n1 x1 x2 z1 < <(span D1 "$T/parts.h5")
check "D1 has the whole tank's walls at its dp ($n1, x $x1 to $x2, z from $z1 m)" \
    awk -v n="$n1" -v a="$x1" -v b="$x2" -v c="$z1" 'BEGIN {exit !(n > 0 && a < 0 && b > 1 && c < 0)}'
read -r r0 _ < <(span D0 "$T/case.h5")
read -r p0 _ < <(span D0 "$T/parts.h5")
check "the root keeps all its $r0 walls ($p0)" [ "$r0" -gt 0 -a "$r0" = "$p0" ]

expect 0 "vres-run to 0.3 s, output every 0.05 s" "$BIN/vres-run" --threads 1 --tout 0.05 "$T/parts.h5" -o "$T/a"
check "no drift warning" sh -c "! grep -q drifted '$ERR'"
check "snapshots 0 to 6 written" [ -f "$(snap "$T/a" 6)" -a ! -e "$(snap "$T/a" 7)" ]
c0=$(attr /Bodies/B0/center "$(snap "$T/a" 0)" | tr '\n' ' ')
worst=0 nsnap=0
for k in 0 1 2 3 4 5 6; do
    f=$(snap "$T/a" $k)
    e=$(awk -v c0="$c0" -v c="$(attr /Bodies/B0/center "$f" | tr '\n' ' ')" \
            -v d="$(attr /Domains/D1/track_shift "$f" | tr '\n' ' ')" 'BEGIN {
        split(c0, A, " "); split(c, B, " "); split(d, D, " "); m = 0
        for (i = 1; i <= 3; i++) { x = D[i] - (B[i] - A[i]); if (x < 0) x = -x; if (x > m) m = x }
        printf "%.3g", m}')
    worst=$(awk -v a="$worst" -v b="$e" 'BEGIN {print (b > a ? b : a)}')
    nsnap=$((nsnap + 1))
done
dz=$(comp /Domains/D1/track_shift "$(snap "$T/a" 6)" 3)
echo "# the box moved $dz m along z by 0.3 s; largest |track_shift - body displacement| $worst m over $nsnap snapshots"
check "the box sank with the body (track_shift z $dz m)" awk -v d="$dz" 'BEGIN {exit !(d < -0.02 && d > -0.1)}'
check "track_shift = the body's displacement (1e-12 m) in all 7 snapshots" \
    awk -v e="$worst" -v n=$nsnap 'BEGIN {exit !(n == 7 && e <= 1e-12)}'

# D1's fluid in the moved box, its buffer in the moved band (x and z, shift along z, 1e-9 m)
inside() { # FILE TYPE LO HI DZ: particles of TYPE in D1 and how many lie outside D1's box LO..HI moved by DZ
    local lo hi
    lo=$(attr "/Domains/D1/$3" "$1" | tr '\n' ' ') hi=$(attr "/Domains/D1/$4" "$1" | tr '\n' ' ')
    paste <(values /Domains/D1/Type "$1") <(values /Domains/D1/Position "$1" | paste - - -) |
        awk -v t="$2" -v lo="$lo" -v hi="$hi" -v s="$5" 'BEGIN {split(lo, L, " "); split(hi, H, " ")}
            $1 == t {n++; z = $4 - s; if (!($2 >= L[1] - 1e-9 && $2 <= H[1] + 1e-9 && z >= L[3] - 1e-9 && z <= H[3] + 1e-9)) bad++}
            END {print n + 0, bad + 0}'
}
bad=
for k in 2 6; do
    f=$(snap "$T/a" $k) s=$(comp /Domains/D1/track_shift "$(snap "$T/a" $k)" 3)
    read -r n1 b1 < <(inside "$f" 0 box_min box_max "$s")
    read -r n2 b2 < <(inside "$f" 1 buffer_min buffer_max "$s")
    [ "$n1" -gt 0 -a "$n2" -gt 0 -a "$b1" -eq 0 -a "$b2" -eq 0 ] || bad="$bad snap $k: $b1/$n1 fluid, $b2/$n2 buffer;"
done
check "snapshots 2 and 6: D1 fluid in the moved box, D1 buffer in the moved band${bad:+ ($bad)}" [ -z "$bad" ]

f=$(snap "$T/a" 6)
ledger_within_bound "$f" "$T/a" 14

# restart bit for bit
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00003.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/b/snap_00003.h5"
diffs=
fa=$(snap "$T/a" 6) fb=$(snap "$T/b" 6)
for d in D0 D1; do
    for ds in Position Velocity Density Mass Type Id; do
        h5diff -q "$fa" "$fb" "/Domains/$d/$ds" "/Domains/$d/$ds" >/dev/null || diffs="$diffs $d/$ds"
    done
done
for i in I0 I1; do h5diff -q "$fa" "$fb" "/Interfaces/$i/Mass" "/Interfaces/$i/Mass" >/dev/null || diffs="$diffs $i/Mass"; done
for a in /Domains/D1/track_rotation /Domains/D1/track_shift /Domains/D1/track_velocity /Bodies/B0/center /Bodies/B0/vel; do
    [ "$(attr "$a" "$fa")" = "$(attr "$a" "$fb")" ] || diffs="$diffs $a"
done
check "snap_00006.h5 after the restart equals the uninterrupted run's bit for bit${diffs:+ (differs:$diffs)}" \
    [ -z "$diffs" -a -f "$fb" ]

# a box that follows the body out of its parent: a static box around a tracking one with little
# room below; the body sinks and the tracking box's band leaves the static box: the run stops
two='<bufferbox> <point x="0.3" y="0" z="0.2" /> <size x="0.4" y="0" z="0.7" /> <dpratio v="2" /> <bufferbox> <point x="0.35" y="0" z="0.25" /> <size x="0.3" y="0" z="0.6" /> <dpratio v="2" /> <tracking mkbound="1" /> </bufferbox> </bufferbox>'
sed -e "s#</geometry>#</geometry> <vres active=\"true\"> $two </vres>#" \
    -e 's|key="TimeMax" value="2.5"|key="TimeMax" value="0.3"|' "$XML" >"$T/out_Def.xml"
expect 0 "vres-gencase | vres-partition of the nested case" \
    sh -c "'$BIN/vres-gencase' -q --dp 0.025 '$T/out_Def.xml' -o '$T/out.h5' && '$BIN/vres-partition' -q '$T/out.h5' -o '$T/outp.h5'"
run "$BIN/vres-run" -q --threads 1 --tout 0.05 "$T/outp.h5" -o "$T/o"
check "the run stops (exit $STATUS)" [ "$STATUS" -ne 0 ]
check "naming the box, the body and the parent it left" \
    grep -q "domain D2's box, which follows floating body mkbound 1, left its parent D1's box" "$ERR"
[ "$STATUS" -ne 0 ] || sed 's/^/#   /' "$ERR" | tail -3
