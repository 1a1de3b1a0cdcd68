//! The coupled characterization loop (dry equilibrium → characterize every contact → equilibrium
//! with the fitted laws → repeat) on the seed case.

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws, Race};
use ehl_bearing::characterize::{
    characterize_bearing, CharacterizeSettings, HertzCharacterizer, LawSource,
};
use ehl_bearing::io::{read_case, Case};

fn seed() -> Case {
    read_case(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/7006.toml"
    )))
    .unwrap()
}

#[test]
fn hertz_characterizer_loop_converges_and_reproduces_the_dry_equilibrium() {
    let case = seed();
    let r = characterize_bearing(
        &case,
        &HertzCharacterizer::default(),
        &CharacterizeSettings::default(),
    )
    .unwrap();
    eprintln!("{:#?}", r.history);
    assert!(r.converged);
}
