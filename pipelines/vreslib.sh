# pipelines/vreslib.sh - shell functions shared by the validation checks (cases/*/check),
# the stability checks and the sweep pipeline. Sourced, never run.
#
# Stores are read with h5dump and awk, not with vres code, so that a check does not inherit
# a bug of the tools it checks. Every function prints to stdout and reports problems on
# stderr as "NAME: ..." where NAME is the calling script's name ($VRES_ME).
#
# The check protocol (what cases/*/check print, what pipelines/sweep.mk reads): one
# "key<TAB>value" line per result, among them
#   case, reference, dp_m, particles, steps, t_end_s, run_time_s, error, error_def,
#   tolerance, verdict (pass or FAIL)
# and exit status 0 (error within tolerance), 1 (error above it, or the run failed),
# 2 (usage error).

VRES_ROOT=${VRES_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
VRES_BIN=${VRES_BIN:-$VRES_ROOT/bin}
VRES_ME=${VRES_ME:-$(basename "$0")}

# need_h5py: make "python3" one with h5py and numpy (setup.sh installs Debian's): when the one
# first on PATH lacks them (a pyenv or conda python) and /usr/bin's has them, put /usr/bin first.
need_h5py() {
    python3 -c 'import h5py, numpy' 2>/dev/null && return 0
    /usr/bin/python3 -c 'import h5py, numpy' 2>/dev/null && export PATH=/usr/bin:$PATH
}

# die MSG...: print "NAME: MSG" on stderr and exit 1.
die() { echo "$VRES_ME: $*" >&2; exit 1; }

# note MSG...: print "NAME: MSG" on stderr (progress and explanations, not results).
note() { echo "$VRES_ME: $*" >&2; }

# report KEY VALUE: one result line of the check protocol.
report() { printf '%s\t%s\n' "$1" "$2"; }

# values DATASET FILE: the numbers of an HDF5 dataset, one per line in row-major order, to 15
# significant digits (h5dump's default %g keeps only 6).
values() {
    h5dump -y -w 1 -m '%.15g' -d "$1" "$2" |
        awk '/DATA \{/ {on = 1; next} on && /^ *[-0-9.eE+naif]+,?$/ {gsub(/[ ,]/, ""); print}'
}

# attr PATH FILE: a scalar numeric attribute (for example /time, /Domains/D0/dp); the first
# value of an array attribute.
attr() {
    h5dump -m '%.15g' -a "$1" "$2" | awk '/\(0\):/ {sub(/.*\(0\): */, ""); sub(/,.*/, ""); print; exit}'
}

# attrv PATH FILE: every value of a numeric attribute (an array such as gravity), one a line.
attrv() {
    h5dump -m '%.15g' -a "$1" "$2" |
        awk '/DATA \{/ {on = 1; next} on && /\}/ {exit}
             on {sub(/^ *(\([0-9,]+\): *)?/, ""); n = split($0, v, /, */); for (i = 1; i <= n; i++) if (v[i] != "") print v[i]}'
}

# param NAME FILE: a numeric parameter of /Parameters (the first value of an array).
param() { attr "/Parameters/$1" "$2"; }

# gravity_norm FILE: |g| (m/s^2) from the gravity parameter.
gravity_norm() { attrv /Parameters/gravity "$1" | awk '{s += $1 * $1} END {printf "%.15g\n", sqrt(s)}'; }

# particles FILE [K]: one line per particle of domain K (default 0, the root): type x y z vx vy
# vz rho p, the numbers of vres-store(5) (type 0 fluid, 1 buffer, 2 fixed wall, 3 moving wall...).
particles() {
    local f=$1 k=${2:-0}
    paste <(values /Domains/D$k/Type "$f") \
          <(values /Domains/D$k/Position "$f" | paste - - -) \
          <(values /Domains/D$k/Velocity "$f" | paste - - -) \
          <(values /Domains/D$k/Density "$f") \
          <(values /Domains/D$k/Pressure "$f")
}

# domains FILE: the number of domains of a store (1 for a single-resolution one).
domains() { h5ls "$1/Domains" 2>/dev/null | grep -c '^D[0-9]'; }

# particles_all FILE: the particles of every domain, as `particles` with the domain index
# appended as a tenth column. Fluid particles (type 0) of different domains never share a
# point: each domain's fluid lies in its own fluid region (buffers, type 1, are the copies).
particles_all() {
    local f=$1 k n
    n=$(domains "$f")
    for ((k = 0; k < n; k++)); do particles "$f" "$k" | awk -v k="$k" '{print $0 "\t" k}'; done
}

# domain_boxes FILE: one line per domain: k parent dp box_min_x y z box_max_x y z (the root's
# parent is -1; a root without box attributes gets none: it owns what no child holds).
domain_boxes() {
    local f=$1 k n p
    n=$(domains "$f")
    for ((k = 0; k < n; k++)); do
        p=$(attr /Domains/D$k/parent "$f"); [ -n "$p" ] || p=-1
        [ "$k" -eq 0 ] && p=-1
        printf '%s %s %s %s %s\n' "$k" "$p" "$(attr /Domains/D$k/dp "$f")" \
            "$(attrv /Domains/D$k/box_min "$f" | paste -s -d ' ')" "$(attrv /Domains/D$k/box_max "$f" | paste -s -d ' ')"
    done
}

# owned_fluid FILE: the fluid particles (type 0) of every domain that their own domain owns, each
# piece of fluid once: the lines of particles_all (type x y z vx vy vz rho p k) with the
# particle's mass appended (an eleventh column). The owner of a point is lib/owner.c's
# (vres_owns): from the root down, the finest child whose box (faces included; y ignored in 2-D)
# holds it, so a child owns its box and a parent's fluid inside it (overlappingh) is not counted.
owned_fluid() {
    local f=$1 k n dim
    n=$(domains "$f")
    dim=$(attr /dim "$f"); [ -n "$dim" ] || dim=3
    for ((k = 0; k < n; k++)); do
        paste <(particles "$f" "$k") <(values /Domains/D$k/Mass "$f") | awk -v k="$k" '$1 == 0 {print $1, $2, $3, $4, $5, $6, $7, $8, $9, k, $10}'
    done | awk -v dim="$dim" -v boxes="$(domain_boxes "$f")" '
        BEGIN { nd = split(boxes, line, "\n")
                for (i = 1; i <= nd; i++) { split(line[i], v, " "); k = v[1]; par[k] = v[2]; dp[k] = v[3]
                    for (a = 0; a < 3; a++) { lo[k, a] = v[4 + a]; hi[k, a] = v[7 + a] } } }
        # 1 when point (x, y, z) lies in the box of domain k (faces included; a flat box holds nothing)
        function inbox(k, x, y, z,   a, c) {
            for (a = 0; a < 3; a++) { if (a == 1 && dim == 2) continue
                c = (a == 0 ? x : a == 1 ? y : z)
                if (!(hi[k, a] > lo[k, a]) || c < lo[k, a] || c > hi[k, a]) return 0 }
            return 1 }
        # the domain that owns point (x, y, z): lib/owner.c vres_owner
        function owner(x, y, z,   cur, best, d, k) {
            cur = 0
            for (d = 0; d < nd; d++) { best = cur
                for (k = 1; k < nd; k++) if (k != cur && par[k] == cur && inbox(k, x, y, z) && (best == cur || dp[k] < dp[best])) best = k
                if (best == cur) break
                cur = best }
            return cur }
        owner($2, $3, $4) == $10 { print }'
}

# snapshots RUNDIR: the numbered snapshots of a run in time order (not snap_last_good.h5).
snapshots() { ls "$1"/snap_[0-9]*.h5 2>/dev/null | sort; }

# tsv_last RUNDIR COLUMN: the value of a run.tsv column (by header name) on its last line.
tsv_last() {
    awk -F'\t' -v c="$2" 'NR == 1 {sub(/^# */, ""); for (i = 1; i <= NF; i++) if ($i == c) k = i; next}
                          !/^#/ {v = $k} END {if (!k) exit 1; print v}' "$1/run.tsv"
}

# run_summary RUNDIR: the cost lines of the check protocol from run.tsv: particles (fluid +
# wall at the last line, and with several domains the buffers of ledger.tsv's last output:
# they cost like the rest), steps, t_end_s and run_time_s (wall-clock seconds of vres-run's
# time loop, snapshot writing included, as run.tsv's wall_s).
run_summary() {
    local d=$1 nb=0
    [ -f "$d/run.tsv" ] || die "$d: no run.tsv (not a vres-run directory)"
    [ -f "$d/ledger.tsv" ] &&
        nb=$(awk -F'\t' '!/^#/ {if ($2 != s) n = 0; s = $2; n += $6} END {print n + 0}' "$d/ledger.tsv")
    report particles "$(( $(tsv_last "$d" n_fluid) + $(tsv_last "$d" n_wall) + nb ))"
    report steps "$(tsv_last "$d" step)"
    report t_end_s "$(tsv_last "$d" time_s)"
    report run_time_s "$(tsv_last "$d" wall_s)"
}

# run_complete RUNDIR: true when the run reached its TimeMax (the last snapshot's time is
# within one time step of the TimeMax it records); otherwise says so on stderr. A run that was
# stopped (killed, exit 3) must not be judged as if it had finished.
run_complete() {
    local last tmax t dt
    last=$(snapshots "$1" | tail -1)
    [ -n "$last" ] || { note "$1: no snapshots"; return 1; }
    tmax=$(param TimeMax "$last") && t=$(attr /time "$last") || { note "$last: no TimeMax or time"; return 1; }
    dt=$(tsv_last "$1" dt_s)
    awk -v t="$t" -v m="$tmax" -v dt="$dt" 'BEGIN {exit !(t >= m - dt - 1e-12 * m)}' ||
        { note "$1: the run stopped at t = $t s, before its TimeMax $tmax s"; return 1; }
}

# check_usage TEXT: print the usage of a check and exit 2.
check_usage() { printf 'usage: %s\n' "$1" >&2; exit 2; }

# check_args SYNOPSIS "$@": parse the options common to every check:
#   [--dp DP] [--threads N] [--tmax T] [--set NAME=VALUE]... [--vres | --single] [-o RUNDIR] [RUNDIR]
# Sets DP, THREADS, TMAX, PART (vres or single: run_case puts the store through vres-partition,
# with --single dropping the refinement boxes), SETS (the --set options, passed on to vres-gencase: a variable,
# constant or parameter of the case, e.g. --set Boundary=2), RUNDIR (a run directory to
# read, or where to run), RUN_NEEDED
# (1 when RUNDIR holds no run.tsv yet, so the check must run the case) and WORK (a temporary
# directory for intermediate files, removed at exit). Without a RUNDIR the run goes to WORK.
check_args() {
    local syn=$1 given=0; shift
    DP="" THREADS="" TMAX="" RUNDIR="" RUN_NEEDED=0 SETS=() PART=""
    while [ $# -gt 0 ]; do
        case $1 in
            --set) [ $# -ge 2 ] || check_usage "$syn"; SETS+=(--set "$2"); shift 2 ;;
            --dp) [ $# -ge 2 ] || check_usage "$syn"; DP=$2; shift 2 ;;
            --threads) [ $# -ge 2 ] || check_usage "$syn"; THREADS=$2; shift 2 ;;
            --tmax) [ $# -ge 2 ] || check_usage "$syn"; TMAX=$2; shift 2 ;;
            --single) PART=single; shift ;;
            --vres) PART=vres; shift ;;
            -o) [ -z "$RUNDIR" ] && [ $# -ge 2 ] || check_usage "$syn"; RUNDIR=$2; shift 2 ;;
            -h|--help) printf 'usage: %s\n' "$syn"; exit 0 ;;
            -*) note "unknown option $1"; check_usage "$syn" ;;
            *) [ -z "$RUNDIR" ] || check_usage "$syn"; RUNDIR=$1; given=1; shift ;;
        esac
    done
    # a run directory given to be read must hold a run; -o names one to make
    if [ "$given" = 1 ] && [ ! -f "$RUNDIR/run.tsv" ]; then
        die "$RUNDIR: no run.tsv, not a vres-run directory (-o RUNDIR runs the case there)"
    fi
    WORK=$(mktemp -d "${TMPDIR:-/tmp}/vres-check.XXXXXX") || die "cannot make a temporary directory"
    trap 'rm -rf "$WORK"' EXIT
    [ -n "$RUNDIR" ] || RUNDIR=$WORK/run
    [ -f "$RUNDIR/run.tsv" ] || RUN_NEEDED=1
    if [ "$RUN_NEEDED" = 0 ] && [ -n "$DP$TMAX${SETS[*]}" ]; then
        note "$RUNDIR already holds a run: --dp, --tmax and --set are ignored"
    fi
}

