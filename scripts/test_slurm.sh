#!/usr/bin/env bash
# Slurm stage of the tests (called by scripts/test.sh): a real one-node Slurm cluster on this
# machine, started without systemd, runs the seed study as job arrays and the result is compared
# byte for byte with a single-machine run.
#
#   scripts/test_slurm.sh               # default: hertz seed study (12 points) + light quasi-static
#                                       # study (2 speeds x 3 loads, grid 33, 5 film solutions)
#   SLURM_FULL=1 scripts/test_slurm.sh  # the full seed study examples/study_7006.toml (12 points,
#                                       # quasi-static at its default options; tens of minutes)
#
# What it does:
#  1. builds the ehl-bearing binary (as cargo test --workspace does; EHL_BEARING_BIN overrides);
#  2. installs Debian's slurm-wlm and munge with apt-get if they are missing (the stage is
#     SKIPPED, not failed, only if they cannot be installed or the script is not run as root);
#  3. (scripts/slurm_local_cluster.sh) writes a munge key and a one-node slurm.conf (NodeName=localhost CPUs=2, proctrack/linuxproc,
#     task/none, select/cons_tres) into a temporary folder and starts munged, slurmctld and slurmd
#     as daemons with pid files there (free ports are picked, so parallel runs do not collide);
#  4. for the hertz and the quasi-static method: a single-machine run, then
#     `ehl-bearing study sbatch … --shards 3 --cpus-per-task 1 --submit` (3 array tasks + the
#     dependent merge job), waits (bounded), checks every job COMPLETED and `diff -r` of the two
#     output folders;
#     then a 3 x 3 x 3 law map by `law-map sbatch --submit` against one generated on this machine;
#  5. a failing task (a foreign point file in its shard): FAILED, message in its log and in
#     `study status`, merge not run; after removing the cause, the resubmission runs that task only;
#  6. fault test: the quasi-static array again, task 2 cancelled with scancel while its point is in
#     flight; `study status` must show the shard interrupted and the merge job must not have run;
#     resubmitting must submit task 2 only, and the merged folder must again equal the single run;
#  7. pending tasks: the node drained, the array submitted, task 1 cancelled: the resubmission
#     submits task 1 only (squeue shows 2 and 3 pending); then a late run of task 2 after the
#     merge leaves the merged folder and its status unchanged;
#  8. stops every daemon it started (trap on EXIT) and removes the temporary folder
#     (KEEP_SLURM_TMP=1 keeps it).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
T_START=$(date +%s)

log() { echo "[slurm $(($(date +%s) - T_START)) s] $*"; }
skip() {
    echo "SKIPPED: Slurm stage: $*"
    exit 0
}
fail() {
    echo "FAILED: Slurm stage: $*" >&2
    exit 1
}

# ---------------------------------------------------------------- 1. the binary
if [ -n "${EHL_BEARING_BIN:-}" ]; then
    BIN=$EHL_BEARING_BIN
else
    # The binary `cargo test --workspace` builds for the CLI's integration tests (test profile,
    # optimized, Cargo.toml; the workspace's test feature set): after the cargo test stage of
    # scripts/test.sh this compiles nothing (`cargo build -p ehl-bearing-cli` would build the
    # dependencies again with another feature set: 90 s on a clean clone).
    log "building ehl-bearing (cargo test --workspace --no-run)"
    cargo test -q --workspace --no-run
    BIN=$ROOT/target/debug/ehl-bearing
fi
[ -x "$BIN" ] || fail "no executable ehl-bearing at $BIN"

# ---------------------------------------------------------------- 2./3. packages and the cluster
# shellcheck source=scripts/slurm_local_cluster.sh
source scripts/slurm_local_cluster.sh

run_bin() { timeout 1800 "$BIN" "$@"; }

# ---------------------------------------------------------------- 4. studies
SEED_STUDY=$ROOT/examples/study_7006.toml
if [ "${SLURM_FULL:-0}" = 1 ]; then
    QS_STUDY=$SEED_STUDY
    JOB_LIMIT=7200
    log "SLURM_FULL=1: the full seed study (12 points) by the quasi-static method"
else
    QS_STUDY=$TMP/study_7006_light.toml
    cat >"$QS_STUDY" <<EOF
# Light quasi-static study of the seed bearing for the Slurm stage: 2 speeds x 3 load scales,
# 5 steady film solutions per contact on a 33 x 33 grid.
case = "$ROOT/examples/7006.toml"
method = "quasi-static"
inner_speeds_rpm = [3000.0, 5000.0]
load_scales = [0.5, 1.0, 2.0]

[method_options]
grid = 33
points = 5
EOF
    JOB_LIMIT=600
fi

