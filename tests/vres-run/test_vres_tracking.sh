#!/usr/bin/env bash
# A refinement box that follows a moving body (<tracking mkbound="1"/>, lib/track.h;
# vres-run(1), Variable resolution): cases/tracking_plate2d, a block pulled through still water
# (2 m/s^2 for 0.1 s, then 0.2 m/s along x), with a dpratio-2 box around it, through
# vres-gencase | vres-partition | vres-run to 0.3 s (0.05 m of travel, five fine spacings).
# Checked from the files with h5dump and awk, not with vres' own reader:
#   - the box's motion in every snapshot (track_shift) is the block's: the mean displacement of
#     the fine domain's block particles, and the motion's closed form;
#   - the regions moved: every fine fluid particle inside the moved box, every fine buffer
#     particle inside the moved band, fine particles ahead of where the box and band were at
#     t = 0 (created by the moved segments), no coarse fluid in the moved hole;
#   - the mass ledger closes within the run's own bound (one particle mass per segment), and
#     both domains created and deleted particles at the moving interfaces; nothing non-finite;
#   - a restart from a snapshot continues bit for bit (every dataset, the segments' masses, the
#     box's motion, ledger.tsv);
#   - post-processing owns points by the moved box (vres-vtk's per-domain counts);
#   - a run beyond the time the partition drew the box's path for is refused, nothing written.
source "$(dirname "$0")/../harness.sh"
CASE=$CASES/tracking_plate2d/tracking_plate2d_Def.xml


expect 0 "vres-gencase | vres-partition of the case" \
    sh -c "'$BIN/vres-gencase' -q '$CASE' | '$BIN/vres-partition' -q - -o '$T/parts.h5'"
check "the partition's D1 follows mkbound 1 from where it stands (track_shift 0, rotation I)" \
    [ "$(attr /Domains/D1/track_shift "$T/parts.h5" | tr '\n' ' ')" = "0 0 0 " -a \
      "$(attr /Domains/D1/track_rotation "$T/parts.h5" | tr '\n' ' ')" = "1 0 0 0 1 0 0 0 1 " -a \
      "$(attr /Domains/D1/tracking_mk "$T/parts.h5")" = 1 ]
check "its path is drawn up to TimeMax (track_until 0.4 s)" [ "$(attr /Domains/D1/track_until "$T/parts.h5")" = 0.40000000000000002 ]

expect 0 "vres-gencase | vres-partition | vres-run to 0.3 s, output every 0.05 s" \
    sh -c "'$BIN/vres-gencase' -q '$CASE' | '$BIN/vres-partition' -q - | '$BIN/vres-run' --threads 1 --tmax 0.3 --tout 0.05 - -o '$T/a'"
check "snapshots 0 to 6 written" [ -f "$T/a/snap_00006.h5" -a ! -e "$T/a/snap_00007.h5" ]
check "no drift warning" sh -c "! grep -q drifted '$ERR'"

# ---- the box follows the block
snap() { printf '%s/snap_%05d.h5' "$1" "$2"; }
# mean x of D1's moving particles (type 3) in snapshot FILE
block_x() {
    paste <(values /Domains/D1/Type "$1") <(values /Domains/D1/Position "$1" | paste - - -) |
        awk '$1 == 3 {s += $2; n++} END {if (n) printf "%.17g\n", s / n; else print "none"}'
}
x0=$(block_x "$(snap "$T/a" 0)")
worst_body=0 worst_form=0 nsnap=0
for k in 0 1 2 3 4 5 6; do
    f=$(snap "$T/a" $k)
    t=$(attr /time "$f") # the snapshot's time at full precision (run.tsv prints 9 digits)
    sx=$(comp /Domains/D1/track_shift "$f" 1)
    bx=$(block_x "$f")
    read -r eb ef < <(awk -v s="$sx" -v b="$bx" -v b0="$x0" -v t="$t" 'BEGIN {
        d = t <= 0.1 ? t * t : 0.01 + 0.2 * (t - 0.1)
        eb = s - (b - b0); ef = s - d; if (eb < 0) eb = -eb; if (ef < 0) ef = -ef
        printf "%.3g %.3g\n", eb, ef}')
    worst_body=$(awk -v a="$worst_body" -v b="$eb" 'BEGIN {print (b > a ? b : a)}')
    worst_form=$(awk -v a="$worst_form" -v b="$ef" 'BEGIN {print (b > a ? b : a)}')
    nsnap=$((nsnap + 1))
