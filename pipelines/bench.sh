#!/usr/bin/env bash
# pipelines/bench.sh - throughput benchmark of vres-run (make bench). Not a test: it prints
# tables and asserts nothing. Each run generates its case once, runs a fixed number of steps
# (about STEPS, to the end time --tmax that the start's time step gives) with one snapshot at
# the end, and reads the solver's own figures from run.tsv, by column name: particle-steps
# per second (particles x steps / wall seconds of stepping, snapshot writing excluded) and
# interactions per second (ordered neighbour pairs within 2h x force evaluations per second:
# two per Symplectic step). Each 2D figure is the median of REPEATS runs, because a shared
# machine makes single runs scatter; the 3D row is one run of STEPS3D steps.
# Peer figure (DESIGN section 8): DualSPHysics 5.4 on the CPU, 2D dam break dp 0.01 m
# (21,001 particles, 2 threads): 0.98 us per Symplectic particle-step.
#
# Table 1: the 2D dam break (cases/dsph_dambreak2d) at about 20k and 200k particles, 1 and 2
#   threads, Symplectic.
# Table 2: the 3D dam break (cases/bench_dambreak3d) at about 1M particles, 2 threads, when
#   the machine has MEM3D_GIB GiB available (BENCH3D=0 leaves it out).
# Table 3: the specialised interaction loop vres-run picks for a scene (only the modules the
#   scene uses compiled in) against the general loop (every option tested at run time,
#   VRES_LOOP=general, see vres-run(1)) on the same scene and threads: the dam break (DBC
#   walls, Fourtakas diffusion, artificial viscosity) and the Taylor-Green vortex (no walls,
#   no diffusion, laminar viscosity, periodic).
# Table 4: the two-domain dam break (cases/dambreak2d through vres-gencase --dp DPVRES |
#   vres-partition: root dp DPVRES, the box over the downstream wall at DPVRES/2), on the CPU
#   backend at 1 and 2 threads, continued (--restart) from its state at WARMVRES s, after the
#   front's impact, when water crosses the interface (that warm-up run is made once, at 2
#   threads, and kept), for about STEPSVRES steps: particles (every domain's fluid, buffer and
#   walls at the start of the measured run), steps, particle-steps per second (run.tsv), and
#   the coupling's share of the time loop with its parts (interpolation onto the buffers,
#   segment flux, classification and creation, sorts and compaction), read from vres-run's
#   last stderr line ("coupling of the N domains: ..."); for reference, the same case in
#   single resolution (vres-partition --single) at the box's dp, from its own state at
#   WARMVRES s.
# Table 5 (phases): where the time loop goes (vres-run --profile, RUNDIR/phases.tsv, named
#   profile.tsv by vres-run before 2026-12-02, read when there is no phases.tsv): the
#   percent of the loop in each phase (sort, forces, integrate, walls, mdbc, check, coupling,
#   output, other) and the microseconds per step, for the 2D dam break (dp 0.01, from t = 0)
#   and the two-domain dam break of table 4 (from its warm state at WARMVRES s), about
#   STEPSPHASE steps each, one run each at PHASE_THREADS threads. Each run writes two snapshots
#   (its start and its end), which is the output share: it shrinks as STEPSPHASE grows.
# Table 6 (scaling): cost per particle-step (microseconds) against the particle count,
#   STEPSSCALE steps at every size from t = 0 (SCALE_REPEATS rounds over the sizes in turn, the
#   median per size; SCALE_THREADS threads). The same steps, not the same particle-steps: the
#   time step scales with dp, so after the same steps the particles have moved the same distance
#   in particle spacings and every size is measured in the same state of its lattice. (Until
#   2026-12-06 the table gave each size 2e7 particle-steps, so the 15,625-particle cube ran
#   1,670 steps, far into its flow, against 21 for the million; the per-pair cost of the forces
#   grows as the lattice's order is lost, by 15-45% on this VM, which made the small sets look
#   slower for a reason that is not their size.)
#   of the 2D dam break (cases/dsph_dambreak2d) at the dp values SCALE2D_DPS and of the 3D
#   one (cases/bench_dambreak3d) at SCALE3D_DPS: by default about 2e4, 1e5, 5e5 and 1e6
#   particles in 2D, 1.7e4, 1.1e5, 3.6e5 and 1e6 in 3D; and of a triply periodic cube of fluid
#   (cases/bench_tgv3d, the 3-D Taylor-Green vortex set by pipelines/tgv_init.py, which needs
#   python3 with h5py and numpy; left out with a note without them) at SCALETGV_DPS, 15,625,
#   125,000, 512,000 and 1e6 particles: there every particle has a whole kernel support at
#   every size, where the dam break's coarse sets have more truncated supports (fewer pairs per
#   particle), so its rows show what the size alone costs. Its cost, measured (2 threads, this VM,
#   2026-12-06, the defaults): 3.5 min in 2D, 8.5 min for the 3D dam break and 10 min for the
#   cube, 22 min in all, each run's start and two snapshots included, plus vres-gencase's
#   drawing of each store once (kept in OUTDIR and reused).
#   Smaller sets: SCALE2D_DPS, SCALE3D_DPS, SCALETGV_DPS, STEPSSCALE, SCALE_REPEATS, SCALE_CASES
#   (of "dambreak2d dambreak3d tgv3d", all by default). SCALE_ALGOS ("symplectic
#   verlet") gives a row set per time integrator (Verlet's rows named -verlet; about half the cost).
#
#   bash pipelines/bench.sh [OUTDIR]      (default build/bench; the stores are kept there and
#                                          reused, the run directories are replaced)
# Environment: STEPS (60), REPEATS (3), STEPS3D (4), BENCH3D (1), MEM3D_GIB (1: the 3D run
# holds about 0.3 GB), DPVRES (0.01), WARMVRES (0.5), STEPSVRES (1000), BENCH_TABLES (the
# tables to make, of "2d 3d loop vres"; default all) and VRES_BIN (the tools' directory,
# default bin/), STEPSPHASE (200), PHASE_THREADS (2, or 1 on one core), STEPSSCALE (40),
# SCALE_REPEATS (3),
# SCALE_THREADS (likewise), SCALE2D_DPS ("0.01 0.0045 0.002 0.0014"), SCALE3D_DPS ("0.02 0.01
# 0.0065 0.0045"), SCALETGV_DPS ("0.04 0.02 0.0125 0.01"), ROOF_THREADS (likewise). BENCH_TABLES names also "phases", "scaling" and "roofline". The coupled runs set
# OMP_WAIT_POLICY=passive unless it is set: on a busy machine spinning threads only steal time.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/bench}
mkdir -p "$out"
BIN=${VRES_BIN:-bin}
STEPS=${STEPS:-60}
REPEATS=${REPEATS:-3}
STEPS3D=${STEPS3D:-4}
BENCH3D=${BENCH3D:-1}
MEM3D_GIB=${MEM3D_GIB:-1}
DPVRES=${DPVRES:-0.01}
WARMVRES=${WARMVRES:-0.5}
STEPSVRES=${STEPSVRES:-1000}
BENCH_TABLES=${BENCH_TABLES:-2d 3d loop vres phases scaling roofline}
TH2=$(($(nproc) < 2 ? 1 : 2))
STEPSPHASE=${STEPSPHASE:-200}
PHASE_THREADS=${PHASE_THREADS:-$TH2}
STEPSSCALE=${STEPSSCALE:-40}
SCALE_REPEATS=${SCALE_REPEATS:-3}
SCALE_ALGOS=${SCALE_ALGOS:-symplectic verlet}
SCALE_THREADS=${SCALE_THREADS:-$TH2}
SCALE2D_DPS=${SCALE2D_DPS:-0.01 0.0045 0.002 0.0014}
SCALE3D_DPS=${SCALE3D_DPS:-0.02 0.01 0.0065 0.0045}
SCALETGV_DPS=${SCALETGV_DPS:-0.04 0.02 0.0125 0.01}
SCALE_CASES=${SCALE_CASES:-dambreak2d dambreak3d tgv3d}
DB=cases/dsph_dambreak2d/dambreak2d_Def.xml
DB3=cases/bench_dambreak3d/bench_dambreak3d_Def.xml
TG=cases/taylor_green2d/taylor_green2d_Def.xml
DBV=cases/dambreak2d/dambreak2d_Def.xml
TGV3=cases/bench_tgv3d/bench_tgv3d_Def.xml

