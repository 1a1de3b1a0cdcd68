#!/usr/bin/env bash
# The steady-EHL benchmark set of BENCHMARKS.md (issues 11 and 16): criterion benches of
# crates/ehl-bearing/benches/{ehl,contact}.rs, with the load average before and after.
#   scripts/bench_ehl.sh            # everything except the harmonic method (~15 min on 2 cores)
#   scripts/bench_ehl.sh quick      # circular 257², seed contact, kernel cache on/off (~3 min)
# Write down the two `uptime` lines next to every figure you copy.
set -euo pipefail
cd "$(dirname "$0")/.."
args=(-- --warm-up-time 1 --measurement-time 5)
uptime
if [[ "${1:-}" == quick ]]; then
  cargo bench -p ehl-bearing --bench ehl "${args[@]}" 'ehl_circular|ehl_7006_inner/257|ehl_kernel_cache'
else
  cargo bench -p ehl-bearing --bench ehl "${args[@]}"
  cargo bench -p ehl-bearing --bench contact "${args[@]}" 'quasi_static'
fi
uptime