done
last_shift=$(comp /Domains/D1/track_shift "$(snap "$T/a" 6)" 1)
echo "# box shift at t = $(grep -v '^#' "$T/a/run.tsv" | tail -1 | cut -f1) s: $last_shift m; largest error against the block's particles $worst_body m, against the closed form $worst_form m ($nsnap snapshots)"
check "the box moved 0.05 m with the block by 0.3 s" awk -v s="$last_shift" 'BEGIN {exit !(s > 0.049 && s < 0.051)}'
check "box shift = the block's displacement (1e-12 m) in all 7 snapshots" awk -v e="$worst_body" -v n=$nsnap 'BEGIN {exit !(n == 7 && e <= 1e-12)}'
check "box shift = the motion's closed form (1e-12 m)" awk -v e="$worst_form" 'BEGIN {exit !(e <= 1e-12)}'

# ---- vres-forces' motion columns of a moving body: its centre and velocity by the motion at each
# snapshot's time (the store's centre is the body's at t = 0), against the closed form
expect 0 "vres-forces --mk 1 of the run (a moving body)" "$BIN/vres-forces" -q --mk 1 "$T/a" -o "$T/fa.tsv"
check "its header names the moving body's motion columns" \
    grep -q -P '^# time_s\tfx_N.*\tmz_Nm\tcx_m\tcy_m\tcz_m\tvx_m_s\tvy_m_s\tvz_m_s\tangle_rad$' "$T/fa.tsv"
c0=$(attr /Bodies/B0/center "$(snap "$T/a" 0)" | head -1)
worst_c=$(awk -F'\t' -v c0="$c0" '!/^#/ {t = $1; d = t <= 0.1 ? t * t : 0.01 + 0.2 * (t - 0.1)
        v = t <= 0.1 ? 2 * t : 0.2; e = $8 - c0 - d; f = $11 - v; if (e < 0) e = -e; if (f < 0) f = -f
        if (e > m) m = e; if (f > m) m = f; n++}
    END {print (n == 7 ? m : "rows " n)}' "$T/fa.tsv")
check "cx - cx(0) and vx follow the closed form in all 7 rows (1e-7: vres-forces prints 8 digits; largest $worst_c)" \
    awk -v e="$worst_c" 'BEGIN {exit !(e + 0 == e && e <= 1e-7)}'

# ---- the regions moved with it: per snapshot, D1's fluid inside the moved box, D1's buffer
# inside the moved band, D0's fluid outside the moved hole (closed boxes, 1e-9 m)
# inside FILE DOMAIN TYPE LO HI SHIFT [out]: the particles of TYPE of DOMAIN and how many of them lie
# outside (with out: inside) the box [LO, HI] of D1's attributes moved by SHIFT along x (x and z
# tested, 1e-9 m)
inside() {
    local lo hi
    lo=$(attr "/Domains/D1/$4" "$1" | tr '\n' ' ') hi=$(attr "/Domains/D1/$5" "$1" | tr '\n' ' ')
    paste <(values "/Domains/$2/Type" "$1") <(values "/Domains/$2/Position" "$1" | paste - - -) |
        awk -v t="$3" -v lo="$lo" -v hi="$hi" -v s="$6" -v want="${7:-in}" '
            BEGIN {split(lo, L, " "); split(hi, H, " ")}
            $1 == t {n++; x = $2 - s; z = $4
                     in_ = x >= L[1] - 1e-9 && x <= H[1] + 1e-9 && z >= L[3] - 1e-9 && z <= H[3] + 1e-9
                     if ((want == "in") != in_) bad++}
            END {print n + 0, bad + 0}'
}
bad_regions=
for k in 1 3 6; do
    f=$(snap "$T/a" $k) s=$(comp /Domains/D1/track_shift "$(snap "$T/a" $k)" 1)
    read -r n1 b1 < <(inside "$f" D1 0 box_min box_max "$s")
    read -r n2 b2 < <(inside "$f" D1 1 buffer_min buffer_max "$s")
    # D0's fluid strictly outside the moved hole, up to 1e-9 m
    read -r n3 b3 < <(inside "$f" D0 0 hole_min hole_max "$s" out)
    [ "$n1" -gt 0 -a "$n2" -gt 0 -a "$n3" -gt 0 -a "$b1" -eq 0 -a "$b2" -eq 0 -a "$b3" -eq 0 ] ||
        bad_regions="$bad_regions snap $k: $b1/$n1 D1 fluid, $b2/$n2 D1 buffer, $b3/$n3 D0 fluid;"
done
check "snapshots 1, 3, 6: D1 fluid in the moved box, D1 buffer in the moved band, D0 fluid out of the moved hole" \
    [ -z "$bad_regions" ]
