#!/usr/bin/env bash
# The steady-EHL benchmark set of BENCHMARKS.md: criterion benches of
# crates/ehl-bearing/benches/{ehl,contact}.rs, with the load average before and after.
#   scripts/bench_ehl.sh            # everything except the harmonic method (~15 min on 2 cores)
#   scripts/bench_ehl.sh quick      # circular 257², seed contact, kernel cache on/off (~3 min)
#   scripts/bench_ehl.sh speed      # speed goals: circular 257² (new stopping rule and fixed
#                                   # tolerances), the 22 seed contacts and the slowest one,
#                                   # quasi-static seed contact, plus the CLI under /usr/bin/time
#   scripts/bench_ehl.sh harmonic   # the harmonic method, see the block at the end
# Write down the two `uptime` lines next to every figure you copy.
set -euo pipefail
cd "$(dirname "$0")/.."
args=(-- --warm-up-time 1 --measurement-time 5)
uptime
if [[ "${1:-}" == speed ]]; then
  cargo bench -p ehl-bearing --bench ehl "${args[@]}" 'ehl_circular|ehl_seed_22'
  cargo bench -p ehl-bearing --bench contact "${args[@]}" 'contact/quasi_static'
  cargo build --release -p ehl-bearing-cli
  for i in 1 2 3; do
    /usr/bin/time -f "%e s wall %U s user" target/release/ehl-bearing ehl --moes-m 20 --moes-l 10 \
      --viscosity roelands --density dowson-higginson --grid 257 | grep -E "H_c|cycles"
    /usr/bin/time -f "%e s wall %U s user" target/release/ehl-bearing contact \
      examples/contact_7006_inner.toml | grep -E "ΔF"
  done
elif [[ "${1:-}" == quick ]]; then
  cargo bench -p ehl-bearing --bench ehl "${args[@]}" 'ehl_circular|ehl_7006_inner/257|ehl_kernel_cache'
elif [[ "${1:-}" != harmonic ]]; then
  cargo bench -p ehl-bearing --bench ehl "${args[@]}"
  cargo bench -p ehl-bearing --bench contact "${args[@]}" 'quasi_static'
fi
uptime
# Harmonic method (BENCHMARKS.md, "Harmonic method speed-up"): the seed contact at the
# defaults, with the two whole settling periods of before, and on 65² (~6 min on 2 cores).
#   scripts/bench_ehl.sh harmonic
if [[ "${1:-}" == harmonic ]]; then
  uptime
  cargo bench -p ehl-bearing --bench contact -- --warm-up-time 1 'harmonic'
  /usr/bin/time -v target/release/ehl-bearing contact examples/contact_7006_inner.toml \
    --method harmonic --json > /dev/null
  uptime
fi