# study_on_slurm NAME STUDY METHOD: single run vs 3-task array + merge, diff -r.
study_on_slurm() {
    local name=$1 study=$2 method=$3 out
    log "$name: single-machine run ($method)"
    RAYON_NUM_THREADS=2 run_bin study "$study" -o "$TMP/ref-$name" --method "$method" >"$TMP/ref-$name.log" 2>&1 ||
        fail "$name: single-machine run failed (log $TMP/ref-$name.log)"
    log "$name: study sbatch --shards 3 --submit"
    out=$(run_bin study sbatch "$study" -o "$TMP/slurm-$name" --method "$method" --shards 3 \
        --cpus-per-task 1 --time-limit-min 30 --submit) || fail "$name: study sbatch --submit failed: $out"
    parse_submission "$out"
    [ "$ARRAY_TASKS" = "1-3" ] || fail "$name: submitted tasks $ARRAY_TASKS, expected 1-3"
    wait_jobs "$JOB_LIMIT" "$ARRAY_ID" "$MERGE_ID"
    expect_completed "$name array" "$ARRAY_ID"
    expect_completed "$name merge" "$MERGE_ID"
    [ "$(job_states "$ARRAY_ID" | wc -l)" = 3 ] || fail "$name: array job $ARRAY_ID does not have 3 tasks"
    for i in 1 2 3; do
        grep -q "ehl-bearing shard $i/3 on .* with 1 thread(s)" "$TMP/slurm-$name.slurm/logs/"*"-${ARRAY_ID}_$i.out" ||
            fail "$name: log of task $i does not show shard $i/3 with 1 thread (SLURM_CPUS_PER_TASK)"
    done
    diff -r "$TMP/ref-$name" "$TMP/slurm-$name" ||
        fail "$name: the merged Slurm folder differs from the single-machine run"
    [ -f "$TMP/slurm-$name/trends.json" ] || fail "$name: no trends.json"
    log "$name: 3 array tasks + merge COMPLETED; merged folder identical to the single run ($(find "$TMP/slurm-$name" -type f | wc -l) files)"
}

study_on_slurm hertz "$SEED_STUDY" hertz

# A task that fails (here: its folder holds a point file of another study under one of its point
# names) exits non-zero with the message in its log; the merge does not run; status shows the
# shard failed; once the cause is removed, the resubmission submits that task only.
log "failing task: hertz array with a foreign point file in shard 1"
FAILING=$TMP/failing
mkdir -p "$FAILING/points"
sed 's/"load_scale": 0.5,/"load_scale": 0.75,/' "$TMP/ref-hertz/points/n3000rpm_s0.5.json" >"$FAILING/points/n3000rpm_s0.5.json"
cmp -s "$FAILING/points/n3000rpm_s0.5.json" "$TMP/ref-hertz/points/n3000rpm_s0.5.json" &&
    fail "failing task: could not alter the point file"