[ -n "$bad_regions" ] && echo "#$bad_regions"
f=$(snap "$T/a" 6)
read -r n ahead_f < <(inside "$f" D1 0 box_min box_max 0)
read -r n ahead_b < <(inside "$f" D1 1 buffer_min buffer_max 0)
echo "# at 0.3 s: $ahead_f D1 fluid particles outside the box's place at t = 0, $ahead_b D1 buffer particles outside its band's"
check "D1 fluid and buffer lie where the box and band were not at t = 0 (the moved segments created there)" \
    [ "$ahead_f" -gt 0 -a "$ahead_b" -gt 0 ]

# ---- the ledger: columns 3 domain, 8 created, 12 deleted_buffer, 19 total mass, 20 drift
ledger_within_bound "$f" "$T/a" 14
last() { grep -v '^#' "$T/a/ledger.tsv" | awk -F'\t' -v k="$1" -v c="$2" '$3 == k {v = $c} END {print v + 0}'; }
check "both domains created particles at their moving segments, D1 deleted buffer past its trailing edge" \
    [ "$(last 0 8)" -gt 0 -a "$(last 1 8)" -gt 0 -a "$(last 1 12)" -gt 0 ]
check "run.tsv: every speed and density finite" \
    awk -F'\t' '!/^#/ {n++; for (i = 7; i <= 9; i++) if ($i !~ /^[0-9.e+-]+$/) exit 1} END {exit !(n == 7)}' "$T/a/run.tsv"
check "the last snapshot holds no NaN or Inf" \
    sh -c "! h5dump -d /Domains/D0/Velocity -d /Domains/D1/Velocity -d /Domains/D0/Density -d /Domains/D1/Density '$f' | grep -qi 'nan\|inf'"

# ---- restart bit for bit
cp -r "$T/a" "$T/b"
expect 0 "restart from snap_00004.h5" "$BIN/vres-run" -q --threads 1 --restart "$T/b/snap_00004.h5"
diffs=
for k in 5 6; do
    fa=$(snap "$T/a" $k) fb=$(snap "$T/b" $k)
    for d in D0 D1; do
        for ds in Position Velocity Density Pressure Mass Type Mk Id; do
            h5diff -q "$fa" "$fb" "/Domains/$d/$ds" "/Domains/$d/$ds" >/dev/null || diffs="$diffs $k:$d/$ds"
        done
    done
    for i in I0 I1; do
        h5diff -q "$fa" "$fb" "/Interfaces/$i/Mass" "/Interfaces/$i/Mass" >/dev/null || diffs="$diffs $k:$i/Mass"
    done
    for a in track_rotation track_shift track_velocity; do
        [ "$(attr "/Domains/D1/$a" "$fa")" = "$(attr "/Domains/D1/$a" "$fb")" ] || diffs="$diffs $k:$a"
    done
done
check "snapshots 5 and 6 equal bit for bit (every dataset, segment masses, the box's motion)${diffs:+: differ in$diffs}" [ -z "$diffs" ]
check "ledger.tsv the same file" cmp -s "$T/a/ledger.tsv" "$T/b/ledger.tsv"

# ---- post-processing owns points by the moved box: vres-vtk writes D0's fluid outside it only
expect 0 "vres-vtk -v of the last snapshot" "$BIN/vres-vtk" -v "$f" -o "$T/last.vtu"
vtk_d0=$(sed -n 's/.*D0 (dp [^)]*): \([0-9]*\) fluid.*/\1/p' "$ERR")
read -r n0 in_moved < <(inside "$f" D0 0 box_min box_max "$(comp /Domains/D1/track_shift "$f" 1)")
read -r n0 in_still < <(inside "$f" D0 0 box_min box_max 0)
echo "# D0 fluid $n0: $in_moved outside the moved box (vres-vtk wrote $vtk_d0), $in_still outside the box's place at t = 0"
# (inside ... counts those outside [LO, HI]: here the particles D0 owns)
check "vres-vtk wrote D0's fluid outside the moved box, not outside the box's first place" \
    [ -n "$vtk_d0" -a "$vtk_d0" = "$in_moved" -a "$in_still" != "$in_moved" ]

# ---- beyond the drawn path
expect_err 1 "partition again with a larger TimeMax" "a run to 0.5 s is refused (the path is drawn to 0.4 s)" \
    "$BIN/vres-run" --tmax 0.5 "$T/parts.h5" -o "$T/far"
check "nothing written for it" [ ! -e "$T/far" ]
