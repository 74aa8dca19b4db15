#!/usr/bin/env bash
# pipelines/bench.sh - throughput benchmark of vres-run (make bench). Not a test: it prints
# tables and asserts nothing. Each run generates its case once, runs a fixed number of steps
# (about STEPS) and reads the solver's own particle-steps per second from run.tsv (which
# excludes snapshot writing); each figure is the median of REPEATS runs, because a shared
# machine makes single runs scatter. Peer figure (DESIGN section 8): DualSPHysics 5.4 on the
# CPU, 2D dam break dp 0.01 (21,001 particles, 2 threads): 0.98 us per Symplectic
# particle-step.
#
# Table 1: the 2D dam break at about 20k and 200k particles, 1 and 2 threads.
# Table 2: the specialised interaction loop vres-run picks for a scene (only the modules the
#   scene uses compiled in) against the general loop (every option tested at run time,
#   VRES_LOOP=general, see vres-run(1)) on the same scene and threads: the dam break (DBC
#   walls, Fourtakas diffusion, artificial viscosity) and the Taylor-Green vortex (no walls,
#   no diffusion, laminar viscosity, periodic).
#   bash pipelines/bench.sh [OUTDIR]      (default build/bench)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/bench}
mkdir -p "$out"
STEPS=${STEPS:-60}
REPEATS=${REPEATS:-3}
DB=cases/dsph_dambreak2d/dambreak2d_Def.xml
TG=cases/taylor_green2d/taylor_green2d_Def.xml

# gen NAME XML [vres-gencase options...]: the store $out/NAME.h5 (made once)
gen() {
    local name=$1 xml=$2
    shift 2
    [ -f "$out/$name.h5" ] || bin/vres-gencase -q "$@" "$xml" -o "$out/$name.h5"
}

# particles STORE: its particle count
particles() { bin/vres-info -t "$1" | awk '!/^#/ {n += $4} END {print n}'; }

# rate NAME TMAX THREADS LOOP: "steps wall_s particle_steps_per_s" of the median of REPEATS
# runs of store NAME to TMAX (by particle-steps per second)
rate() {
    local name=$1 tmax=$2 th=$3 loop=$4 rd
    for r in $(seq "$REPEATS"); do
        rd=$out/run-$name-t$th-$loop-$r
        rm -rf "$rd"
        VRES_LOOP=$loop OMP_NUM_THREADS=$th bin/vres-run -q --threads "$th" --tmax "$tmax" --tout "$tmax" \
            "$out/$name.h5" -o "$rd"
        awk '!/^#/ {l = $0} END {split(l, f, "\t"); print f[2], f[10], f[11]}' "$rd/run.tsv"
    done | sort -g -k3 | awk -v m="$(((REPEATS + 1) / 2))" 'NR == m'
}

# tmax DP: the end time of about STEPS steps (dt ~ CFL h / c0, h = sqrt(2) dp, c0 88.37 m/s, CFL 0.2)
tmax_for() { awk -v dp="$1" -v s="$STEPS" 'BEGIN {printf "%.6g", s * 0.2 * 1.41421 * dp / 88.37}'; }

printf '# vres-run throughput, Symplectic, about %s steps, median of %s runs; host: %s, %s cores\n' \
    "$STEPS" "$REPEATS" "$(uname -m)" "$(nproc)"
printf '# %s\n' "$(bin/vres-run --version)"
printf '\n# 2D dam break (%s)\n' "$DB"
printf 'case\tdp_m\tparticles\tthreads\tsteps\twall_s\tparticle_steps_per_s\tus_per_particle_step\n'
for spec in "dambreak2d-20k 0.01" "dambreak2d-200k 0.00316"; do
    set -- $spec
    name=$1 dp=$2
    gen "$name" "$DB" --dp "$dp"
    n=$(particles "$out/$name.h5")
    for th in 1 2; do
        rate "$name" "$(tmax_for "$dp")" "$th" specialised | awk -v name="$name" -v dp="$dp" -v n="$n" -v th="$th" \
            '{printf "%s\t%s\t%d\t%d\t%d\t%.2f\t%.4g\t%.3f\n", name, dp, n, th, $1, $2, $3, 1e6 / $3}'
    done
done

printf '\n# specialised loop (the scene'"'"'s modules only) against the general loop (VRES_LOOP=general)\n'
printf 'case\tparticles\tthreads\tloop\tparticle_steps_per_s\tus_per_particle_step\tspeedup\n'
gen tg2d "$TG" --dp 0.01
# the Taylor-Green case at dp 0.01 m (10,000 particles): h = sqrt(2) dp, c0 10 m/s, CFL 0.2
tg_tmax=$(awk -v s="$STEPS" 'BEGIN {printf "%.6g", s * 0.2 * 1.41421 * 0.01 / 10}')
for spec in "dambreak2d-20k $(tmax_for 0.01)" "tg2d $tg_tmax"; do
    set -- $spec
    name=$1 tmax=$2
    n=$(particles "$out/$name.h5")
    for th in 1 2; do
        g=$(rate "$name" "$tmax" "$th" general | awk '{print $3}')
        s=$(rate "$name" "$tmax" "$th" specialised | awk '{print $3}')
        awk -v name="$name" -v n="$n" -v th="$th" -v g="$g" -v s="$s" 'BEGIN {
            printf "%s\t%d\t%d\tgeneral\t%.4g\t%.3f\t\n", name, n, th, g, 1e6 / g
            printf "%s\t%d\t%d\tspecialised\t%.4g\t%.3f\t%.2f\n", name, n, th, s, 1e6 / s, s / g }'
    done
done
