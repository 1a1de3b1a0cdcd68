//! The Slurm route without a cluster: `study sbatch` writes array and merge scripts whose content
//! follows the options, refuses bad options naming them, submits through `sbatch --parsable`
//! (a recording stand-in here) with the merge job depending on the array and only the unfinished
//! shards on resubmission; the scripts run by bash as array tasks give the single run's files;
//! `study status` counts done, failed, in-flight and interrupted points per shard from a prepared
//! folder. The real cluster is `scripts/test_slurm.sh`.

mod study_common;

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use study_common::{assert_same_tree, ok, run, s, study_file};

fn err(o: Output) -> String {
    assert!(
        !o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    String::from_utf8_lossy(&o.stderr).to_string()
}

/// The seed bearing, dry method, 3 speeds × 4 loads (12 points).
fn hertz_study(dir: &Path) -> PathBuf {
    study_file(
        dir,
        "hertz",
        "[3000, 4000, 5000]",
        "[0.5, 1.0, 1.5, 2.0]",
        "",
    )
}

#[test]
fn sbatch_scripts_follow_the_options() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let out = tmp.path().join("maps");
    let o = ok(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--shards",
        "3",
        "--cpus-per-task",
        "4",
        "--time-limit-min",
        "1500",
        "--partition",
        "short",
        "--method",
        "hertz",
    ]));
    assert!(o.contains("12 points in 3 shards"), "{o}");
    assert!(o.contains("--dependency=afterok:$id"), "{o}");
    let out = std::fs::canonicalize(&out).unwrap();
    let job_dir = out.with_file_name("maps.slurm");
    let array = std::fs::read_to_string(job_dir.join("study.sbatch")).unwrap();
    for line in [
        "#!/bin/bash\n",
        "#SBATCH --array=1-3\n",
        "#SBATCH --cpus-per-task=4\n",
        "#SBATCH --time=1-01:00:00\n",
        "#SBATCH --partition=short\n",
        "#SBATCH --job-name=ehl-study\n",
        "export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"\n",
    ] {
        assert!(array.contains(line), "missing {line:?} in\n{array}");
    }
    let logs = format!("#SBATCH --output={}/logs/%x-%A_%a.out\n", job_dir.display());
    assert!(array.contains(&logs), "{array}");
    let exec = format!(
        "study {} -o {} --shard \"${{SLURM_ARRAY_TASK_ID}}/3\" --method hertz\n",
        std::fs::canonicalize(&study).unwrap().display(),
        out.display()
    );
    assert!(array.contains(&exec), "{exec:?} not in\n{array}");
    let merge = std::fs::read_to_string(job_dir.join("merge.sbatch")).unwrap();
    assert!(
        merge.contains(&format!(
            "study merge {} -o {} --method hertz\n",
            std::fs::canonicalize(&study).unwrap().display(),
            out.display()
        )),
        "{merge}"
    );
    assert!(
        merge.contains("#SBATCH --job-name=ehl-study-merge\n"),
        "{merge}"
    );
    assert!(!merge.contains("--array"), "{merge}");
    // Both are valid bash.
    for f in ["study.sbatch", "merge.sbatch"] {
        let o = Command::new("bash")
            .arg("-n")
            .arg(job_dir.join(f))
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{f}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // Defaults: 4 shards, 2 CPUs, 2 h, no partition line; the output folder holds no scripts.
    let out2 = tmp.path().join("defaults");
    ok(run(&["study", "sbatch", s(&study), "-o", s(&out2)]));
    let a = std::fs::read_to_string(tmp.path().join("defaults.slurm/study.sbatch")).unwrap();
    for line in [
        "#SBATCH --array=1-4\n",
        "#SBATCH --cpus-per-task=2\n",
        "#SBATCH --time=02:00:00\n",
    ] {
        assert!(a.contains(line), "{line:?} not in\n{a}");
    }
    assert!(!a.contains("--partition"), "{a}");
    assert!(!a.contains("--method"), "{a}");
    let names: Vec<_> = std::fs::read_dir(&out2)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    let mut names = names;
    names.sort();
    assert_eq!(names, [".progress", "points"]);
}

