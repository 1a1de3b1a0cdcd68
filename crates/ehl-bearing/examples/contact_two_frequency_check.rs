//! Two-frequency transient check of a contact law: a transient EHL run with the ball's equation of
//! motion under w(t) = w0·(1 + ε·sin Ω₁t + ε·sin Ω₂t), Ω₂ = n·Ω₁, and the film force ∬p dA it
//! records against the force Q = K·δ^d + ΔF + c·δ̇ of fitted laws fed with the recorded δ(t) and
//! δ̇(t): the quasi-static law (c = 0) and harmonic laws fitted at single frequencies (in the rotor
//! band and at 0.1·ω_n, the default until 2026-11-26). Prints per law the largest and the RMS error over one period
//! of Ω₁, relative to the recorded force's swing (max − min) and in N.
//!
//! `cargo run --release -p ehl-bearing --example contact_two_frequency_check -- [RPM BALL+RACE
//! GRID R1 N EPS]`: defaults 3000 1i 129 0.002 5 0.1 (Ω₁ = 0.002·ω_n and Ω₂ = 0.01·ω_n, the ends
//! of the rotor band 100–400 Hz on the heavy inner contact; ε = 0.1 each, so the load spans
//! w0·(1 ± 0.2) as the fits). Contacts of `benches/seed_contacts.csv`; the laws are fitted on the
//! same grid; 64 steps per period of Ω₂.
use ehl_bearing::contact::{
    ball_mass, characterize_harmonic, characterize_quasi_static, ContactFit, Excitation,
    ExcitationFrequency, HarmonicExcitation, HarmonicSettings, QuasiStaticSettings,
};
use ehl_bearing::ehl::{solve_steady, EhlContact, EhlSettings, TransientSolver, TransientStep};
use ehl_bearing::material::Solid;

#[path = "../benches/common/seed_contacts.rs"]
mod seed_contacts;

/// The run's inputs: speed and contact id, grid, Ω₁/ω_n, Ω₂/Ω₁ and ε.
struct Check {
    rpm: String,
    which: String,
    grid: usize,
    r1: f64,
    n: usize,
    eps: f64,
}

fn main() -> Result<(), ehl_bearing::Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let get = |i: usize, d: &str| args.get(i).cloned().unwrap_or_else(|| d.to_string());
    let run = Check {
        rpm: get(0, "3000"),
        which: get(1, "1i"),
        grid: get(2, "129").parse().expect("grid"),
        r1: get(3, "0.002").parse().expect("Ω₁/ω_n"),
        n: get(4, "5").parse().expect("Ω₂/Ω₁, an integer"),
        eps: get(5, "0.1").parse().expect("ε"),
    };
    let c = seed_contacts::seed_contacts()
        .into_iter()
        .find(|r| r.rpm == run.rpm && r.id() == run.which)
        .expect("a contact of seed_contacts.csv")
        .contact;
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    let ehl = EhlSettings {
        grid: run.grid,
        discretization_fraction: 0.0,
        ..EhlSettings::default()
    };
    let laws = fit_laws(&c, m, ehl, &run)?;
    let Excitation::Harmonic(x) = laws[1].1.excitation else {
        unreachable!("a harmonic result")
    };
    let t0 = std::time::Instant::now();
    let (hist, settle, per1) = two_frequency_run(&c, m, ehl, &run, &x)?;
    let rec = &hist[settle..];
    let swing_d = rec
        .iter()
        .map(|s| s.approach)
        .fold(f64::NEG_INFINITY, f64::max)
        - rec.iter().map(|s| s.approach).fold(f64::INFINITY, f64::min);
    // Periodicity: the last quarter period of Ω₁ before recording against one period later.
    let periodicity = (settle - per1 / 4..settle)
        .map(|i| (hist[i + per1].approach - hist[i].approach).abs())
        .fold(0.0, f64::max)
        / swing_d;
    let not_converged = hist.iter().filter(|s| !s.converged).count();
    let fmax = rec
        .iter()
        .map(|s| s.film_force)
        .fold(f64::NEG_INFINITY, f64::max);
    let fmin = rec
        .iter()
        .map(|s| s.film_force)
        .fold(f64::INFINITY, f64::min);
    let Check {
        rpm,
        which,
        grid,
        r1,
        n,
        eps,
    } = &run;
    let omega_n = x.natural_frequency_rad_s;
    println!(
        "{rpm} rpm ball {which}, w0 {:.1} N, grid {grid}: Ω₁ = {r1}·ω_n ({:.1} Hz), Ω₂ = {}·ω_n \
         ({:.1} Hz), ε = {eps}; {} steps ({settle} settling), {:.1} s, periodicity {:.1e}, steps not \
         converged {not_converged}; recorded ∬p dA {fmin:.2}–{fmax:.2} N",
        c.load,
        r1 * omega_n / (2.0 * std::f64::consts::PI),
        *n as f64 * r1,
        *n as f64 * r1 * omega_n / (2.0 * std::f64::consts::PI),
        hist.len(),
        t0.elapsed().as_secs_f64(),
        periodicity
    );
    print_errors(&laws, rec, fmax - fmin);
    Ok(())
}

