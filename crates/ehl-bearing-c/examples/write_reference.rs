//! Writes the Rust library's reference numbers for the C and MATLAB/Octave tests
//! (`ehl_bearing_c::reference`) to the file given (default: stdout).
//!
//! `cargo run --release -p ehl-bearing-c --example write_reference -- OUT.txt`

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = match ehl_bearing_c::reference::reference_text(&root) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    match std::env::args().nth(1) {
        Some(path) => std::fs::write(&path, text).unwrap_or_else(|e| {
            eprintln!("error: writing {path}: {e}");
            std::process::exit(1)
        }),
        None => print!("{text}"),
    }
}