#[test]
fn sbatch_refuses_bad_options_naming_them() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let out = tmp.path().join("o");
    let not_executable = tmp.path().join("plain.txt");
    std::fs::write(&not_executable, "").unwrap();
    let cases: [(&[&str], &[&str]); 13] = [
        (&["--bin", "/tmp"], &["--bin /tmp", "not a file"]),
        (
            &["--bin", s(&not_executable)],
            &["plain.txt", "not executable"],
        ),
        (
            &["--stale-after-s", "10"],
            &["--stale-after-s 10", "30 to 86400"],
        ),
        (&["--shards", "0"], &["--shards 0", "1 to 12"]),
        (&["--shards", "13"], &["--shards 13", "1 to 12"]),
        (
            &["--cpus-per-task", "0"],
            &["--cpus-per-task 0", "1 to 1024"],
        ),
        (
            &["--cpus-per-task", "2000"],
            &["--cpus-per-task 2000", "1 to 1024"],
        ),
        (
            &["--time-limit-min", "0"],
            &["--time-limit-min 0", "1 to 525600"],
        ),
        (
            &["--time-limit-min", "600000"],
            &["--time-limit-min 600000", "1 to 525600"],
        ),
        (&["--partition", "a b"], &["--partition \"a b\"", "letters"]),
        (&["--job-name", "x;rm"], &["--job-name \"x;rm\"", "letters"]),
        (&["--method", "magic"], &["--method", "magic"]),
        (&["--shards=-1"], &["--shards", "-1"]),
    ];
    for (args, words) in cases {
        let mut a = vec!["study", "sbatch", s(&study), "-o", s(&out)];
        a.extend_from_slice(args);
        let e = err(run(&a));
        for w in words {
            assert!(e.contains(w), "{args:?}: {w:?} not in {e}");
        }
    }
    // The job folder must not be inside the output folder (which holds results only).
    let e = err(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--job-dir",
        s(&out.join("jobs")),
    ]));
    assert!(
        e.contains("--job-dir") && e.contains("outside the output folder"),
        "{e}"
    );
    // A missing sbatch is an error naming the option.
    let e = err(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--submit",
        "--sbatch",
        "/nonexistent/sbatch",
    ]));
    assert!(
        e.contains("--sbatch") && e.contains("/nonexistent/sbatch"),
        "{e}"
    );
}

/// A stand-in for sbatch that records its arguments and prints job ids like `sbatch --parsable`.
fn fake_sbatch(dir: &Path) -> (PathBuf, PathBuf) {
    let log = dir.join("sbatch.log");
    let path = dir.join("fake-sbatch");
    std::fs::write(
        &path,
        format!(
            "#!/bin/sh\necho \"$*\" >> {log:?}\nn=$(wc -l < {log:?})\necho \"$((40 + n));cluster\"\n"
        ),
    )
    .unwrap();
    Command::new("chmod").arg("+x").arg(&path).status().unwrap();
    (path, log)
}

/// `study sbatch STUDY -o OUT --shards 3 --submit --sbatch SB`: its output.
fn submit_3_shards(study: &Path, out: &Path, sb: &Path) -> String {
    ok(run(&[
        "study",
        "sbatch",
        s(study),
        "-o",
        s(out),
        "--shards",
        "3",
        "--submit",
        "--sbatch",
        s(sb),
    ]))
}

#[test]
fn submit_chains_the_merge_and_resubmits_only_unfinished_shards() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let out = tmp.path().join("o");
    let (sb, log) = fake_sbatch(tmp.path());
    let submit = || submit_3_shards(&study, &out, &sb);
    let o = submit();
    assert!(
        o.contains("submitted array job 41 (tasks 1-3) and merge job 42"),
        "{o}"
    );
    let calls = std::fs::read_to_string(&log).unwrap();
    let lines: Vec<_> = calls.lines().collect();
    assert_eq!(lines.len(), 2, "{calls}");
    assert!(
        lines[0].starts_with("--parsable --array=1-3 ") && lines[0].ends_with("study.sbatch"),
        "{calls}"
    );
    assert!(
        lines[1].starts_with("--parsable --dependency=afterok:41 --kill-on-invalid-dep=yes ")
            && lines[1].ends_with("merge.sbatch"),
        "{calls}"
    );
    // Shard 2 is finished: a resubmission sends tasks 1 and 3 only.
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "2/3"]));
    let o = submit();
    assert!(o.contains("(tasks 1,3)"), "{o}");
    assert!(std::fs::read_to_string(&log)
        .unwrap()
        .contains("--array=1,3 "));
    // Every point done: the merge job alone, without dependency.
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "1/3"]));
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "3/3"]));
    let o = submit();
    assert!(o.contains("submitting the merge job only"), "{o}");
    let calls = std::fs::read_to_string(&log).unwrap();
    let last = calls.lines().last().unwrap();
    assert!(
        last.starts_with("--parsable ")
            && last.ends_with("merge.sbatch")
            && !last.contains("dependency"),
        "{last}"
    );
    // The submissions are in the status.
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(st["submissions"].as_array().unwrap().len(), 3, "{st}");
    assert_eq!(st["submissions"][0]["array_job_id"], "41");
    assert_eq!(st["submissions"][1]["array_tasks"], "1,3");
    assert_eq!(st["complete"], true);
    assert_eq!(st["merged"], false);
}