/// The laws compared: the quasi-static one and harmonic ones fitted at 0.005, Ω₁, Ω₂ and 0.1
/// times ω_n (each frequency once).
fn fit_laws(
    c: &EhlContact,
    m: f64,
    ehl: EhlSettings,
    run: &Check,
) -> Result<Vec<(String, ContactFit)>, ehl_bearing::Error> {
    let harmonic = |r: f64| {
        characterize_harmonic(
            c,
            m,
            &HarmonicSettings {
                frequency: ExcitationFrequency::FractionOfNatural(r),
                settling_periods: 4,
                ehl,
                ..HarmonicSettings::default()
            },
        )
    };
    let mut laws: Vec<(String, ContactFit)> = vec![(
        "quasi-static".into(),
        characterize_quasi_static(
            c,
            &QuasiStaticSettings {
                ehl,
                ..QuasiStaticSettings::default()
            },
        )?,
    )];
    for r in [0.005, run.r1, run.n as f64 * run.r1, 0.1] {
        if laws
            .iter()
            .any(|(name, _)| *name == format!("harmonic {r}"))
        {
            continue;
        }
        laws.push((format!("harmonic {r}"), harmonic(r)?));
    }
    Ok(laws)
}

/// The transient run under the two-frequency load, 64 steps per period of Ω₂: its steps, the
/// number of settling steps (half a period of Ω₁) and the steps per period of Ω₁.
fn two_frequency_run(
    c: &EhlContact,
    m: f64,
    ehl: EhlSettings,
    run: &Check,
    x: &HarmonicExcitation,
) -> Result<(Vec<TransientStep>, usize, usize), ehl_bearing::Error> {
    let (grid, r1, n, eps) = (run.grid, run.r1, run.n, run.eps);
    let omega_n = x.natural_frequency_rad_s;
    let (w1, w2) = (r1 * omega_n, n as f64 * r1 * omega_n);
    let per2 = 64;
    let per1 = per2 * n;
    let dt = 2.0 * std::f64::consts::PI / w2 / per2 as f64;
    let step_settings = EhlSettings {
        tol_film: 7e-5,
        coarsest: if grid >= 65 { 17 } else { ehl.coarsest },
        coarse_sweeps: if grid >= 65 { 6 } else { ehl.coarse_sweeps },
        ..ehl
    };
    let centre = solve_steady(c, &ehl)?;
    // Start at w0 with the quasi-static rate of the load's derivative at t = 0.
    let v0 = eps * c.load * (w1 + w2) / x.linearized_stiffness_n_m;
    let mut solver = TransientSolver::from_steady(c, &step_settings, centre, m, dt, v0, 20)?;
    let settle = per1 / 2;
    let mut hist = Vec::with_capacity(settle + per1);
    for k in 1..=settle + per1 {
        let t = k as f64 * dt;
        let w = c.load * (1.0 + eps * (w1 * t).sin() + eps * (w2 * t).sin());
        hist.push(solver.step(w)?);
    }
    Ok((hist, settle, per1))
}

/// Per law, its constants and its force error against the recorded film force over the
/// recorded steps (largest and RMS, in % of the recorded swing `swing`, N, and largest in N).
fn print_errors(laws: &[(String, ContactFit)], rec: &[TransientStep], swing: f64) {
    println!("| law | K N/m^d | d | ΔF N | c N·s/m | largest error % of swing | RMS error % of swing | largest error N |");
    println!("|---|---|---|---|---|---|---|---|");
    for (name, fit) in laws {
        let errs: Vec<f64> = rec
            .iter()
            .map(|s| fit.law.force_with_rate(s.approach, s.velocity).0 - s.film_force)
            .collect();
        let max = errs.iter().map(|e| e.abs()).fold(0.0, f64::max);
        let rms = (errs.iter().map(|e| e * e).sum::<f64>() / errs.len() as f64).sqrt();
        println!(
            "| {name} | {:.4e} | {:.4} | {:.2} | {} | {:.2} | {:.2} | {:.2} |",
            fit.k,
            fit.d,
            fit.delta_f,
            fit.c.map_or("—".into(), |c| format!("{c:.1}")),
            100.0 * max / swing,
            100.0 * rms / swing,
            max
        );
    }
}