# want TABLE: true when BENCH_TABLES names TABLE
want() { case " $BENCH_TABLES " in *" $1 "*) return 0 ;; esac; return 1; }

# gen NAME XML [vres-gencase options...]: the store $out/NAME.h5, made again only when the
# XML is newer or the options differ from those it was made with ($out/NAME.args)
gen() {
    local name=$1 xml=$2
    shift 2
    local args="$xml $*"
    if [ ! -f "$out/$name.h5" ] || [ "$xml" -nt "$out/$name.h5" ] ||
        [ "$(cat "$out/$name.args" 2>/dev/null)" != "$args" ]; then
        "$BIN/vres-gencase" -q "$@" "$xml" -o "$out/$name.h5"
        printf '%s\n' "$args" >"$out/$name.args"
    fi
}

# tgv_python: the python3 that has h5py and numpy (printed), or a non-zero status
tgv_python() {
    local py
    for py in python3 /usr/bin/python3; do
        "$py" -c 'import h5py, numpy' 2>/dev/null && { echo "$py"; return 0; }
    done
    return 1
}

# tgv_set STORE: the 3-D Taylor-Green vortex set in STORE (pipelines/tgv_init.py), once: again
# only when vres-gencase has drawn the store anew (STORE.tgv, its mark, is then older)
tgv_set() {
    [ "$1.tgv" -nt "$1" ] && return 0
    "$(tgv_python)" pipelines/tgv_init.py "$1" 2>"$1.tgvlog" || { cat "$1.tgvlog" >&2; exit 1; }
    touch "$1.tgv"
}

