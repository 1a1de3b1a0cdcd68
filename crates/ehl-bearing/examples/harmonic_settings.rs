//! The harmonic method on the seed inner contact (600 N, 5000 rpm, as benches/contact.rs) at
//! chosen settings, one line per run: the fitted K, d, ΔF, c, the settling steps, periodicity,
//! cycles per step and time. Used for the time-step and settling study of docs/contact.md.
//!
//! `cargo run --release -p ehl-bearing --example harmonic_settings -- GRID STEPS SETTLING_PERIODS
//! PERIODICITY_TOL STEP_TOL_FILM [LOAD_N [v|w [STEP_COARSEST STEP_COARSE_SWEEPS
//! [SETTLING_TOL_FILM]]]]` (v|w: the cycle type of the steps and of the steady solutions; then
//! the steps' coarsest level and its sweeps per visit, defaults 17 and 6, and the film tolerance
//! of the first quarter period's steps, default 1e-3)
use ehl_bearing::contact::{ball_mass, characterize_harmonic, HarmonicSettings};
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};
use ehl_bearing::ContactLaw;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let num = |i: usize, d: f64| a.get(i).map_or(d, |x| x.parse().expect("a number"));
    let mut s = HarmonicSettings::default();
    s.ehl.grid = num(0, 129.0) as usize;
    s.steps_per_period = num(1, 64.0) as usize;
    s.settling_periods = num(2, 2.0) as usize;
    s.periodicity_tol = num(3, s.periodicity_tol);
    s.step_tol_film = a.get(4).map(|x| x.parse().expect("a number"));
    s.step_coarsest = num(7, s.step_coarsest as f64) as usize;
    s.step_coarse_sweeps = num(8, s.step_coarse_sweeps as f64) as usize;
    s.settling_tol_film = num(9, s.settling_tol_film);
    if a.get(6).map(String::as_str) == Some("v") {
        s.ehl.cycle = ehl_bearing::ehl::CycleType::V;
    }
    let c = EhlContact {
        load: num(5, 600.0),
        rx: 2.9487e-3,
        ry: 178.5e-3,
        sum_velocity: 10.85,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    };
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    let f = characterize_harmonic(&c, m, &s).expect("harmonic run");
    let ehl_bearing::contact::Excitation::Harmonic(e) = f.excitation else {
        unreachable!()
    };
    let stiff = f.k * f.d * f.approach.powf(f.d - 1.0);
    println!(
        "grid {} steps {} settle_max {} tol {:e} step_tol {:e} step mg {}/{}: K {:.5e} d {:.5} ± {:.5} dF {:.3} ± {:.3} \
         c {:.3} dQ/dδ(δ0) {:.5e} F(δ0) {:.3} | settled {} steps, periodicity {:.2e}, cycles/step {:.2}, \
         {} steps not converged, {:.2} s",
        s.ehl.grid,
        s.steps_per_period,
        s.settling_periods,
        s.periodicity_tol,
        e.step_tol_film,
        s.step_coarsest,
        s.step_coarse_sweeps,
        f.k,
        f.d,
        f.std_errors.d,
        f.delta_f,
        f.std_errors.delta_f,
        f.c.unwrap_or(f64::NAN),
        stiff,
        f.law.force(f.approach).0,
        e.settling_steps,
        e.periodicity,
        e.cycles_per_step,
        e.steps_not_converged,
        f.seconds
    );
}