#[test]
fn scripts_run_as_array_tasks_give_the_single_run() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let full = tmp.path().join("full");
    ok(run(&["study", s(&study), "-o", s(&full)]));
    let out = tmp.path().join("shared");
    ok(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--shards",
        "3",
    ]));
    let jobs = tmp.path().join("shared.slurm");
    // Without Slurm's variables the array script refuses to run.
    let o = Command::new("bash")
        .arg(jobs.join("study.sbatch"))
        .env_remove("SLURM_ARRAY_TASK_ID")
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("submit this script with sbatch"));
    for i in ["3", "1", "2"] {
        let o = Command::new("bash")
            .arg(jobs.join("study.sbatch"))
            .env("SLURM_ARRAY_TASK_ID", i)
            .env("SLURM_CPUS_PER_TASK", "1")
            .output()
            .unwrap();
        let text = ok(o);
        assert!(
            text.contains(&format!("shard {i}/3 on ")) && text.contains("with 1 thread(s)"),
            "{text}"
        );
        assert!(
            text.contains(&format!("shard {i}/3: 4 points (4 computed")),
            "{text}"
        );
    }
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(st["done"], 12, "{st}");
    for sh in st["shards"].as_array().unwrap() {
        assert_eq!(sh["state"], "done", "{st}");
        assert_eq!(sh["done"], 4, "{st}");
    }
    ok(Command::new("bash")
        .arg(jobs.join("merge.sbatch"))
        .output()
        .unwrap());
    // The markers are gone and the folder is the single run's, byte for byte.
    assert_same_tree(&full, &out);
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(st["merged"], true, "{st}");
    assert_eq!(st["done"], 12, "{st}");
    // A late task (held, then released after the merge) does not undo the merge: it finds its
    // points stored and leaves the folder as it was (it re-created the markers, and the status
    // asked for a merge again).
    let o = Command::new("bash")
        .arg(jobs.join("study.sbatch"))
        .env("SLURM_ARRAY_TASK_ID", "2")
        .env("SLURM_CPUS_PER_TASK", "1")
        .output()
        .unwrap();
    assert!(ok(o).contains("0 computed"));
    assert_same_tree(&full, &out);
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(st["merged"], true, "{st}");
}

/// Resubmission asks Slurm what is still queued: pending (or held) tasks of the earlier array
/// are not submitted twice, and the new merge also waits for them.
#[test]
fn resubmission_skips_tasks_slurm_still_holds() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let out = tmp.path().join("o");
    let (sb, log) = fake_sbatch(tmp.path());
    // A stand-in squeue: tasks 2 and 3 of array 41 are pending (after a scancel of task 1).
    let squeue = tmp.path().join("squeue");
    let squeue_log = tmp.path().join("squeue.log");
    std::fs::write(
        &squeue,
        format!(
            "#!/bin/sh\necho \"$*\" >> {squeue_log:?}\necho '41_2 PENDING'\necho '41_3 PENDING'\n"
        ),
    )
    .unwrap();
    Command::new("chmod")
        .arg("+x")
        .arg(&squeue)
        .status()
        .unwrap();
    let submit = || submit_3_shards(&study, &out, &sb);
    let o = submit();
    assert!(o.contains("submitted array job 41 (tasks 1-3)"), "{o}");
    let o = submit();
    assert!(
        o.contains(
            "still queued in Slurm, not resubmitted: shard(s) 2 (41, PENDING), 3 (41, PENDING)"
        ),
        "{o}"
    );
    assert!(o.contains("(tasks 1)"), "{o}");
    let calls = std::fs::read_to_string(&log).unwrap();
    let lines: Vec<_> = calls.lines().collect();
    assert_eq!(lines.len(), 4, "{calls}");
    assert!(lines[2].starts_with("--parsable --array=1 "), "{calls}");
    assert!(
        lines[3].starts_with("--parsable --dependency=afterok:43,afterany:41 "),
        "{calls}"
    );
    let asked = std::fs::read_to_string(&squeue_log).unwrap();
    assert!(
        asked.contains("--array --jobs 41 --format %i %T"),
        "{asked}"
    );
}

fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .unwrap()
        .trim()
        .to_string()
}

fn now_s() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_secs()
}

fn write(path: &Path, v: Value) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, serde_json::to_string_pretty(&v).unwrap()).unwrap();
}

/// A pid that is not running: a child that has exited and been reaped.
fn dead_pid() -> u32 {
    let mut c = Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    pid
}

#[test]
fn status_counts_points_per_shard_from_the_markers() {
    let tmp = tempfile::tempdir().unwrap();
    // 8 points in 4 shards of 2 points each: shard k holds points k-1 and k+3.
    let study = study_file(
        tmp.path(),
        "hertz",
        "[3000, 5000]",
        "[0.5, 1.0, 1.5, 2.0]",
        "",
    );
    let out = tmp.path().join("o");
    ok(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--shards",
        "4",
    ]));
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(
        (st["points"].as_u64(), st["pending"].as_u64()),
        (Some(8), Some(8)),
        "{st}"
    );
    assert_eq!(st["shards"][0]["state"], "pending");
    // Shard 1 done; one point of shard 4 made a failed point (a record with an error).
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "1/4"]));
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "4/4"]));
    let failed = out.join("points/n3000rpm_s2.json");
    let mut rec: Value = serde_json::from_str(&std::fs::read_to_string(&failed).unwrap()).unwrap();
    rec.as_object_mut().unwrap().remove("result");
    rec["error"] = Value::from("equilibrium did not converge");
    write(&failed, rec);
    let p = out.join(".progress");
    let me = hostname();
    // Shard 2: running on this host in a live process (this test), one point in flight.
    let live = std::process::id();
    write(
        &p.join("shard-2of4.json"),
        serde_json::json!({"shard": "2/4", "state": "running", "host": me, "pid": live, "slurm_job": "7_2", "heartbeat_unix_s": now_s()}),
    );
    write(
        &p.join("running/n3000rpm_s1.json"),
        serde_json::json!({"shard": "2/4", "host": me, "pid": live}),
    );
    // Shard 3: its process on this host is gone (cancelled): its point is interrupted.
    let dead = dead_pid();
    write(
        &p.join("shard-3of4.json"),
        serde_json::json!({"shard": "3/4", "state": "running", "host": me, "pid": dead, "slurm_job": "7_3", "heartbeat_unix_s": now_s()}),
    );
    write(
        &p.join("running/n3000rpm_s1.5.json"),
        serde_json::json!({"shard": "3/4", "host": me, "pid": dead}),
    );
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    let counts = |v: &Value| {
        ["done", "failed", "in_flight", "interrupted", "pending"].map(|k| v[k].as_u64().unwrap())
    };
    assert_eq!(counts(&st), [3, 1, 1, 1, 2], "{st}");
    assert_eq!(st["complete"], false);
    let sh = st["shards"].as_array().unwrap();
    assert_eq!(sh[0]["state"], "done");
    assert_eq!(counts(&sh[0]), [2, 0, 0, 0, 0]);
    assert_eq!(
        (sh[1]["state"].as_str(), sh[1]["slurm_job"].as_str()),
        (Some("running"), Some("7_2"))
    );
    assert_eq!(counts(&sh[1]), [0, 0, 1, 0, 1]);
    assert_eq!(sh[2]["state"], "interrupted");
    assert_eq!(counts(&sh[2]), [0, 0, 0, 1, 1]);
    assert_eq!(counts(&sh[3]), [1, 1, 0, 0, 0]);
    // The table says the same, and names the shard to resubmit (3: shard 2 still runs).
    let text = ok(run(&["study", "status", s(&out)]));
    assert!(
        text.contains("8 points: 3 done, 1 failed, 1 in flight, 1 interrupted, 2 pending"),
        "{text}"
    );
    assert!(text.contains("no live process: 3 "), "{text}");
    // Another host: the heartbeat decides (fresh: running; older than --stale-after-s: interrupted).
    write(
        &p.join("shard-2of4.json"),
        serde_json::json!({"shard": "2/4", "state": "running", "host": "node-elsewhere", "pid": 1, "heartbeat_unix_s": now_s() - 100}),
    );
    write(
        &p.join("running/n3000rpm_s1.json"),
        serde_json::json!({"shard": "2/4", "host": "node-elsewhere", "pid": 1}),
    );
    let st: Value = serde_json::from_str(&ok(run(&[
        "study",
        "status",
        s(&out),
        "--json",
        "--stale-after-s",
        "300",
    ])))
    .unwrap();
    assert_eq!(
        (st["shards"][1]["state"].as_str(), st["in_flight"].as_u64()),
        (Some("running"), Some(1)),
        "{st}"
    );
    let st: Value = serde_json::from_str(&ok(run(&[
        "study",
        "status",
        s(&out),
        "--json",
        "--stale-after-s",
        "60",
    ])))
    .unwrap();
    assert_eq!(
        (
            st["shards"][1]["state"].as_str(),
            st["interrupted"].as_u64()
        ),
        (Some("interrupted"), Some(2)),
        "{st}"
    );
    // A stale marker is harmless: the shard's next run redoes its interrupted point and ends done.
    ok(run(&["study", s(&study), "-o", s(&out), "--shard", "3/4"]));
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    assert_eq!(st["shards"][2]["state"], "done", "{st}");
    assert_eq!(counts(&st["shards"][2]), [2, 0, 0, 0, 0], "{st}");
    // Bad options are refused, naming them.
    let e = err(run(&["study", "status", s(&out), "--stale-after-s", "5"]));
    assert!(
        e.contains("--stale-after-s 5") && e.contains("30 to 86400"),
        "{e}"
    );
    let e = err(run(&["study", "status", s(&tmp.path().join("nothing"))]));
    assert!(e.contains("not the output folder of a study"), "{e}");
}