# particles STORE: its particle count
particles() { "$BIN/vres-info" -t "$1" | awk '!/^#/ {n += $4} END {print n}'; }

# param STORE NAME: a resolved parameter of the store (vres-info's parameter lines)
param() { "$BIN/vres-info" "$1" | awk -v k="$2" '$1 == k {print $2; exit}'; }

# tmax_for STORE NSTEPS: the end time of about NSTEPS steps, from the start's time step
# dt = CFL h / c0 (the sound-speed bound, which decides dt while the fluid is slow)
tmax_for() {
    awk -v s="$2" -v cfl="$(param "$1" cflnumber)" -v h="$(param "$1" h)" -v c="$(param "$1" cs0)" \
        'BEGIN {printf "%.6g", s * cfl * h / c}'
}

# figures RUNDIR: "steps particle_steps_per_s interactions_per_s pairs" from the last line of
# RUNDIR/run.tsv, columns found by their header names ("-" for a column run.tsv lacks)
figures() {
    awk -F'\t' 'NR == 1 {sub(/^# */, ""); for (i = 1; i <= NF; i++) col[$i] = i; next}
                !/^#/ {for (i = 1; i <= NF; i++) v[i] = $i}
                function get(name) {return (name in col) ? v[col[name]] : "-"}
                END {print get("step"), get("particle_steps_per_s"), get("interactions_per_s"), get("pairs")}' \
        "$1/run.tsv"
}

# rate NAME TMAX THREADS LOOP RUNS: figures (see above) of the median of RUNS runs of store
# NAME to TMAX, by particle-steps per second
rate() {
    local name=$1 tmax=$2 th=$3 loop=$4 runs=$5 rd
    for r in $(seq "$runs"); do
        rd=$out/run-$name-t$th-$loop-$r
        rm -rf "$rd"
        VRES_LOOP=$loop OMP_NUM_THREADS=$th "$BIN/vres-run" -q --threads "$th" --tmax "$tmax" --tout "$tmax" \
            "$out/$name.h5" -o "$rd"
        figures "$rd"
    done | sort -g -k2 | awk -v m="$(((runs + 1) / 2))" 'NR == m'
}

