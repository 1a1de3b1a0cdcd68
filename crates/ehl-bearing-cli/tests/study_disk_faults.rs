//! Faults on disk during a study: a full disk, a read-only output folder and
//! corrupted point files. In each case the study ends with a clear error or redoes the point,
//! and no finished point file is lost or replaced by a partial one. (Truncated point files,
//! `-o` naming a file and a closed stdout: `study_resume.rs`.)
//!
//! The tests run as root here, where permission bits do not stop writes: the read-only folder
//! is made with `chattr +i` (immutable: not even root may create files in it), falling back to
//! `chmod 555` for other users; the full disk is a size limit on the files the child process may
//! write (`RLIMIT_FSIZE`, set in `pre_exec`, with SIGXFSZ ignored so that the write fails with
//! EFBIG as on a full file system), which needs no privileges.

mod study_common;

use assert_cmd::cargo::CommandCargoExt;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::Command;
use study_common::{assert_same_tree, study_file};

fn bin() -> Command {
    Command::cargo_bin("ehl-bearing").unwrap()
}

fn study(study: &Path, out: &Path, extra: &[&str]) -> Command {
    let mut c = bin();
    c.args([
        "study",
        study.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    c.args(extra);
    c
}

/// The point files of a folder and their bytes.
fn point_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir.join("points"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn full_disk_fails_clearly_and_keeps_finished_points() {
    let tmp = tempfile::tempdir().unwrap();
    let file = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    let clean = tmp.path().join("clean");
    assert!(study(&file, &clean, &[]).output().unwrap().status.success());
    // Shard 1/2 finished earlier; the rest runs on a "full disk": files above 64 bytes fail.
    let out = tmp.path().join("full");
    let o = study(&file, &out, &["--shard", "1/2"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let before = point_files(&out);
    assert_eq!(before.len(), 2);
    let mut c = study(&file, &out, &[]);
    full_disk_above(&mut c, 64);
    let o = c.output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("points") && err.contains("File too large"),
        "the error names the file and the cause: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    // The finished points are untouched, no partial point file and no temporary file is left.
    assert_eq!(point_files(&out), before);
    // With space again the study completes, identical to an undisturbed run.
    let o = study(&file, &out, &[]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("2 computed, 2 loaded"));
    assert_same_tree(&clean, &out);
}

/// Files written by the child fail above `bytes` (as on a full file system).
fn full_disk_above(c: &mut Command, bytes: u64) {
    // SAFETY: only async-signal-safe calls (setrlimit, signal) between fork and exec.
    unsafe {
        c.pre_exec(move || {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let lim = libc::rlimit {
                rlim_cur: bytes as libc::rlim_t,
                rlim_max: bytes as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
}

/// The disk fills while the figures are written (the tables fit, the figures do not): no
/// truncated figure stays under its final name, and `study status` does not call the study
/// merged (it said `complete: true, merged: true` with a truncated k_vs_load.png); with space
/// again `study merge` completes it, identical to an undisturbed run.
#[test]
fn full_disk_while_plotting_leaves_no_partial_figure_and_no_merged_status() {
    let tmp = tempfile::tempdir().unwrap();
    let file = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    let clean = tmp.path().join("clean");
    assert!(study(&file, &clean, &[]).output().unwrap().status.success());
    let size = |p: &Path| std::fs::metadata(p).unwrap().len();
    let mut tables = vec![
        size(&clean.join("results.csv")),
        size(&clean.join("points.csv")),
        size(&clean.join("trends.json")),
    ];
    tables.extend(point_files(&clean).iter().map(|(_, b)| b.len() as u64));
    let limit = tables.into_iter().max().unwrap() + 1;
    // The PNG figures (≈ 140 kB) do not fit; the tables (results.csv ≈ 47 kB) and the SVGs may.
    let smallest_png = ["k", "d", "delta_f"]
        .iter()
        .map(|s| size(&clean.join(format!("{s}_vs_load.png"))))
        .min()
        .unwrap();
    assert!(smallest_png > limit, "{smallest_png} <= {limit}");
    let out = tmp.path().join("full");
    let mut c = study(&file, &out, &[]);
    full_disk_above(&mut c, limit);
    let o = c.output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("File too large"), "{err}");
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().to_string();
        assert!(!name.contains(".tmp-"), "temporary file left: {name}");
        if let Some(stem) = name.strip_suffix(".png").or(name.strip_suffix(".svg")) {
            let ext = &name[stem.len()..];
            assert_eq!(
                std::fs::read(out.join(&name)).unwrap(),
                std::fs::read(clean.join(&name)).unwrap(),
                "a partial figure {name} ({ext}) under its final name"
            );
        }
    }
    let status = bin()
        .args(["study", "status", out.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    let st: serde_json::Value = serde_json::from_slice(&status.stdout).unwrap();
    assert_eq!(st["complete"], true, "{st}");
    assert_eq!(st["merged"], false, "{st}");
    assert!(
        !st["missing_outputs"].as_array().unwrap().is_empty(),
        "{st}"
    );
    let o = bin()
        .args([
            "study",
            "merge",
            "-o",
            out.to_str().unwrap(),
            file.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_same_tree(&clean, &out);
}

/// Makes `dir` read-only for this process (root included); false if the file system or the
/// privileges allow neither way.
fn make_read_only(dir: &Path) -> bool {
    let chattr = Command::new("chattr")
        .arg("+i")
        .arg(dir)
        .output()
        .is_ok_and(|o| o.status.success());
    if chattr {
        return true;
    }
    // SAFETY: geteuid has no preconditions.
    if unsafe { libc::geteuid() } != 0 {
        use std::os::unix::fs::PermissionsExt;
        return std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o555)).is_ok();
    }
    false
}

fn make_writable(dir: &Path) {
    let _ = Command::new("chattr").arg("-i").arg(dir).output();
    use std::os::unix::fs::PermissionsExt;
    let _ = std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o755));
}

#[test]
fn read_only_output_folder_is_refused_before_any_work() {
    let tmp = tempfile::tempdir().unwrap();
    let file = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    let out = tmp.path().join("ro");
    let o = study(&file, &out, &["--shard", "1/2"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let before = point_files(&out);
    let points = out.join("points");
    if !make_read_only(&points) {
        eprintln!(
            "skipped: neither chattr +i nor permission bits can make a folder read-only here"
        );
        return;
    }
    let o = study(&file, &out, &[]).output();
    make_writable(&points);
    let o = o.unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("points") && (err.contains("not permitted") || err.contains("denied")),
        "{err}"
    );
    // Refused by the probe before any point was computed: no per-point log line.
    assert!(!err.contains("converged"), "{err}");
    assert_eq!(point_files(&out), before);
}

#[test]
fn corrupted_point_files_are_redone_and_the_others_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let file = study_file(tmp.path(), "hertz", "[3000, 5000]", "[0.5, 1.0]", "");
    let clean = tmp.path().join("clean");
    assert!(study(&file, &clean, &[]).output().unwrap().status.success());
    let out = tmp.path().join("corrupt");
    assert!(study(&file, &out, &[]).output().unwrap().status.success());
    let pts = point_files(&out);
    // Random bytes, an empty file, and JSON of the wrong shape.
    std::fs::write(out.join("points").join(&pts[0].0), [0u8, 0xff, 0x13, b'{']).unwrap();
    std::fs::write(out.join("points").join(&pts[1].0), b"").unwrap();
    std::fs::write(out.join("points").join(&pts[2].0), b"{\"spec\": 1}").unwrap();
    let o = study(&file, &out, &[]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("3 unreadable point file(s)"), "{err}");
    assert!(String::from_utf8_lossy(&o.stdout).contains("3 computed, 1 loaded"));
    assert_same_tree(&clean, &out);
}