#[test]
fn a_shard_refused_before_any_work_is_shown_failed_with_its_message() {
    let tmp = tempfile::tempdir().unwrap();
    let study = hertz_study(tmp.path());
    let out = tmp.path().join("o");
    let other = tmp.path().join("other");
    ok(run(&["study", s(&study), "-o", s(&other)]));
    ok(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--shards",
        "3",
    ]));
    // Shard 2/3 holds point 2 (3000 rpm × 1); put another study's file under its name.
    let name = "points/n3000rpm_s1.json";
    let text = std::fs::read_to_string(other.join(name)).unwrap();
    let foreign = text.replacen("\"load_scale\": 1.0,", "\"load_scale\": 1.25,", 1);
    assert_ne!(text, foreign);
    std::fs::write(out.join(name), foreign).unwrap();
    let e = err(run(&["study", s(&study), "-o", s(&out), "--shard", "2/3"]));
    assert!(e.contains("different study"), "{e}");
    let st: Value =
        serde_json::from_str(&ok(run(&["study", "status", s(&out), "--json"]))).unwrap();
    let sh = &st["shards"][1];
    assert_eq!(sh["state"], "failed", "{st}");
    assert!(
        sh["message"].as_str().unwrap().contains("different study"),
        "{st}"
    );
    // Its other 3 points were not computed, so the shard is one to resubmit.
    assert_eq!(sh["pending"], 3, "{st}");
    let text = ok(run(&["study", "status", s(&out)]));
    assert!(text.contains("no live process: 1,2,3 "), "{text}");
    assert!(
        text.contains("failed: ") && text.contains("different study"),
        "{text}"
    );
}

/// A garbage plan or shard marker is an error naming the file and the remedy (it showed as
/// "0 points, pending").
#[test]
fn garbage_markers_are_named_not_shown_as_pending() {
    let tmp = tempfile::tempdir().unwrap();
    let study = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    let out = tmp.path().join("o");
    ok(run(&[
        "study",
        "sbatch",
        s(&study),
        "-o",
        s(&out),
        "--shards",
        "2",
    ]));
    let progress = out.join(".progress");
    let plan = progress.join("plan.json");
    let good = std::fs::read(&plan).unwrap();
    for garbage in [
        "not json at all",
        "[1, 2]",
        "{\"points\": 3, \"shards\": 2}",
    ] {
        std::fs::write(&plan, garbage).unwrap();
        let e = err(run(&["study", "status", s(&out)]));
        assert!(
            e.contains("plan.json") && e.contains("remove the folder"),
            "{garbage}: {e}"
        );
    }
    std::fs::write(&plan, good).unwrap();
    ok(run(&["study", "status", s(&out)]));
    // The marker `study status` reads for shard 1/2.
    std::fs::write(progress.join("shard-1of2.json"), "\u{0}\u{1}garbage").unwrap();
    let e = err(run(&["study", "status", s(&out)]));
    assert!(
        e.contains("shard-1of2.json") && e.contains("not a marker"),
        "{e}"
    );
}