# row NAME DP N THREADS FIGURES...: one line of tables 1 and 2
row() {
    awk -v name="$1" -v dp="$2" -v n="$3" -v th="$4" -v steps="$5" -v ps="$6" -v is="$7" -v pairs="$8" 'BEGIN {
        printf "%s\t%s\t%d\t%d\t%d\t%.4g\t%.3f\t", name, dp, n, th, steps, ps, (ps > 0 ? 1e6 / ps : 0)
        if (is == "-" || pairs == "-") printf "-\t-\n"
        else printf "%.4g\t%.1f\n", is, pairs / n }'
}

header='case\tdp_m\tparticles\tthreads\tsteps\tparticle_steps_per_s\tus_per_particle_step\tinteractions_per_s\tpairs_per_particle\n'
printf '# vres-run throughput, Symplectic; host: %s, %s cores, %s\n' "$(uname -m)" "$(nproc)" \
    "$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)"
printf '# %s\n' "$("$BIN/vres-run" --version)"
printf '# peer: DualSPHysics 5.4 (CPU) on dambreak2d-20k at 2 threads: 0.98 us per particle-step\n'

if want 2d; then
printf '\n# 2D dam break (%s), about %s steps, median of %s runs\n' "$DB" "$STEPS" "$REPEATS"
printf "$header"
for spec in "dambreak2d-20k 0.01" "dambreak2d-200k 0.0032"; do
    set -- $spec
    name=$1 dp=$2
    gen "$name" "$DB" --dp "$dp"
    n=$(particles "$out/$name.h5")
    tmax=$(tmax_for "$out/$name.h5" "$STEPS")
    for th in 1 2; do
        f=$(rate "$name" "$tmax" "$th" specialised "$REPEATS")
        row "$name" "$dp" "$n" "$th" $f
    done
done
fi

if want 3d; then
printf '\n# 3D dam break (%s), about %s steps, one run\n' "$DB3" "$STEPS3D"
avail=$(awk '/^MemAvailable:/ {printf "%d", $2 / 1048576}' /proc/meminfo)
if [ "$BENCH3D" != 1 ]; then
    printf '# left out (BENCH3D=%s)\n' "$BENCH3D"
elif [ "$avail" -lt "$MEM3D_GIB" ]; then
    printf '# left out: %s GiB of memory available, the run needs about %s\n' "$avail" "$MEM3D_GIB"
else
    printf "$header"
    gen dambreak3d-1m "$DB3"
    n=$(particles "$out/dambreak3d-1m.h5")
    dp=$(param "$out/dambreak3d-1m.h5" dp)
    tmax=$(tmax_for "$out/dambreak3d-1m.h5" "$STEPS3D")
    th=$(($(nproc) < 2 ? 1 : 2))
    f=$(rate dambreak3d-1m "$tmax" "$th" specialised 1)
    row dambreak3d-1m "$dp" "$n" "$th" $f
fi
fi

if want loop; then
printf '\n# specialised loop (the scene'"'"'s modules only) against the general loop (VRES_LOOP=general)\n'
printf 'case\tparticles\tthreads\tloop\tparticle_steps_per_s\tus_per_particle_step\tspeedup\n'
gen dambreak2d-20k "$DB" --dp 0.01
gen tg2d "$TG" --dp 0.01
for name in dambreak2d-20k tg2d; do
    n=$(particles "$out/$name.h5")
    tmax=$(tmax_for "$out/$name.h5" "$STEPS")
    for th in 1 2; do
        g=$(rate "$name" "$tmax" "$th" general "$REPEATS" | awk '{print $2}')
        s=$(rate "$name" "$tmax" "$th" specialised "$REPEATS" | awk '{print $2}')
        awk -v name="$name" -v n="$n" -v th="$th" -v g="$g" -v s="$s" 'BEGIN {
            printf "%s\t%d\t%d\tgeneral\t%.4g\t%.3f\t\n", name, n, th, g, 1e6 / g
            printf "%s\t%d\t%d\tspecialised\t%.4g\t%.3f\t%.2f\n", name, n, th, s, 1e6 / s, s / g }'
    done
done
fi

