//! The committed header `include/ehl_bearing.h` is the one cbindgen generates from the sources
//! (`build.rs` writes it to `$OUT_DIR`). After a change of the interface, rewrite the committed
//! copy with `EHL_BLESS_HEADER=1 cargo test -p ehl-bearing-c --test header`.

use std::path::Path;

#[test]
fn committed_header_is_up_to_date() {
    let generated = include_str!(concat!(env!("OUT_DIR"), "/ehl_bearing.h"));
    let committed_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/ehl_bearing.h");
    if std::env::var_os("EHL_BLESS_HEADER").is_some() {
        std::fs::write(&committed_path, generated).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&committed_path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/ehl_bearing.h is not the header cbindgen generates from the sources; rewrite it \
         with `EHL_BLESS_HEADER=1 cargo test -p ehl-bearing-c --test header` and commit it"
    );
}
