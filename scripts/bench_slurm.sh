#!/usr/bin/env bash
# BENCHMARKS.md "Studies on Slurm": a 5 speeds x 4 loads quasi-static study of the seed bearing
# (examples/7006.toml, default quasi-static settings) as one process with 2 threads, and as a
# 2-task array (one CPU each, RAYON_NUM_THREADS=1 from SLURM_CPUS_PER_TASK) plus the merge job on
# the local one-node Slurm of scripts/slurm_local_cluster.sh; wall and CPU time per run and per
# task, and the overhead per task. Checks that both folders are identical. Needs root.
#   scripts/bench_slurm.sh        (~3-6 min on 2 idle cores)
# Write down the `uptime` lines it prints next to the figures.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
T_START=$(date +%s)
log() { echo "[bench $(($(date +%s) - T_START)) s] $*"; }
skip() {
    echo "SKIPPED: $*"
    exit 0
}
fail() {
    echo "FAILED: $*" >&2
    exit 1
}
[ -x /usr/bin/time ] || fail "needs /usr/bin/time (apt-get install time)"
log "building the release binary"
cargo build -q --release -p ehl-bearing-cli --bin ehl-bearing
REAL=$ROOT/target/release/ehl-bearing
# shellcheck source=scripts/slurm_local_cluster.sh
source scripts/slurm_local_cluster.sh

STUDY=$TMP/study_7006_5x4.toml
cat >"$STUDY" <<EOF
case = "$ROOT/examples/7006.toml"
method = "quasi-static"
inner_speeds_rpm = [3000.0, 3500.0, 4000.0, 4500.0, 5000.0]
load_scales = [0.5, 1.0, 1.5, 2.0]
EOF
# The tasks run the binary through /usr/bin/time, which writes its figures into the task's log.
WRAP=$TMP/timed-ehl-bearing
cat >"$WRAP" <<EOF
#!/bin/bash
exec /usr/bin/time -f "time: wall_s=%e user_s=%U sys_s=%S" "$REAL" "\$@"
EOF
chmod +x "$WRAP"

echo "uptime before: $(uptime)"
log "one process, 2 threads"
/usr/bin/time -f "time: wall_s=%e user_s=%U sys_s=%S" -o "$TMP/one.time" \
    env RAYON_NUM_THREADS=2 "$REAL" study "$STUDY" -o "$TMP/one" >"$TMP/one.log" 2>&1 ||
    fail "single run failed (log $TMP/one.log)"
echo "uptime after one process: $(uptime)"
log "2-task array (1 CPU each) + merge"
t0=$(date +%s.%N)
out=$("$REAL" study sbatch "$STUDY" -o "$TMP/array" --shards 2 --cpus-per-task 1 \
    --time-limit-min 60 --bin "$WRAP" --submit)
parse_submission "$out"
wait_jobs 3600 "$ARRAY_ID" "$MERGE_ID"
t1=$(date +%s.%N)
expect_completed "array" "$ARRAY_ID"
expect_completed "merge" "$MERGE_ID"
echo "uptime after the array: $(uptime)"
diff -r "$TMP/one" "$TMP/array" || fail "the array's merged folder differs from the single run"

field() { sed -nE "s/.*time: .*$1=([0-9.]+).*/\\1/p" "$2" | tail -1; }
points_s() { sed -nE 's/^point .* in ([0-9.]+) s$/\1/p' "$1" | awk '{ s += $1 } END { printf "%.1f", s }'; }
echo
echo "| run | wall s | CPU s (user + sys) | points' own time s | overhead s |"
echo "|---|---|---|---|---|"
f=$TMP/one.time
echo "| one process, 2 threads | $(field wall_s "$f") | $(awk "BEGIN { print $(field user_s "$f") + $(field sys_s "$f") }") | $(points_s "$TMP/one.log") | |"
logs=$TMP/array.slurm/logs
cpu_total=0
for i in 1 2; do
    f=$(ls "$logs"/*-"${ARRAY_ID}_$i".out)
    w=$(field wall_s "$f")
    c=$(awk "BEGIN { print $(field user_s "$f") + $(field sys_s "$f") }")
    p=$(points_s "$f")
    cpu_total=$(awk "BEGIN { print $cpu_total + $c }")
    echo "| array task $i (shard $i/2, 1 CPU) | $w | $c | $p | $(awk "BEGIN { printf \"%.1f\", $w - $p }") |"
done
f=$(ls "$logs"/*-merge-"$MERGE_ID".out)
c=$(awk "BEGIN { print $(field user_s "$f") + $(field sys_s "$f") }")
cpu_total=$(awk "BEGIN { print $cpu_total + $c }")
echo "| merge job | $(field wall_s "$f") | $c | | |"
echo "| array + merge, submission to merge end | $(awk "BEGIN { printf \"%.1f\", $t1 - $t0 }") | $cpu_total | | |"
log "done"