# genpart NAME XML DP [vres-partition options...]: the partition $out/NAME.h5 of XML drawn at
# root dp DP (vres-gencase | vres-partition), made again as gen does
genpart() {
    local name=$1 xml=$2 dp=$3
    shift 3
    local args="$xml --dp $dp | $*"
    if [ ! -f "$out/$name.h5" ] || [ "$xml" -nt "$out/$name.h5" ] ||
        [ "$(cat "$out/$name.args" 2>/dev/null)" != "$args" ]; then
        "$BIN/vres-gencase" -q --dp "$dp" "$xml" | "$BIN/vres-partition" -q "$@" - -o "$out/$name.h5"
        printf '%s\n' "$args" >"$out/$name.args"
    fi
}

# col RUNDIR NAME: column NAME of the last line of RUNDIR/run.tsv
col() {
    awk -F'\t' -v k="$2" 'NR == 1 {sub(/^# */, ""); for (i = 1; i <= NF; i++) c[$i] = i; next}
                          !/^#/ {v = $(c[k])} END {print v}' "$1/run.tsv"
}

# warm NAME T: $out/warm-NAME, store NAME run to T (one snapshot there, snap_00001.h5), made
# again when the store is newer or T differs
warm() {
    local name=$1 t=$2 wd=$out/warm-$1 th
    th=$(($(nproc) < 2 ? 1 : 2))
    if [ ! -f "$wd/snap_00001.h5" ] || [ "$out/$name.h5" -nt "$wd/snap_00001.h5" ] ||
        [ "$(cat "$wd.args" 2>/dev/null)" != "$t" ]; then
        rm -rf "$wd"
        OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=$th "$BIN/vres-run" -q --device cpu --threads "$th" --tmax "$t" --tout "$t" \
            "$out/$name.h5" -o "$wd"
        printf '%s\n' "$t" >"$wd.args"
    fi
}

# couple_parts ERRFILE: "total interp flux create compact" (percent of the time loop) from
# vres-run's "coupling of the N domains" line in ERRFILE ("- - - - -" without one)
couple_parts() {
    awk '/coupling of the [0-9]+ domains:/ {
            t = $0; sub(/% of the time loop.*/, "", t); sub(/.* /, "", t)
            n = split("interpolation|flux|classification and creation|sorts and compaction", k, "|")
            r = t
            for (i = 1; i <= n; i++) {
                v = $0; if (!sub(".*[(,] ?" k[i] " ", "", v)) v = "-"; sub(/%.*/, "", v); r = r " " v
            }
            line = r
         }
         END {print (line == "" ? "- - - - -" : line)}' "$1"
}

# rate_restart NAME THREADS NSTEPS RUNS: "steps particle_steps_per_s total interp flux create
# compact" of the median of RUNS runs (by particle-steps per second) continuing
# $out/warm-NAME's snapshot for about NSTEPS steps (its last time step's worth each)
rate_restart() {
    local name=$1 th=$2 nsteps=$3 runs=$4 wd=$out/warm-$1 t0 s0 tmax rd
    t0=$(col "$wd" time_s)
    s0=$(col "$wd" step)
    tmax=$(awk -v t="$t0" -v n="$nsteps" -v dt="$(col "$wd" dt_s)" 'BEGIN {printf "%.9g", t + n * dt}')
    for r in $(seq "$runs"); do
        rd=$out/run-$name-t$th-$r
        rm -rf "$rd"
        mkdir -p "$rd"
        OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=$th "$BIN/vres-run" --device cpu \
            --threads "$th" --tmax "$tmax" --tout "$(awk -v a="$tmax" -v b="$t0" 'BEGIN {print a - b}')" \
            --restart "$wd/snap_00001.h5" -o "$rd" 2>"$rd.err"
        echo "$(($(col "$rd" step) - s0)) $(col "$rd" particle_steps_per_s) $(couple_parts "$rd.err")"
    done | sort -g -k2 | awk -v m="$(((runs + 1) / 2))" 'NR == m'
}

