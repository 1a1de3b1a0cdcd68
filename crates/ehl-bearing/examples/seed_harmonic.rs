//! The harmonic method on the 22 contacts of the seed bearing at one speed (dry-Hertz loads of
//! `benches/seed_contacts.csv`), one after the other on one thread, at the default settings:
//! one line per contact (race, load, d, ΔF, c, settling steps, periodicity, cycles per step,
//! steps not converged, seconds) and a total. Used for the step-iteration study of
//! BENCHMARKS.md and docs/contact.md.
//!
//! `cargo run --release -p ehl-bearing --example seed_harmonic -- [RPM [CONTACT…]]`: RPM 3000
//! (default), 4000 or 5000; CONTACTs select some, as ball number and race initial (`7i 5o`).
//! Environment: `STEP_TOL_FILM` overrides the steps' film tolerance, `FREQUENCY_FRACTION` Ω/ω_n.
use ehl_bearing::contact::{ball_mass, characterize_harmonic, Excitation, HarmonicSettings};
use ehl_bearing::material::Solid;

#[path = "../benches/common/seed_contacts.rs"]
mod seed_contacts;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let rpm = args.first().cloned().unwrap_or_else(|| "3000".into());
    let only = &args[args.len().min(1)..];
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    let mut s = HarmonicSettings::default();
    let env = |k: &str| {
        std::env::var(k)
            .ok()
            .map(|v| v.parse::<f64>().expect("a number"))
    };
    if let Some(t) = env("STEP_TOL_FILM") {
        s.step_tol_film = Some(t);
    }
    if let Some(f) = env("FREQUENCY_FRACTION") {
        s.frequency = ehl_bearing::contact::ExcitationFrequency::FractionOfNatural(f);
    }
    let (mut steps, mut cycles, mut seconds, mut bad) = (0usize, 0.0, 0.0, 0usize);
    for row in seed_contacts::seed_contacts()
        .into_iter()
        .filter(|r| r.rpm == rpm)
    {
        if !only.is_empty() && !only.contains(&row.id()) {
            continue;
        }
        let c = row.contact;
        match characterize_harmonic(&c, m, &s) {
            Ok(fit) => {
                let Excitation::Harmonic(x) = fit.excitation else {
                    unreachable!("the harmonic method records a harmonic excitation")
                };
                let n = fit.history.len();
                steps += n;
                cycles += x.cycles_per_step * n as f64;
                seconds += fit.seconds;
                bad += x.steps_not_converged;
                println!(
                    "{} ball {:>2} {:<5} {:7.1} N: d {:.5} dF {:8.3} c {:8.3} | settling {:2} periodicity {:.2e} \
                     cycles/step {:.2} not converged {} {:.2} s",
                    rpm,
                    row.ball,
                    row.race,
                    c.load,
                    fit.d,
                    fit.delta_f,
                    fit.c.unwrap_or(f64::NAN),
                    x.settling_steps,
                    x.periodicity,
                    x.cycles_per_step,
                    x.steps_not_converged,
                    fit.seconds
                );
            }
            Err(err) => println!(
                "{rpm} ball {} {} {:.1} N: error {err}",
                row.ball, row.race, c.load
            ),
        }
    }
    println!(
        "total: {steps} steps, {:.2} cycles/step, {bad} steps not converged, {seconds:.1} s",
        cycles / steps.max(1) as f64
    );
}