# RUN_EXTRA: the extra vres-run options of VRES_RUN_ARGS in the environment (split at spaces;
# e.g. VRES_RUN_ARGS='--vres-order 1', for a sweep of the coupling's options), which run_case and
# every check that runs vres-run itself pass on.
RUN_EXTRA=()
read -r -a RUN_EXTRA <<<"${VRES_RUN_ARGS:-}"

# run_case XML [GENCASE OPTION]...: generate the case at $DP (the case's own dp when empty),
# with the --set options of $SETS,
# and run it into $RUNDIR with $THREADS threads (OpenMP's choice when empty) to $TMAX (the
# case's TimeMax when empty), with the extra vres-run options of VRES_RUN_ARGS in the environment
# (split at spaces; e.g. VRES_RUN_ARGS='--vres-order 1', for a sweep of the coupling's options).
# Sets RUN_STATUS to vres-run's exit status; keeps its stderr in
# $WORK/run.log (shown when the run fails) and, when the run directory was made, its stderr
# and exit status there too as vres-run.log and vres-run.status, so that a later check of the
# directory alone (a stability check reading the diagnosis) finds them.
run_case() {
    local xml=$1; shift
    "$VRES_BIN/vres-gencase" -q ${DP:+--dp "$DP"} "${SETS[@]}" "$@" "$xml" -o "$WORK/case.h5" ||
        die "vres-gencase failed on $xml"
    # --vres: the case's refinement boxes as domains; --single: the boxes dropped (one domain)
    if [ -n "$PART" ]; then
        "$VRES_BIN/vres-partition" -q $([ "$PART" = single ] && echo --single) "$WORK/case.h5" -o "$WORK/parts.h5" ||
            die "vres-partition failed on $xml"
        mv "$WORK/parts.h5" "$WORK/case.h5"
    fi
    note "running $(basename "$xml") at dp ${DP:-as in the case} into $RUNDIR"
    "$VRES_BIN/vres-run" -q ${THREADS:+--threads "$THREADS"} ${TMAX:+--tmax "$TMAX"} "${RUN_EXTRA[@]}" \
        "$WORK/case.h5" -o "$RUNDIR" 2>"$WORK/run.log"
    RUN_STATUS=$?
    rm -f "$WORK/case.h5"
    if [ -d "$RUNDIR" ]; then
        cp "$WORK/run.log" "$RUNDIR/vres-run.log"
        echo "$RUN_STATUS" >"$RUNDIR/vres-run.status"
    fi
    [ "$RUN_STATUS" -eq 0 ] || sed "s|^|$VRES_ME: |" "$WORK/run.log" >&2
    return 0
}

# verdict ERROR TOLERANCE: report the tolerance and the verdict; exit 1 when ERROR is above
# TOLERANCE or is not a finite number, 0 otherwise.
verdict() {
    report tolerance "$2"
    # a number written out, never nan or inf: mawk takes "-nan" for a number that passes any
    # comparison, and an error over no samples comes out as nan (measured: poiseuille2d/check on
    # snapshots without fluid passed with "error -nan" before this test)
    if [[ $1 =~ ^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] &&
        awk -v e="$1" -v t="$2" 'BEGIN {exit !(e <= t && e >= -t)}'; then
        report verdict pass; exit 0
    fi
    [[ $1 =~ ^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] || note "the error '$1' is not a number: nothing was measured"
    report verdict FAIL; exit 1
}