out=$(run_bin study sbatch "$SEED_STUDY" -o "$FAILING" --method hertz --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "failing task: study sbatch --submit failed: $out"
parse_submission "$out"
wait_jobs "$JOB_LIMIT" "$ARRAY_ID" "$MERGE_ID"
[ "$(job_states "${ARRAY_ID}_1")" = FAILED ] || fail "failing task: task 1 ended as $(job_states "${ARRAY_ID}_1"), expected FAILED"
expect_completed "failing task: tasks 2 and 3" "${ARRAY_ID}_2" "${ARRAY_ID}_3"
[ "$(job_states "$MERGE_ID" 2>/dev/null || echo gone)" != COMPLETED ] || fail "failing task: the merge job ran"
grep -q "^error: .*different study" "$FAILING.slurm/logs/"*"-${ARRAY_ID}_1.out" ||
    fail "failing task: the log of task 1 does not give the error"
status=$(run_bin study status "$FAILING")
if [ "$(awk '$1 == "1/3" { print $2 }' <<<"$status")" != failed ] || ! grep -q "failed: .*different study" <<<"$status"; then
    fail "failing task: study status does not show shard 1/3 failed with its message: $status"
fi
rm "$FAILING/points/n3000rpm_s0.5.json"
out=$(run_bin study sbatch "$SEED_STUDY" -o "$FAILING" --method hertz --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "failing task: resubmission failed: $out"
parse_submission "$out"
[ "$ARRAY_TASKS" = 1 ] || fail "failing task: resubmission submitted tasks $ARRAY_TASKS, expected only 1"
wait_jobs "$JOB_LIMIT" "$ARRAY_ID" "$MERGE_ID"
expect_completed "failing task: resubmitted task and merge" "$ARRAY_ID" "$MERGE_ID"
diff -r "$TMP/ref-hertz" "$FAILING" || fail "failing task: the merged folder differs from the single run"
log "failing task: FAILED with its message in the log and the status; only task 1 resubmitted; identical merge"

study_on_slurm quasi-static "$QS_STUDY" quasi-static

# ---------------------------------------------------------------- 4b. a law map
# A 3 x 3 x 3 law map on grid 33 (seconds): `law-map sbatch --shards 3 --submit` (3 array tasks
# of `law-map generate --shard` and the dependent assemble job) against `law-map generate` and
# `assemble` on this machine: the map files must be the same bytes but the CPU times they record.
MAP_SPEC=$TMP/law_map_small.toml
cat >"$MAP_SPEC" <<EOF
viscosity_model = "roelands"
density_model = "dowson-higginson"
alpha_p0 = 4.312
ln_eta0_ratio = 6.451124175131799
amplitude = 0.2
points = 7
grid = 33
[[axis]]
group = "m"
min = 300.0
max = 1000.0
nodes = 3
log = true
[[axis]]
group = "l"
min = 20.0
max = 24.0
nodes = 3
log = false
[[axis]]
group = "ry_over_rx"
min = 10.0
max = 20.0
nodes = 3
log = true
EOF
log "law map: single-machine generate + assemble"
RAYON_NUM_THREADS=2 run_bin law-map generate "$MAP_SPEC" -o "$TMP/ref-map" >"$TMP/ref-map.log" 2>&1 ||
    fail "law map: single-machine generate failed (log $TMP/ref-map.log)"
run_bin law-map assemble "$MAP_SPEC" -o "$TMP/ref-map" --map "$TMP/ref-map.json" >>"$TMP/ref-map.log" 2>&1 ||
    fail "law map: single-machine assemble failed (log $TMP/ref-map.log)"
log "law map: law-map sbatch --shards 3 --submit"
out=$(run_bin law-map sbatch "$MAP_SPEC" -o "$TMP/slurm-map" --map "$TMP/slurm-map.json" --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "law map: law-map sbatch --submit failed: $out"
line=$(grep '^submitted array job' <<<"$out") || fail "law map: no submission in: $out"
MAP_ARRAY=$(sed -E 's/^submitted array job ([0-9]+) .*/\1/' <<<"$line")
MAP_ASSEMBLE=$(sed -E 's/.* and assemble job ([0-9]+) .*/\1/' <<<"$line")
wait_jobs "$JOB_LIMIT" "$MAP_ARRAY" "$MAP_ASSEMBLE"
expect_completed "law map array" "$MAP_ARRAY"
expect_completed "law map assemble" "$MAP_ASSEMBLE"
[ "$(job_states "$MAP_ARRAY" | wc -l)" = 3 ] || fail "law map: array job $MAP_ARRAY does not have 3 tasks"
strip_cpu() { sed -E 's/"(seconds|cpu_seconds)": *[0-9.eE+-]+/"\1": _/g' "$1"; }
cmp <(strip_cpu "$TMP/ref-map.json") <(strip_cpu "$TMP/slurm-map.json") ||
    fail "law map: the map assembled on Slurm differs from the single-machine map (beyond CPU times)"
out=$(run_bin law-map sbatch "$MAP_SPEC" -o "$TMP/slurm-map" --map "$TMP/slurm-map.json" --shards 3 --submit) ||
    fail "law map: resubmission failed: $out"
grep -q "every node is done: submitting the assemble job only" <<<"$out" ||
    fail "law map: a resubmission of a finished map did not submit the assemble job alone: $out"
log "law map: 3 array tasks + assemble COMPLETED; map identical to the single-machine one; resubmission assembles only"

# ---------------------------------------------------------------- 5. fault test
log "fault test: quasi-static array, task 2 cancelled mid-run"
FAULT=$TMP/fault
out=$(run_bin study sbatch "$QS_STUDY" -o "$FAULT" --method quasi-static --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "fault: study sbatch --submit failed: $out"
parse_submission "$out"
shard2() { run_bin study status "$FAULT" | awk '$1 == "2/3" { print $2, $6 }'; }
t0=$SECONDS
until [ "$(shard2)" = "running 1" ]; do # state running, one point in flight
    ((SECONDS - t0 > 120)) && fail "fault: shard 2/3 never had a point in flight within 120 s (status: $(shard2))"
    sleep 0.2
done
scancel "${ARRAY_ID}_2" || fail "fault: scancel ${ARRAY_ID}_2 failed"
log "fault: scancel ${ARRAY_ID}_2 with its point in flight"
wait_jobs "$JOB_LIMIT" "$ARRAY_ID" "$MERGE_ID"
[ "$(job_states "${ARRAY_ID}_2")" = CANCELLED ] || fail "fault: task 2 ended as $(job_states "${ARRAY_ID}_2"), expected CANCELLED"
expect_completed "fault: tasks 1 and 3" "${ARRAY_ID}_1" "${ARRAY_ID}_3"
merge_state=$(job_states "$MERGE_ID" 2>/dev/null || echo gone)
[ "$merge_state" != COMPLETED ] || fail "fault: the merge job ran although task 2 was cancelled"
status=$(run_bin study status "$FAULT")
echo "$status"
[ "$(awk '$1 == "2/3" { print $2 }' <<<"$status")" = interrupted ] || fail "fault: study status does not show shard 2/3 interrupted"
awk '$1 == "2/3" && $7 >= 1 { ok = 1 } END { exit !ok }' <<<"$status" || fail "fault: no interrupted point in shard 2/3"
[ ! -f "$FAULT/points.csv" ] || fail "fault: outputs were written although a shard was cancelled"
log "fault: resubmitting"
out=$(run_bin study sbatch "$QS_STUDY" -o "$FAULT" --method quasi-static --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "fault: resubmission failed: $out"
parse_submission "$out"
[ "$ARRAY_TASKS" = 2 ] || fail "fault: resubmission submitted tasks $ARRAY_TASKS, expected only 2"
wait_jobs "$JOB_LIMIT" "$ARRAY_ID" "$MERGE_ID"
expect_completed "fault: resubmitted task" "$ARRAY_ID"
expect_completed "fault: merge" "$MERGE_ID"
diff -r "$TMP/ref-quasi-static" "$FAULT" ||
    fail "fault: the merged folder after the resubmission differs from the single-machine run"
log "fault: only task 2 resubmitted; merged folder identical to the single run"

# ---------------------------------------------------------------- 6. pending and late tasks
# Resubmission asks Slurm what it still holds: with the node drained the array's tasks stay
# PENDING; after scancel of task 1 the resubmission must submit task 1 only (not 2 and 3 a second
# time) with a merge that also waits for the pending ones. After the merge, a late run of task 2
# (a held task released late) must leave the merged folder as it is.
log "pending tasks: hertz array on a drained node, task 1 cancelled, resubmission"
PEND=$TMP/pending
timeout 10 scontrol update NodeName=localhost State=DRAIN Reason=ehl-bearing-test ||
    fail "pending: could not drain the node"
out=$(run_bin study sbatch "$SEED_STUDY" -o "$PEND" --method hertz --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "pending: study sbatch --submit failed: $out"
parse_submission "$out"
FIRST_ID=$ARRAY_ID
FIRST_MERGE=$MERGE_ID
scancel "${FIRST_ID}_1" || fail "pending: scancel ${FIRST_ID}_1 failed"
t0=$SECONDS
while timeout 10 squeue -h -r -j "$FIRST_ID" -o %i | grep -qx "${FIRST_ID}_1"; do
    ((SECONDS - t0 > 60)) && fail "pending: task ${FIRST_ID}_1 still queued 60 s after scancel"
    sleep 0.2
done
out=$(run_bin study sbatch "$SEED_STUDY" -o "$PEND" --method hertz --shards 3 \
    --cpus-per-task 1 --time-limit-min 30 --submit) || fail "pending: resubmission failed: $out"
echo "$out"
grep -q "still queued in Slurm, not resubmitted: shard(s) 2 (${FIRST_ID}, PENDING), 3 (${FIRST_ID}, PENDING)" <<<"$out" ||
    fail "pending: the resubmission does not report tasks 2 and 3 as still queued"
parse_submission "$out"
[ "$ARRAY_TASKS" = 1 ] || fail "pending: resubmission submitted tasks $ARRAY_TASKS, expected only 1"
timeout 10 scontrol update NodeName=localhost State=RESUME || fail "pending: could not resume the node"
wait_jobs "$JOB_LIMIT" "$FIRST_ID" "$FIRST_MERGE" "$ARRAY_ID" "$MERGE_ID"
expect_completed "pending: tasks 2 and 3 of the first array" "${FIRST_ID}_2" "${FIRST_ID}_3"
expect_completed "pending: the resubmitted task and its merge" "$ARRAY_ID" "$MERGE_ID"
diff -r "$TMP/ref-hertz" "$PEND" || fail "pending: the merged folder differs from the single run"
log "pending: tasks 2 and 3 not queued twice; only task 1 resubmitted; identical merge"
log "late task: task 2 submitted again after the merge"
late=$(sbatch --parsable --array=2 "$PEND.slurm/study.sbatch") || fail "late task: sbatch failed"
late=${late%%;*}
wait_jobs "$JOB_LIMIT" "$late"
expect_completed "late task" "$late"
diff -r "$TMP/ref-hertz" "$PEND" || fail "late task: the merged folder changed"
status=$(run_bin study status "$PEND" --json) || fail "late task: study status failed"
grep -q '"merged": true' <<<"$status" || fail "late task: study status no longer calls the study merged: $status"
log "late task: the merged folder unchanged, status still merged"

log "Slurm stage passed in $(($(date +%s) - T_START)) s"
