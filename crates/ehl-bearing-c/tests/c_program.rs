//! Builds the C test program `tests/c/test_ehl.c` with the system C compiler (`$CC`, else `cc`)
//! against the shared library this test run built, writes the Rust library's reference numbers
//! (`ehl_bearing_c::reference`) and runs the program: every number through C must equal the
//! Rust one to round-off, and the error paths must give their status and message. A missing C
//! compiler fails the test (it is not skipped).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The directory of the libehl_bearing_c.so built with this test binary (the same compilation
/// of the library as the rlib linked into this test).
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap().to_path_buf();
    for dir in [deps.clone(), deps.parent().unwrap().to_path_buf()] {
        if dir.join("libehl_bearing_c.so").exists() {
            return dir;
        }
    }
    panic!(
        "libehl_bearing_c.so not found next to {} (cargo builds it with the test)",
        exe.display()
    );
}

#[test]
fn c_program_agrees_with_the_rust_library() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = manifest.join("../..").canonicalize().unwrap();
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_program");
    std::fs::create_dir_all(&tmp).unwrap();
    let reference = tmp.join("reference.txt");
    std::fs::write(
        &reference,
        ehl_bearing_c::reference::reference_text(&root).unwrap(),
    )
    .unwrap();
    let lib = library_dir();
    let exe = tmp.join("test_ehl");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args([
            "-std=c99",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
        ])
        .arg("-I")
        .arg(manifest.join("include"))
        .arg(manifest.join("tests/c/test_ehl.c"))
        .arg("-L")
        .arg(&lib)
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .args(["-lehl_bearing_c", "-lm", "-o"])
        .arg(&exe)
        .status()
        .unwrap_or_else(|e| panic!("the C compiler `{cc}` could not be run: {e} (install gcc)"));
    assert!(status.success(), "compiling tests/c/test_ehl.c failed");
    // The library found first is the one it was linked against: cargo's LD_LIBRARY_PATH (which
    // outranks the rpath) may name target/debug first, where an earlier build's copy can lack
    // the newest functions.
    let out = Command::new(&exe)
        .env("LD_LIBRARY_PATH", &lib)
        .arg(&root)
        .arg(&reference)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    println!("{stdout}");
    eprintln!("{stderr}");
    assert!(
        out.status.success() && stdout.contains(" passed, 0 failed"),
        "the C test program failed:\n{stdout}\n{stderr}"
    );
}