if want vres; then
    fine=$(awk -v d="$DPVRES" 'BEGIN {print d / 2}')
    printf '\n# two-domain dam break (%s, vres-partition; box dpratio 2) against single resolution at the box'"'"'s dp,\n' "$DBV"
    printf '# CPU backend, from the state at %s s, about %s steps, median of %s runs; coupling_pct and its parts:\n' \
        "$WARMVRES" "$STEPSVRES" "$REPEATS"
    printf '# percent of the time loop (vres-run'"'"'s "coupling of the N domains" line)\n'
    printf 'case\tdp_m\tparticles\tthreads\tsteps\tparticle_steps_per_s\tus_per_particle_step\tcoupling_pct\tinterpolation_pct\tflux_pct\tcreation_pct\tcompaction_pct\n'
    genpart dambreak2d-vres "$DBV" "$DPVRES"
    genpart dambreak2d-fine "$DBV" "$fine" --single
    for spec in "dambreak2d-vres $DPVRES/$fine" "dambreak2d-fine $fine"; do
        set -- $spec
        name=$1 dp=$2
        warm "$name" "$WARMVRES"
        n=$(particles "$out/warm-$name/snap_00001.h5")
        for th in 1 2; do
            f=$(rate_restart "$name" "$th" "$STEPSVRES" "$REPEATS")
            awk -v name="$name" -v dp="$dp" -v n="$n" -v th="$th" -v f="$f" 'BEGIN {
                split(f, v, " ")
                printf "%s\t%s\t%d\t%d\t%d\t%.4g\t%.3f\t%s\t%s\t%s\t%s\t%s\n", name, dp, n, th, v[1], v[2],
                    (v[2] > 0 ? 1e6 / v[2] : 0), v[3], v[4], v[5], v[6], v[7] }'
        done
    done
fi

# PHASES: the phase columns of table 5, in phases.tsv's order
PHASES="sort forces integrate walls mdbc check coupling output other"

# phase_row NAME PARTICLES THREADS STEPS RUNDIR: one line of table 5 from RUNDIR/phases.tsv (or
# an older vres-run's profile.tsv): percent of the loop per phase, by the phases' names ("-" for
# one the table lacks)
phase_row() {
    local tsv=$5/phases.tsv
    [ -f "$tsv" ] || tsv=$5/profile.tsv
    awk -F'\t' -v name="$1" -v n="$2" -v th="$3" -v steps="$4" -v phases="$PHASES" '
        !/^#/ {pct[$1] = $3; us[$1] = $4}
        END {
            if (!("total" in us)) {print "bench.sh: no total in " FILENAME > "/dev/stderr"; exit 1}
            printf "%s\t%d\t%d\t%d", name, n, th, steps
            k = split(phases, ph, " ")
            for (i = 1; i <= k; i++) printf "\t%s", (ph[i] in pct) ? pct[ph[i]] : "-"
            printf "\t%s\n", us["total"] }' "$tsv"
}

if want phases; then
    printf '\n# where the time loop goes (vres-run --profile): percent of the loop per phase, %s threads;\n' \
        "$PHASE_THREADS"
    printf '# about %s steps: dambreak2d-20k from t = 0, dambreak2d-vres (table 4'"'"'s two domains) from its state at %s s\n' \
        "$STEPSPHASE" "$WARMVRES"
    printf 'case\tparticles\tthreads\tsteps'
    for p in $PHASES; do printf '\t%s_pct' "$p"; done
    printf '\tus_per_step\n'
    gen dambreak2d-20k "$DB" --dp 0.01
    rd=$out/phase-dambreak2d-20k
    rm -rf "$rd"
    tmax=$(tmax_for "$out/dambreak2d-20k.h5" "$STEPSPHASE")
    OMP_NUM_THREADS=$PHASE_THREADS "$BIN/vres-run" -q --profile --threads "$PHASE_THREADS" --tmax "$tmax" \
        --tout "$tmax" "$out/dambreak2d-20k.h5" -o "$rd" 2>/dev/null
    phase_row dambreak2d-20k "$(particles "$out/dambreak2d-20k.h5")" "$PHASE_THREADS" "$(col "$rd" step)" "$rd"
    genpart dambreak2d-vres "$DBV" "$DPVRES"
    warm dambreak2d-vres "$WARMVRES"
    wd=$out/warm-dambreak2d-vres
    rd=$out/phase-dambreak2d-vres
    rm -rf "$rd"
    t0=$(col "$wd" time_s)
    tmax=$(awk -v t="$t0" -v n="$STEPSPHASE" -v dt="$(col "$wd" dt_s)" 'BEGIN {printf "%.9g", t + n * dt}')
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=$PHASE_THREADS "$BIN/vres-run" -q --profile \
        --device cpu --threads "$PHASE_THREADS" --tmax "$tmax" \
        --tout "$(awk -v a="$tmax" -v b="$t0" 'BEGIN {print a - b}')" --restart "$wd/snap_00001.h5" -o "$rd" 2>/dev/null
    phase_row dambreak2d-vres "$(particles "$wd/snap_00001.h5")" "$PHASE_THREADS" \
        "$(($(col "$rd" step) - $(col "$wd" step)))" "$rd"
