#!/usr/bin/env bash
# Repeats the default test run (.ci/run, i.e. scripts/test.sh) in a clean clone of this
# repository's HEAD, N times in a row, stopping at the first failure; one summary line per run.
#
#   scripts/repeat_tests.sh [N=20] [CLONE_DIR=/tmp/ehl-bearing-repeat]
#
# The first run builds everything in the clone (about 12 minutes on 2 cores), later runs reuse
# the build (about 4-5 minutes each). Each run's log: CLONE_DIR.run-I.log; summary:
# CLONE_DIR.summary. Exit status 0 if every run passed.
set -euo pipefail
n=${1:-20}
dir=${2:-/tmp/ehl-bearing-repeat}
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$dir"
git clone -q "$root" "$dir"
summary=$dir.summary
echo "repeat of the default test run at $(git -C "$dir" log --oneline -1), $(date -u)" >"$summary"
for i in $(seq "$n"); do
    t0=$SECONDS
    if (cd "$dir" && CI=true bash .ci/run) >"$dir.run-$i.log" 2>&1; then
        echo "run $i: passed in $((SECONDS - t0)) s" | tee -a "$summary"
    else
        echo "run $i: FAILED in $((SECONDS - t0)) s (log $dir.run-$i.log)" | tee -a "$summary"
        exit 1
    fi
done
echo "$n of $n runs passed" | tee -a "$summary"
