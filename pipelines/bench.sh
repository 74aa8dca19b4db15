#!/usr/bin/env bash
# pipelines/bench.sh - throughput benchmark of vres-run (make bench). Not a test: it prints a
# table and asserts nothing. For each case size and thread count it generates the case, runs a
# fixed number of steps (about STEPS), and reads the solver's own particle-steps per second
# from run.tsv (which excludes snapshot writing). Peer figure (DESIGN section 8): DualSPHysics
# 5.4 on the CPU, 2D dam break dp 0.01 (21,001 particles, 2 threads): 0.98 us per Symplectic
# particle-step.
#   bash pipelines/bench.sh [OUTDIR]      (default build/bench)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/bench}
mkdir -p "$out"
STEPS=${STEPS:-60}
CASE=cases/dsph_dambreak2d/dambreak2d_Def.xml
printf '# vres-run throughput, 2D dam break (%s), Symplectic, about %s steps; host: %s, %s cores\n' \
    "$CASE" "$STEPS" "$(uname -m)" "$(nproc)"
printf '# %s\n' "$(bin/vres-run --version)"
printf 'case\tdp_m\tparticles\tthreads\tsteps\twall_s\tparticle_steps_per_s\tus_per_particle_step\n'
for spec in "dambreak2d-20k 0.01" "dambreak2d-200k 0.00316"; do
    set -- $spec
    name=$1 dp=$2
    store=$out/$name.h5
    [ -f "$store" ] || bin/vres-gencase -q --dp "$dp" "$CASE" -o "$store"
    n=$(bin/vres-info -t "$store" | awk '!/^#/ {n += $4} END {print n}')
    # dt ~ CFL h / c0 with h = sqrt(2) dp, c0 = 88.37 m/s, CFL 0.2: run STEPS such steps
    tmax=$(awk -v dp="$dp" -v s="$STEPS" 'BEGIN {printf "%.6g", s * 0.2 * 1.41421 * dp / 88.37}')
    for th in 1 2; do
        rd=$out/run-$name-t$th
        rm -rf "$rd"
        OMP_NUM_THREADS=$th bin/vres-run -q --threads "$th" --tmax "$tmax" --tout "$tmax" "$store" -o "$rd"
        awk -v name="$name" -v dp="$dp" -v n="$n" -v th="$th" '!/^#/ {l = $0} END {
            split(l, f, "\t"); printf "%s\t%s\t%d\t%d\t%d\t%.2f\t%.4g\t%.3f\n", name, dp, n, th, f[2], f[10], f[11], 1e6 / f[11] }' \
            "$rd/run.tsv"
    done
done