fi

if want scaling; then
    printf '\n# cost per particle-step against size (from t = 0, about %s steps at every size: the same distance\n' \
        "$STEPSSCALE"
    printf '# moved in particle spacings, %s rounds over the sizes in turn, the median per size; %s threads):\n# the 2D dam break (%s),\n' \
        "$SCALE_REPEATS" "$SCALE_THREADS" "$DB"
    printf '# the 3D one (%s) and the periodic cube (%s, tgv3d: every particle with a whole support) at\n' "$DB3" "$TGV3"
    printf '# several dp; us_per_particle_step leaves out the two snapshots\n'
    printf "$header"
    for spec in "dambreak2d $DB $SCALE2D_DPS" "dambreak3d $DB3 $SCALE3D_DPS" "tgv3d $TGV3 $SCALETGV_DPS"; do
      set -- $spec
      cname=$1
      case " $SCALE_CASES " in *" $cname "*) ;; *) continue ;; esac
      if [ "$cname" = tgv3d ] && ! tgv_python >/dev/null; then
          printf '# tgv3d left out: no python3 with h5py and numpy to set its vortex (setup.sh installs them)\n'
          continue
      fi
      for algo in $SCALE_ALGOS; do
        set -- $spec
        xml=$2
        shift 2
        # Symplectic as the cases say; Verlet through --set (the name's suffix)
        sfx=; [ "$algo" = verlet ] && sfx=-verlet
        for dp in "$@"; do
            if [ -n "$sfx" ]; then gen "scale-$cname-$dp$sfx" "$xml" --dp "$dp" --set StepAlgorithm=1
            else gen "scale-$cname-$dp" "$xml" --dp "$dp"; fi
            if [ "$cname" = tgv3d ]; then tgv_set "$out/scale-$cname-$dp$sfx.h5"; fi
        done
        # rounds: every size once per round, so that the sizes share the machine's slow minutes
        for r in $(seq "$SCALE_REPEATS"); do
            for dp in "$@"; do
                name=scale-$cname-$dp$sfx
                n=$(particles "$out/$name.h5")
                steps=$STEPSSCALE
                rd=$out/run-$name-t$SCALE_THREADS-r$r
                rm -rf "$rd"
                OMP_NUM_THREADS=$SCALE_THREADS "$BIN/vres-run" -q --threads "$SCALE_THREADS" \
                    --tmax "$(tmax_for "$out/$name.h5" "$steps")" --tout "$(tmax_for "$out/$name.h5" "$steps")" \
                    "$out/$name.h5" -o "$rd"
                echo "$dp $n $(figures "$rd")" >>"$out/scale-$cname.runs"
            done
        done
        for dp in "$@"; do
            f=$(awk -v d="$dp" '$1 == d {print $3, $4, $5, $6}' "$out/scale-$cname.runs" | sort -g -k2 |
                awk -v m="$(((SCALE_REPEATS + 1) / 2))" 'NR == m')
            row "$cname$sfx" "$dp" "$(particles "$out/scale-$cname-$dp$sfx.h5")" "$SCALE_THREADS" $f
        done
        rm -f "$out/scale-$cname.runs"
      done
    done
fi

