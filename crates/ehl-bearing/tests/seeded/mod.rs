//! The property tests' configuration: the same cases on every default run.
//!
//! A test that can fail by chance fails CI at random, so every `proptest!` block of the default
//! run draws its cases from one fixed seed ([`SEED`]): a failure is reproduced by rerunning the
//! test, and a seed that once failed stays in the committed `*.proptest-regressions` file (for the
//! blocks that persist failures) and is replayed first.
//!
//! The many-case, unseeded version draws a fresh seed every run:
//!
//! ```text
//! EHL_TEST_RANDOM=1 PROPTEST_CASES=5000 cargo test -p ehl-bearing
//! ```
//!
//! (`PROPTEST_CASES` alone sets the case count of the seeded run; proptest prints the failing
//! input and its seed when a case fails.)

use proptest::test_runner::{Config, RngSeed};

/// The default run's seed.
pub const SEED: u64 = 0x7006_5eed;

/// `cases` cases (or `PROPTEST_CASES`) from the fixed seed, or from a random one with
/// `EHL_TEST_RANDOM=1`; other settings as proptest's defaults.
pub fn config(cases: u32) -> Config {
    let random = std::env::var("EHL_TEST_RANDOM").is_ok_and(|v| v != "0");
    Config {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(cases),
        rng_seed: if random {
            RngSeed::Random
        } else {
            RngSeed::Fixed(SEED)
        },
        ..Config::default()
    }
}