# Table 7 (roofline): the machine's roofs, measured by pipelines/roofline.c (double- and
#   single-precision FMA peaks and a STREAM-style triad's bandwidth, 1 and ROOF_THREADS threads;
#   compiled here with cc -O2 -mavx2 -mfma -fopenmp, skipped where that fails), and where the
#   interaction stands under them: for the 2D dam break at dp 0.01 (21k particles) and the 3D
#   one at dp 0.02 (17k), one run of about STEPS steps at ROOF_THREADS threads, its
#   interactions per second (pairs within 2h) times the flops of one pair, counted from
#   kernels/sph.h's pair terms for these scenes (fluid-fluid pair, Wendland, artificial
#   viscosity, Fourtakas diffusion): 3D 78 (distance 8 in double for the support test; then in
#   single precision: sqrt 1, kernel 6, grad W 3, relative velocity 3, 1/(r^2+eta^2) 2,
#   continuity 7, 1/rho_b 1, pressure coefficient 4, viscous coefficient with its dot product
#   12, largest rate 1, the pair's acceleration 7 (prs + Pi, three products, three sums),
#   diffusion 23 with Fourtakas' series) and 2D 67 (the y terms left out, but for g.x_ab's); the divisions and
#   the sqrt count one flop each though they take several FMA slots, and the pairs beyond 2h
#   that the cells offer and the test rejects count nothing, so the percentage understates the
#   loop's use of the machine. The percentage is of the single-precision peak, the precision of
#   all but the distance (before 2026-12-05 the pair terms were doubles, 86 and 72 flops, and
#   the percentage was of the double peak). The memory column: the state each force
#   evaluation must at least read and write, 2 x 218 B per particle (the bytes vres-run holds
#   per particle, pipelines/reports/memory.txt), two evaluations per Symplectic step, as GB/s at
#   the measured particle-steps per second, against the triad's bandwidth.
ROOF_THREADS=${ROOF_THREADS:-$TH2}
if want roofline; then
    if ${CC:-cc} -O2 -mavx2 -mfma -fopenmp pipelines/roofline.c -o "$out/roofline" 2>/dev/null; then
        printf '\n# roofline: the machine (pipelines/roofline.c: best of 5; FMA chains of AVX2 doubles and floats; triad of 3 x 256 MiB)\n'
        printf 'threads\tpeak_gflops\tpeak_sp_gflops\ttriad_gbs\n'
        OMP_NUM_THREADS=$ROOF_THREADS "$out/roofline" "$ROOF_THREADS" | tee "$out/roofs.tsv"
        peak=$(awk -v t="$ROOF_THREADS" '$1 == t {print $3}' "$out/roofs.tsv")
        bw=$(awk -v t="$ROOF_THREADS" '$1 == t {print $4}' "$out/roofs.tsv")
        printf '\n# roofline: the interaction under those roofs, %s threads, about %s steps, one run each\n' "$ROOF_THREADS" "$STEPS"
        printf 'case\tparticles\tinteractions_per_s\tflops_per_pair\tgflops\tpct_of_sp_peak\tstate_gbs\tpct_of_triad\n'
        gen dambreak2d-20k "$DB" --dp 0.01
        gen scale3-0.02 "$DB3" --dp 0.02
        for c in "dambreak2d-20k 67" "scale3-0.02 78"; do
            set -- $c
            rd=$out/run-roof-$1
            rm -rf "$rd"
            OMP_NUM_THREADS=$ROOF_THREADS "$BIN/vres-run" -q --threads "$ROOF_THREADS" --tmax "$(tmax_for "$out/$1.h5" "$STEPS")" \
                --tout "$(tmax_for "$out/$1.h5" "$STEPS")" "$out/$1.h5" -o "$rd"
            read -r _ ps is _ <<<"$(figures "$rd")"
            awk -v name="$1" -v n="$(particles "$out/$1.h5")" -v is="$is" -v f="$2" -v ps="$ps" -v pk="$peak" -v bw="$bw" 'BEGIN {
                g = is * f / 1e9; s = ps * 2 * 2 * 218 / 1e9
                printf "%s\t%d\t%.4g\t%d\t%.2f\t%.0f\t%.2f\t%.0f\n", name, n, is, f, g, 100 * g / pk, s, 100 * s / bw }'
        done
    else
        printf '\n# roofline: pipelines/roofline.c does not compile here (cc -mavx2 -mfma -fopenmp): skipped\n'
    fi
fi
