//! Characterization of one lubricated contact: the nonlinear law Q = K·δ^d + ΔF fitted to EHL
//! solutions.
//!
//! The **quasi-static method** solves a family of steady EHL problems at loads
//! w_k = w0·(1 + ε·(2k/(n−1) − 1)), k = 0…n−1, from the operating load outward, each
//! warm-started from its neighbour (from the third on, extrapolated from two), and fits the
//! law to the (approach, load) pairs with Levenberg–Marquardt ([`crate::fit`]). It is the limit of
//! the harmonic method for slow excitation, where the squeeze term vanishes.
//!
//! The **harmonic method** runs the transient EHL solver ([`crate::ehl::TransientSolver`]) with
//! the ball's equation of motion m·δ̈ = w(t) − ∬p dA under w(t) = w0·(1 + ε·sin Ωt), from a steady
//! solution at the load maximum (or at w0 near resonance), settles until the measured periodicity
//! is below its bound, records the (δ, δ̇, ∬p dA) history over the recorded periods, and fits
//! Q = K·δ^d + ΔF (+ c·δ̇) to it. See `docs/contact.md`.

use crate::budget::Deadline;
use crate::ehl::{
    solve_steady_extrapolated_within, solve_steady_from_within, solve_steady_within, EhlContact,
    EhlSettings, EhlSolution, TransientSolver, TransientStep,
};
use crate::fit::{
    fit_power_law, fit_power_law_damped, FitOptions, FittedLaw, PowerLawFit, PowerLawStdErrors,
};
use crate::Error;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Settings of the quasi-static method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct QuasiStaticSettings {
    /// Relative load amplitude ε: loads span w0·(1 ± ε) (dimensionless, in (0, 0.9]; default 0.2).
    pub amplitude: f64,
    /// Number of steady solutions n (≥ 4 for three parameters with one degree of freedom;
    /// default 7).
    pub points: usize,
    /// Steady EHL solver settings (default: 129 × 129 grid and the fixed tolerances alone,
    /// `discretization_fraction` 0: the fit differentiates the family, so its members must be
    /// converged far below the discretization error — with the discretization-following rule
    /// ΔF of a heavy outer seed contact moved by 26 %; see `docs/contact.md`).
    pub ehl: EhlSettings,
    /// Richardson estimate of the central film and the approach at w0 from the family's grid
    /// and one more steady solution at w0 on the twice finer grid ([`FilmEstimate`], in
    /// `ContactFit::film`; default false — the `contact` command turns it on). The law is the
    /// family's either way; the bearing loop does not report films and leaves it off.
    #[serde(default)]
    pub film_extrapolation: bool,
}

impl Default for QuasiStaticSettings {
    fn default() -> Self {
        QuasiStaticSettings {
            amplitude: 0.2,
            points: 7,
            ehl: EhlSettings {
                grid: 129,
                discretization_fraction: 0.0,
                ..EhlSettings::default()
            },
            film_extrapolation: false,
        }
    }
}

/// Richardson estimate of the central film and the approach at the operating load w0 (SI):
/// X = X_f + (X_f − X_c)/3 from the family's centre solution on grid n (X_c) and one on grid
/// 2n − 1 over the same domain (X_f), second order as both converge on the seed contacts (the
/// differences fall by 3.4–3.9 per halving of the mesh from 65² on; docs/contact.md, "Default
/// accuracy"). The minimum film is not extrapolated (its node moves with the grid; order
/// 1.2–2.7, docs/ehl.md §5.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FilmEstimate {
    /// The finer grid, points per side.
    pub grid_fine: usize,
    /// Extrapolated central film, m.
    pub h_central: f64,
    /// Extrapolated approach, m.
    pub approach: f64,
    /// Central film on the finer grid, m.
    pub h_central_fine: f64,
    /// Approach on the finer grid, m.
    pub approach_fine: f64,
    /// Minimum film on the finer grid, m (not extrapolated).
    pub h_min_fine: f64,
    /// Size of the extrapolation step |X_f − X_c|/3 for the central film, m: the estimated
    /// discretization error of the finer grid's value.
    pub h_central_correction: f64,
    /// The same for the approach, m.
    pub approach_correction: f64,
    /// Whether the finer solution met its tolerances.
    pub converged: bool,
    /// Wall time of the finer solution, s.
    pub seconds: f64,
}

/// One steady EHL solution of the family.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactSample {
    /// Load, N.
    pub load: f64,
    /// Approach δ = −h0, m.
    pub approach: f64,
    /// Central film, m.
    pub h_central: f64,
    /// Minimum film, m.
    pub h_min: f64,
    /// Maximum pressure, Pa.
    pub p_max: f64,
    /// Relative Reynolds residual at the end.
    pub residual: f64,
    /// Relative force-balance error.
    pub force_balance_residual: f64,
    /// Whether this steady solution met its convergence criteria.
    pub converged: bool,
}

/// The fitted law of one contact and what a user needs to judge it. SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactFit {
    /// "quasi-static" or "harmonic".
    pub method: String,
    /// Stiffness K, N/m^d.
    pub k: f64,
    /// Nonlinear index d.
    pub d: f64,
    /// Force offset ΔF (hydrodynamic lift at zero approach), N.
    pub delta_f: f64,
    /// Damping coefficient c of the extended law, N·s/m (None for the quasi-static method).
    pub c: Option<f64>,
    /// Standard errors of the parameters.
    pub std_errors: PowerLawStdErrors,
    /// Coefficient of determination of the fit.
    pub r_squared: f64,
    /// RMS residual of the fit, N.
    pub rms_residual: f64,
    /// Approaches the law was fitted on, [min, max], m.
    pub delta_range: [f64; 2],
    /// Approach at the operating load w0 from the steady EHL solution, m.
    pub approach: f64,
    /// Operating load w0, N.
    pub load: f64,
    /// Moes M at w0.
    pub moes_m: f64,
    /// Moes L.
    pub moes_l: f64,
    /// Ry/Rx.
    pub ry_over_rx: f64,
    /// How the samples were produced: the method's settings and, for the harmonic method, the
    /// excitation's measured figures (written into every result).
    pub excitation: Excitation,
    /// True when every EHL solution converged and the fit converged.
    pub converged: bool,
    /// Wall time, s.
    pub seconds: f64,
    /// The steady solutions the law was fitted to (quasi-static method), or the steady start
    /// and the steady solutions at w0·(1 ± 5 %) that give the linearized natural frequency
    /// (harmonic method).
    pub samples: Vec<ContactSample>,
    /// Time history of the harmonic method, every step (empty for the quasi-static method).
    #[serde(skip)]
    pub history: Vec<TransientStep>,
    /// Number of leading steps of `history` in the settling periods (not fitted).
    pub settling_steps: usize,
    /// Richardson estimate of h_c and δ at w0 (quasi-static method with
    /// `film_extrapolation`; None otherwise).
    pub film: Option<FilmEstimate>,
    /// The fitted law, ready for the bearing model.
    #[serde(skip)]
    pub law: FittedLaw,
}

/// First-harmonic complex stiffness of a harmonic result's recorded period,
/// k*(Ω) = F₁/δ₁ = k' + i·Ω·c_eq, with F₁ and δ₁ the first Fourier coefficients at the excitation
/// frequency of the film force ∬p dA and of the approach δ (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DynamicStiffness {
    /// Excitation frequency Ω, rad/s.
    pub frequency_rad_s: f64,
    /// Dynamic stiffness k' = Re k*, N/m.
    pub stiffness_n_m: f64,
    /// Equivalent viscous damping c_eq = Im k*/Ω, N·s/m.
    pub damping_n_s_m: f64,
    /// Amplitude of the first harmonic of δ, m.
    pub approach_amplitude_m: f64,
}

impl ContactFit {
    /// The first-harmonic complex stiffness of the recorded periods (harmonic method; None for
    /// the quasi-static method, or a recorded δ without a first harmonic). The recorded steps
    /// span whole periods at equal steps, so the discrete Fourier sums are exact for the
    /// harmonics the steps resolve.
    pub fn dynamic_stiffness(&self) -> Option<DynamicStiffness> {
        let Excitation::Harmonic(x) = self.excitation else {
            return None;
        };
        let rec = self.history.get(self.settling_steps..)?;
        let n = x.recorded_periods * x.steps_per_period;
        let rec = rec.get(..n)?;
        let omega = x.frequency_rad_s;
        let fourier = |f: &dyn Fn(&TransientStep) -> f64| {
            rec.iter().fold((0.0, 0.0), |(a, b), s| {
                let (sin, cos) = (omega * s.time).sin_cos();
                (a + f(s) * cos, b - f(s) * sin)
            })
        };
        let (fr, fi) = fourier(&|s| s.film_force);
        let (dr, di) = fourier(&|s| s.approach);
        let m = dr * dr + di * di;
        if !(m.is_finite() && m > 0.0) {
            return None;
        }
        let (kr, ki) = ((fr * dr + fi * di) / m, (fi * dr - fr * di) / m);
        Some(DynamicStiffness {
            frequency_rad_s: omega,
            stiffness_n_m: kr,
            damping_n_s_m: ki / omega,
            approach_amplitude_m: 2.0 * m.sqrt() / n as f64,
        })
    }
}

/// How a contact's samples were produced (SI), as written into every result.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "method", rename_all = "kebab-case")]
pub enum Excitation {
    /// A family of steady solutions over w0·(1 ± ε).
    QuasiStatic {
        /// Relative load amplitude ε.
        amplitude: f64,
        /// Number of steady solutions.
        points: usize,
        /// EHL grid (nodes per side).
        grid: usize,
    },
    /// A transient run under w0·(1 + ε·sin Ωt) with the ball's equation of motion.
    Harmonic(HarmonicExcitation),
}

/// The harmonic method's excitation and what was measured of it (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HarmonicExcitation {
    /// Relative load amplitude ε.
    pub amplitude: f64,
    /// Excitation frequency Ω, rad/s.
    pub frequency_rad_s: f64,
    /// Ω/ω_n (dimensionless).
    pub frequency_over_natural: f64,
    /// Linearized natural frequency ω_n = √(k/m) of the lubricated contact, rad/s.
    pub natural_frequency_rad_s: f64,
    /// The dry Hertz contact's natural frequency, rad/s.
    pub natural_frequency_hertz_rad_s: f64,
    /// Secant stiffness of the steady solutions at w0·(1 ± 5 %), N/m.
    pub linearized_stiffness_n_m: f64,
    /// Mass on the contact, kg.
    pub mass_kg: f64,
    /// The mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) (dimensionless; `law_map::mass_group`), which
    /// sets the default `step_tol_film` (7e-6·Ψ_H within [7e-8, 7e-5]; docs/contact.md, "Known
    /// limits"). 0 in results written before it was recorded.
    #[serde(default)]
    pub mass_group_psi_h: f64,
    /// Largest number of settling periods (the setting).
    pub settling_periods: usize,
    /// Time steps actually run before recording: a quarter period, then further sixteenths of a
    /// period until the periodicity is at most `periodicity_tol` or `settling_periods` are
    /// reached (quarter periods in results written by earlier versions).
    #[serde(default)]
    pub settling_steps: usize,
    /// Bound on the periodicity that ends the settling (the setting).
    #[serde(default)]
    pub periodicity_tol: f64,
    /// True when the measured periodicity is at most `periodicity_tol` (the recorded period is
    /// settled); false also when it could not be measured (no settling steps).
    #[serde(default)]
    pub settled: bool,
    /// Periods recorded and fitted.
    pub recorded_periods: usize,
    /// Time steps per period.
    pub steps_per_period: usize,
    /// Time step, s.
    pub time_step_s: f64,
    /// Time step over the transit time a_x/u_m (dimensionless).
    pub time_step_over_transit: f64,
    /// Whether the damping term c·δ̇ was fitted.
    pub damping_term: bool,
    /// EHL grid (nodes per side).
    pub grid: usize,
    /// Per-step film convergence tolerance the recorded steps used: the setting, or by default
    /// 7e-6·Ψ_H within [7e-8, 7e-5] (a fixed 7e-5 in results written before the default followed
    /// Ψ_H).
    pub step_tol_film: f64,
    /// Film tolerance of the first quarter period's steps, which are never recorded (the
    /// setting; 0 in results written before it existed, whose steps all used `step_tol_film`).
    #[serde(default)]
    pub settling_tol_film: f64,
    /// Largest number of FAS cycles per step.
    pub max_cycles_per_step: usize,
    /// Coarsest multigrid level the steps used, points per side: the setting `step_coarsest`
    /// where the grid is at least 4·(step_coarsest − 1) + 1, else the steady solutions'
    /// `ehl.coarsest` (0 in results written before it existed, whose steps used the steady
    /// solutions' coarsest level).
    #[serde(default)]
    pub step_coarsest: usize,
    /// Relaxation sweeps per visit of the steps' coarsest level as used (`step_coarse_sweeps`
    /// with `step_coarsest`, else `ehl.coarse_sweeps`; 0 in results written before it existed).
    #[serde(default)]
    pub step_coarse_sweeps: usize,
    /// Steps that stopped at the cycle limit.
    pub steps_not_converged: usize,
    /// Largest relative Reynolds residual of a step.
    pub max_step_residual: f64,
    /// Mean FAS cycles per step.
    pub cycles_per_step: f64,
    /// The periodic state's error: the largest change of δ between the last quarter period
    /// before recording and the same phase one period later (at the end of the recorded
    /// period), relative to the recorded peak-to-peak δ (NaN without settling steps).
    pub periodicity: f64,
}

fn sample(s: &EhlSolution, load: f64) -> ContactSample {
    ContactSample {
        load,
        approach: s.approach,
        h_central: s.h_central,
        h_min: s.h_min,
        p_max: s.p_max,
        residual: s.residual,
        force_balance_residual: s.force_balance_residual,
        converged: s.converged,
    }
}

/// The settings of the family's other solutions: `s` with the domain (inlet, outlet, half-width
/// in Hertz semi-axes) the centre solution was solved on, so that every solution of the family
/// has the same dimensionless domain and grid. Left unchanged for a nearly rigid centre (inlet
/// beyond 31 a_x), whose automatic domain also scales the H0 update.
fn family_domain(s: &EhlSettings, centre: &EhlSolution) -> EhlSettings {
    let f = &centre.fields;
    let (Some(&x0), Some(&x1), Some(&y1)) = (f.x.first(), f.x.last(), f.y.last()) else {
        return *s;
    };
    let inlet = -x0 / f.a_x;
    if !(inlet.is_finite() && inlet > 0.0 && inlet <= 31.0) {
        return *s;
    }
    EhlSettings {
        inlet: Some(inlet),
        outlet: x1 / f.a_x,
        half_width: Some(y1 / f.a_y),
        ..*s
    }
}

/// Characterize a contact by the quasi-static method (see the module documentation).
///
/// Errors: invalid settings or contact; an EHL solution that diverges; a family with approaches
/// ≤ 0 (light, hydrodynamic contacts, where δ^d is undefined — the error says which load). A
/// family in which some steady solution stopped short of its tolerances is returned with
/// `converged: false` and each sample's residuals.
pub fn characterize_quasi_static(
    c: &EhlContact,
    s: &QuasiStaticSettings,
) -> Result<ContactFit, Error> {
    characterize_quasi_static_within(c, s, None)
}

/// [`characterize_quasi_static`] within a wall-time budget: every EHL solve checks `deadline`
/// (None: no budget) and ends with [`crate::ehl::EhlError::TimeLimit`] once it has passed.
pub fn characterize_quasi_static_within(
    c: &EhlContact,
    s: &QuasiStaticSettings,
    deadline: Option<Deadline>,
) -> Result<ContactFit, Error> {
    let t0 = Instant::now();
    if !(s.amplitude.is_finite() && s.amplitude > 0.0 && s.amplitude <= 0.9) {
        return Err(crate::fit::FitError::Setting {
            name: "amplitude",
            value: s.amplitude.to_string(),
            expected: "0 < ε ≤ 0.9",
        }
        .into());
    }
    if !(4..=101).contains(&s.points) {
        return Err(crate::fit::FitError::Setting {
            name: "points",
            value: s.points.to_string(),
            expected: "4 to 101 steady solutions",
        }
        .into());
    }
    if s.film_extrapolation && s.ehl.grid > 513 {
        return Err(crate::fit::FitError::ExtrapolationGrid { grid: s.ehl.grid }.into());
    }
    let n = s.points;
    let loads: Vec<f64> = (0..n)
        .map(|k| c.load * (1.0 + s.amplitude * (2.0 * k as f64 / (n - 1) as f64 - 1.0)))
        .collect();
    // Solve from the operating load outward in both directions, warm-starting each solution from
    // its neighbour, or from the third on from the linear extrapolation of its two neighbours
    // (cheaper, and the discretization error varies smoothly along the family).
    let mid = n / 2;
    let mut sols: Vec<Option<EhlSolution>> = vec![None; n];
    let c_mid = EhlContact {
        load: loads[mid],
        ..*c
    };
    let centre = solve_steady_within(&c_mid, &s.ehl, deadline)?;
    // One domain for the whole family: the automatic inlet depends on the load (through Moes M,
    // with a kink at M = 1000), so a family solved on per-load domains carries a discretization
    // error that changes shape along it, which the fit absorbs into d and ΔF (measured in
    // docs/gallery.md, "Smoothness of the fitted parameters").
    let ehl = family_domain(&s.ehl, &centre);
    sols[mid] = Some(centre);
    for k in (0..mid).rev().chain(mid + 1..n) {
        let from = if k < mid { k + 1 } else { k - 1 };
        let prev = sols[from].as_ref().expect("neighbour solved first");
        let before = if k < mid { k + 2 } else { k.wrapping_sub(2) };
        let ck = EhlContact {
            load: loads[k],
            ..*c
        };
        let sol = match sols.get(before).and_then(|x| x.as_ref()) {
            Some(e) => solve_steady_extrapolated_within(
                &ck,
                &ehl,
                (prev, loads[from]),
                (e, loads[before]),
                deadline,
            )?,
            _ => solve_steady_from_within(&ck, &ehl, prev, deadline)?,
        };
        sols[k] = Some(sol);
    }
    let sols: Vec<EhlSolution> = sols.into_iter().map(|x| x.expect("all solved")).collect();
    let samples: Vec<ContactSample> = sols
        .iter()
        .zip(&loads)
        .map(|(s, &w)| sample(s, w))
        .collect();
    if let Some(bad) = samples.iter().find(|x| x.approach <= 0.0) {
        return Err(crate::fit::FitError::HydrodynamicRegime {
            approach: bad.approach,
            load: bad.load,
            time: None,
            centre_load: loads[mid],
            centre_approach: sols[mid].approach,
            amplitude: s.amplitude,
        }
        .into());
    }
    let delta: Vec<f64> = samples.iter().map(|x| x.approach).collect();
    let fit = fit_power_law(&delta, &loads, &FitOptions::default())?;
    let law = fit.law()?;
    let centre = &sols[mid];
    let film = if s.film_extrapolation {
        Some(film_estimate(&c_mid, &ehl, centre, deadline)?)
    } else {
        None
    };
    Ok(ContactFit {
        method: "quasi-static".into(),
        k: fit.k,
        d: fit.d,
        delta_f: fit.delta_f,
        c: None,
        std_errors: fit.std_errors,
        r_squared: fit.r_squared,
        rms_residual: fit.rms_residual,
        delta_range: fit.delta_range,
        approach: centre.approach,
        load: c.load,
        moes_m: centre.moes_m,
        moes_l: centre.moes_l,
        ry_over_rx: centre.ry_over_rx,
        excitation: Excitation::QuasiStatic {
            amplitude: s.amplitude,
            points: s.points,
            grid: s.ehl.grid,
        },
        converged: fit.converged && samples.iter().all(|x| x.converged),
        seconds: t0.elapsed().as_secs_f64(),
        samples,
        history: Vec::new(),
        settling_steps: 0,
        film,
        law,
    })
}

/// The [`FilmEstimate`] of a family: the contact at w0 solved on grid 2n − 1 over the centre's
/// domain, warm-started from the centre solution.
fn film_estimate(
    c: &EhlContact,
    ehl: &EhlSettings,
    centre: &EhlSolution,
    deadline: Option<Deadline>,
) -> Result<FilmEstimate, Error> {
    let t0 = Instant::now();
    let grid_fine = 2 * ehl.grid - 1;
    let fine = solve_steady_from_within(
        c,
        &EhlSettings {
            grid: grid_fine,
            ..*ehl
        },
        centre,
        deadline,
    )?;
    // (extrapolated value, size of the correction) from the fine and the coarse value.
    let rich =
        |fine: f64, coarse: f64| (fine + (fine - coarse) / 3.0, ((fine - coarse) / 3.0).abs());
    let (h_central, h_central_correction) = rich(fine.h_central, centre.h_central);
    let (approach, approach_correction) = rich(fine.approach, centre.approach);
    Ok(FilmEstimate {
        grid_fine,
        h_central,
        approach,
        h_central_fine: fine.h_central,
        approach_fine: fine.approach,
        h_min_fine: fine.h_min,
        h_central_correction,
        approach_correction,
        converged: fine.converged,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Excitation frequency Ω of the harmonic method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ExcitationFrequency {
    /// Ω as a fraction of the contact's linearized natural frequency ω_n = √(k/m), with k the
    /// secant stiffness of steady EHL solutions at w0·(1 ± 5 %) (dimensionless, > 0).
    FractionOfNatural(f64),
    /// Ω in rad/s (> 0).
    RadPerSecond(f64),
}

/// Settings of the harmonic method. Every result carries them (`ContactFit::excitation`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HarmonicSettings {
    /// Relative load amplitude ε of w(t) = w0·(1 + ε·sin Ωt) (dimensionless, in (0, 0.9];
    /// default 0.2, the quasi-static method's span, so that the two fit the same range).
    pub amplitude: f64,
    /// Excitation frequency (default 0.005·ω_n, inside the rotor band: rotor-dynamic
    /// frequencies, 100–400 Hz on the seed bearing, lie at Ω/ω_n ≈ 0.002–0.011 of the contact
    /// resonance (ω_n/2π ≈ 36–47 kHz). Over that band the fitted c changes by ≤ 1.6 % and the
    /// dynamic stiffness by ≤ 0.03 %, so a law fitted at 0.005·ω_n holds at every rotor frequency;
    /// at higher Ω the squeeze film relaxes and the law's c, d and ΔF fall — at 0.1·ω_n, the
    /// default before, c is 0.50–0.94 of its in-band value; docs/contact.md, "Contact dynamics
    /// over frequency"). The steps are per period, so the cost does not depend on Ω.
    pub frequency: ExcitationFrequency,
    /// Largest number of periods run before recording, to let the start transient decay
    /// (default 2). The run settles a quarter period, records one period, and measures the
    /// periodicity (the last settled quarter period against the same phase one period later);
    /// while it exceeds `periodicity_tol` it runs one more sixteenth of a period and moves the
    /// recorded period along, up to `settling_periods` periods of settling. 0: record from the
    /// start, periodicity not measured.
    pub settling_periods: usize,
    /// Periodicity bound that ends the settling (relative to the recorded peak-to-peak δ,
    /// ≥ 0; default 1e-3: on the seed contact a recorded period with periodicity 4.7e-3 moves
    /// the fitted d by 2.4e-4 and ΔF by 0.3 % against a run settled for two periods, one with
    /// 1.1e-4 by 2e-5 — docs/contact.md). 0 settles `settling_periods` whole periods.
    #[serde(default = "default_periodicity_tol")]
    pub periodicity_tol: f64,
    /// Periods recorded and fitted (default 1).
    pub recorded_periods: usize,
    /// Time steps per excitation period (default 64; docs/contact.md shows the effect of 32 and
    /// 128).
    pub steps_per_period: usize,
    /// Mass on the contact, kg (`None`, the default: the ball's mass given by the caller).
    pub mass: Option<f64>,
    /// Fit the extended law Q = K·δ^d + ΔF + c·δ̇ (default true); false fits Q = K·δ^d + ΔF.
    pub damping_term: bool,
    /// Largest number of FAS cycles per time step (default 20).
    pub max_cycles_per_step: usize,
    /// Per-step convergence: relative change of h_c and H0 over the last cycle. `None` (the
    /// default): it follows the contact's mass group Ψ_H ([`HarmonicSettings::step_tol_film_at`]:
    /// 7e-6·Ψ_H within [7e-8, 7e-5]), because the lag of the unconverged remainder biases c
    /// upward by about 2.8 %/Ψ_H at a fixed 7e-5 (28 % at Ψ_H = 0.1) and by 0.24–0.44 % with
    /// the rule from Ψ_H 0.1 to 10, while d and ΔF do not move (docs/contact.md, "Known
    /// limits"). `Some(t)`: every recorded step uses t, in (0, 0.01].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_tol_film: Option<f64>,
    /// Film tolerance of the steps of the first quarter period (default 1e-3, > 0), which only
    /// settle the start transient and are never recorded (the recorded period starts a quarter
    /// period in at the earliest; with `settling_periods` 0 every step uses `step_tol_film`).
    /// Their H0, and so δ, still converges in the first cycle; looser film iterations there
    /// leave the law within 5e-5 in d and 0.05 % in ΔF of fully iterated settling steps on the
    /// seed contact, in 6 % fewer cycles (docs/contact.md).
    #[serde(default = "default_settling_tol_film")]
    pub settling_tol_film: f64,
    /// Points per side of the coarsest multigrid level of the time steps, 2^k + 1 ≥ 9 (default
    /// 17; the steady solutions keep `ehl.coarsest`), used when the grid has at least two
    /// levels above it (grid ≥ 4·(step_coarsest − 1) + 1; otherwise the steps use
    /// `ehl.coarsest` and `ehl.coarse_sweeps`, as a 33²/17² pair stalls in some steps). From the
    /// converged state of the previous step the extra levels pay: on the seed contact 2.74
    /// instead of 2.92 cycles per step and ≈ 13 % less time on 129², 2.52 instead of 3.42 on 65²,
    /// with `step_coarse_sweeps` 6 (docs/contact.md).
    #[serde(default = "default_step_coarsest")]
    pub step_coarsest: usize,
    /// Relaxation sweeps per visit of the steps' coarsest level, 1 to 100 (default 6; the steady
    /// solutions keep `ehl.coarse_sweeps`; with `step_coarsest`).
    #[serde(default = "default_step_coarse_sweeps")]
    pub step_coarse_sweeps: usize,
    /// EHL settings of the steady start and of every step (default: 129 × 129 and
    /// `discretization_fraction` 0, as the quasi-static method: the secant stiffness that sets
    /// Ω is a difference of two steady solutions, and the transient starts from the centre one).
    pub ehl: EhlSettings,
}

/// The harmonic method's default Ω/ω_n (see [`HarmonicSettings::frequency`]).
pub const DEFAULT_FREQUENCY_FRACTION: f64 = 0.005;

fn default_periodicity_tol() -> f64 {
    1e-3
}

fn default_settling_tol_film() -> f64 {
    1e-3
}

fn default_step_coarsest() -> usize {
    17
}

fn default_step_coarse_sweeps() -> usize {
    6
}

impl Default for HarmonicSettings {
    fn default() -> Self {
        HarmonicSettings {
            amplitude: 0.2,
            frequency: ExcitationFrequency::FractionOfNatural(DEFAULT_FREQUENCY_FRACTION),
            settling_periods: 2,
            periodicity_tol: default_periodicity_tol(),
            recorded_periods: 1,
            steps_per_period: 64,
            mass: None,
            damping_term: true,
            max_cycles_per_step: 20,
            step_tol_film: None,
            settling_tol_film: default_settling_tol_film(),
            step_coarsest: default_step_coarsest(),
            step_coarse_sweeps: default_step_coarse_sweeps(),
            ehl: EhlSettings {
                grid: 129,
                discretization_fraction: 0.0,
                ..EhlSettings::default()
            },
        }
    }
}

/// The default per-step film tolerance per unit of the mass group Ψ_H
/// ([`HarmonicSettings::step_tol_film_at`]).
pub const STEP_TOL_FILM_PER_PSI_H: f64 = 7e-6;
/// The default per-step film tolerance's upper bound (reached at Ψ_H ≥ 10; the fixed default of
/// earlier versions).
pub const STEP_TOL_FILM_MAX: f64 = 7e-5;
/// The default per-step film tolerance's lower bound (reached at Ψ_H ≤ 0.01; ≈ 6.4 cycles per
/// step on the oils map's centre contact).
pub const STEP_TOL_FILM_MIN: f64 = 7e-8;

impl HarmonicSettings {
    /// The per-step film tolerance of a contact with mass group `psi_h` (dimensionless,
    /// [`crate::law_map::mass_group`]): the setting if given, else [`STEP_TOL_FILM_PER_PSI_H`]·Ψ_H within
    /// [[`STEP_TOL_FILM_MIN`], [`STEP_TOL_FILM_MAX`]] ([`STEP_TOL_FILM_MAX`] if Ψ_H is not a
    /// finite number > 0). The rule keeps the bias of c from the steps' unconverged remainder
    /// at 0.24–0.44 % from Ψ_H 0.1 to 10 (measured against steps iterated to 7e-8:
    /// `cargo run --release -p ehl-bearing --example harmonic_step_tolerance`).
    pub fn step_tol_film_at(&self, psi_h: f64) -> f64 {
        match self.step_tol_film {
            Some(t) => t,
            None if psi_h.is_finite() && psi_h > 0.0 => {
                (STEP_TOL_FILM_PER_PSI_H * psi_h).clamp(STEP_TOL_FILM_MIN, STEP_TOL_FILM_MAX)
            }
            None => STEP_TOL_FILM_MAX,
        }
    }
}

/// A setting of [`HarmonicSettings`] outside its range: the name the library's message uses, the
/// key a user writes in a case file's `[method_options]` (`crate::method::Method::validate`),
/// the value (with its unit where it has one) and the valid range.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SettingViolation {
    pub name: &'static str,
    pub key: &'static str,
    pub value: String,
    pub range: &'static str,
}

impl HarmonicSettings {
    /// Checks every setting; the error names the setting, its value and the valid range.
    pub fn validate(&self) -> Result<(), Error> {
        match self.violation() {
            Some(v) => Err(crate::fit::FitError::Setting {
                name: v.name,
                value: v.value,
                expected: v.range,
            }
            .into()),
            None => Ok(()),
        }
    }

    /// The first setting outside its range (the EHL settings are checked by their own
    /// validation), or None. One list for the library's [`HarmonicSettings::validate`] and the
    /// method's validation.
    pub(crate) fn violation(&self) -> Option<SettingViolation> {
        let bad = |name, key, value: String, range| {
            Some(SettingViolation {
                name,
                key,
                value,
                range,
            })
        };
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !(positive(self.amplitude) && self.amplitude <= 0.9) {
            return bad(
                "amplitude",
                "amplitude",
                self.amplitude.to_string(),
                "a relative amplitude 0 < ε ≤ 0.9",
            );
        }
        match self.frequency {
            ExcitationFrequency::FractionOfNatural(f) if !(positive(f) && f <= 10.0) => {
                return bad(
                    "frequency fraction of ω_n",
                    "frequency_fraction",
                    f.to_string(),
                    "a fraction of the natural frequency 0 < Ω/ω_n ≤ 10",
                )
            }
            ExcitationFrequency::RadPerSecond(w) if !positive(w) => {
                return bad(
                    "frequency",
                    "frequency_rad_s",
                    format!("{w} rad/s"),
                    "a finite number > 0",
                )
            }
            _ => {}
        }
        let counts = [
            (
                "settling_periods",
                self.settling_periods,
                0,
                100,
                "0 to 100",
            ),
            (
                "recorded_periods",
                self.recorded_periods,
                1,
                100,
                "1 to 100",
            ),
            (
                "steps_per_period",
                self.steps_per_period,
                8,
                4096,
                "8 to 4096",
            ),
        ];
        for (k, v, lo, hi, range) in counts {
            if !(lo..=hi).contains(&v) {
                return bad(k, k, v.to_string(), range);
            }
        }
        if !(self.periodicity_tol.is_finite() && self.periodicity_tol >= 0.0) {
            return bad(
                "periodicity_tol",
                "periodicity_tol",
                self.periodicity_tol.to_string(),
                "a finite number ≥ 0",
            );
        }
        if let Some(m) = self.mass {
            if !positive(m) {
                return bad("mass", "mass_kg", format!("{m} kg"), "a finite number > 0");
            }
        }
        if !(1..=1000).contains(&self.max_cycles_per_step) {
            let v = self.max_cycles_per_step.to_string();
            return bad("max_cycles_per_step", "max_cycles_per_step", v, "1 to 1000");
        }
        for (k, v) in [
            ("step_tol_film", self.step_tol_film),
            ("settling_tol_film", Some(self.settling_tol_film)),
        ] {
            let Some(v) = v else { continue };
            if !(positive(v) && v <= 0.01) {
                return bad(k, k, v.to_string(), "a relative film change in (0, 0.01]");
            }
        }
        let n = self.step_coarsest;
        if !((9..=1025).contains(&n) && (n - 1).is_power_of_two()) {
            return bad(
                "step_coarsest",
                "step_coarsest",
                n.to_string(),
                "a grid size 2^k + 1 from 9 to 1025",
            );
        }
        if !(1..=100).contains(&self.step_coarse_sweeps) {
            let v = self.step_coarse_sweeps.to_string();
            return bad("step_coarse_sweeps", "step_coarse_sweeps", v, "1 to 100");
        }
        None
    }
}

/// Mass of a solid ball, kg, from its diameter (m) and density (kg/m³).
pub fn ball_mass(diameter: f64, density: f64) -> f64 {
    density * std::f64::consts::PI / 6.0 * diameter.powi(3)
}

/// One run of the harmonic method: the contact, the settings, and the excitation derived from
/// the steady solutions at w0 (SI).
struct HarmonicRun<'a> {
    c: &'a EhlContact,
    s: &'a HarmonicSettings,
    /// Ball mass m, kg.
    mass: f64,
    /// Linearized stiffness k, the secant of the steady solutions at w0·(1 ± 5 %), N/m.
    k_lin: f64,
    /// Linearized natural frequency ω_n = √(k/m), rad/s.
    omega_n: f64,
    /// Excitation frequency Ω, rad/s.
    omega: f64,
    /// Time steps per period.
    n_per: usize,
    /// Time step, s.
    dt: f64,
    /// The contact's mass group Ψ_H ([`mass_group`]; NaN if its Hertz contact is undefined).
    psi_h: f64,
    /// The recorded steps' film tolerance ([`HarmonicSettings::step_tol_film_at`] at `psi_h`).
    step_tol: f64,
    deadline: Option<Deadline>,
}

/// The steady solutions of the harmonic method at w0 and w0·(1 ± 5 %), and the linearized
/// stiffness from them.
struct SteadyCentre {
    /// The solution at w0.
    centre: EhlSolution,
    /// The solutions at 0.95·w0 and 1.05·w0.
    lo: EhlSolution,
    hi: EhlSolution,
    /// Secant stiffness 0.1·w0/(δ(1.05·w0) − δ(0.95·w0)), N/m.
    k_lin: f64,
}

/// The time history of a harmonic run and how far it settled.
struct Recording {
    /// Every step, the settling ones first.
    history: Vec<TransientStep>,
    /// Steps run before the recorded periods.
    settling: usize,
    /// See [`HarmonicExcitation::periodicity`].
    periodicity: f64,
}

/// Steady start of the harmonic method at w0 (it must converge) and the linearized stiffness
/// from the solutions at w0·(1 ± 5 %), each warm-started from the one at w0.
fn steady_centre(
    c: &EhlContact,
    s: &HarmonicSettings,
    deadline: Option<Deadline>,
) -> Result<SteadyCentre, Error> {
    let centre = solve_steady_within(c, &s.ehl, deadline)?;
    if !centre.converged {
        return Err(crate::ehl::EhlError::NotConverged {
            stage: "steady start of the harmonic method",
            residual: centre.residual,
            force_residual: centre.force_balance_residual,
        }
        .into());
    }
    let side = |f: f64| {
        solve_steady_from_within(
            &EhlContact {
                load: c.load * f,
                ..*c
            },
            &s.ehl,
            &centre,
            deadline,
        )
    };
    let (lo, hi) = (side(0.95)?, side(1.05)?);
    let k_lin = 0.1 * c.load / (hi.approach - lo.approach);
    if !(k_lin.is_finite() && k_lin > 0.0) {
        return Err(crate::fit::FitError::NoElasticApproach {
            load_n: c.load,
            secant_stiffness_n_m: k_lin,
        }
        .into());
    }
    Ok(SteadyCentre {
        centre,
        lo,
        hi,
        k_lin,
    })
}

/// The steady settings of the transient steps: the film tolerance `step_tol` (the run's, from
/// [`HarmonicSettings::step_tol_film_at`]), and the steps' own coarsest level only with at least
/// two levels above it (on 33² the 33/17 pair stalls in some steps of the seed contact; there
/// the steady solutions' levels serve).
fn step_settings(s: &HarmonicSettings, step_tol: f64) -> EhlSettings {
    let mut step_settings = EhlSettings {
        tol_film: step_tol,
        ..s.ehl
    };
    if s.ehl.grid > 4 * (s.step_coarsest - 1) {
        step_settings.coarsest = s.step_coarsest;
        step_settings.coarse_sweeps = s.step_coarse_sweeps;
    }
    step_settings
}

/// The periodicity of `history` with `settling` steps before the recorded ones: the largest
/// change of δ over one period (`n_per` steps) in the last `quarter` steps before the recorded
/// ones (fewer if there are fewer settling steps), relative to the recorded peak-to-peak δ; NaN
/// without settling steps.
fn periodicity_of(history: &[TransientStep], settling: usize, quarter: usize, n_per: usize) -> f64 {
    let window = settling.min(quarter);
    if window == 0 {
        return f64::NAN;
    }
    let (lo, hi) = history[settling..]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x.approach), b.max(x.approach))
        });
    (settling - window..settling)
        .map(|i| (history[i + n_per].approach - history[i].approach).abs())
        .fold(0.0, f64::max)
        / (hi - lo)
}

impl HarmonicRun<'_> {
    /// The start at the load maximum (see `characterize_harmonic`): a steady solution under the
    /// film force w0·(1 + ε) + m·Ω²·δa, δa = ε·w0/(k − m·Ω²), solved on the physical domain and
    /// grid of the centre solution at w0 (its domain in semi-axes scaled by the ratio of the
    /// semi-axes, which grow as w^(1/3)), warm-started from `warm`, and returned with its
    /// pressure in units of w0's Hertz pressure, with the start's acceleration δ̈ = −Ω²·δa
    /// (m/s²). None when the centre's domain is automatic (nearly rigid contacts) or the
    /// solution does not converge.
    fn peak_start(&self, centre: &EhlSolution, warm: &EhlSolution) -> Option<(EhlSolution, f64)> {
        let (c, ehl) = (self.c, &self.s.ehl);
        let (amplitude, mass, omega) = (self.s.amplitude, self.mass, self.omega);
        let delta_a = amplitude * c.load / (self.k_lin - mass * omega * omega);
        let load = c.load * (1.0 + amplitude) + mass * omega * omega * delta_a;
        let domain = family_domain(ehl, centre);
        let (Some(inlet), Some(half_width)) = (domain.inlet, domain.half_width) else {
            return None;
        };
        let scale = (c.load / load).cbrt();
        let settings = EhlSettings {
            inlet: Some(inlet * scale),
            outlet: domain.outlet * scale,
            half_width: Some(half_width * scale),
            ..*ehl
        };
        let load_c = EhlContact { load, ..*c };
        let mut sol = solve_steady_from_within(&load_c, &settings, warm, self.deadline).ok()?;
        let (x0, x1) = (centre.fields.x.first()?, sol.fields.x.first()?);
        if !sol.converged
            || sol.fields.x.len() != centre.fields.x.len()
            || (x1 - x0).abs() > 1e-9 * centre.fields.a_x
        {
            return None;
        }
        let ratio = sol.p_hertz / centre.p_hertz;
        for p in &mut sol.fields.p_dimensionless {
            *p *= ratio;
        }
        Some((sol, -omega * omega * delta_a))
    }

    /// The transient solver at its start, with the phase of the load w0·(1 + ε·sin(Ωt + φ)) that
    /// matches it (φ, rad). Below 0.7·ω_n: at the load maximum (phase 0 of
    /// w(t) = w0·(1 + ε·cos Ωt)), where the periodic response is nearly at rest — δ̇ = 0 up to
    /// the squeeze film's phase lag (≈ c·Ω/k, 2 % of the rate's amplitude on the seed contact)
    /// and δ̈ = −Ω²·δa with δa = ε·w0/(k − m·Ω²) — from a steady solution under the film force
    /// w0·(1 + ε) + m·Ω²·δa on the grid of w0 ([`HarmonicRun::peak_start`]). Its start
    /// transient is ≈ 40× smaller than that of a start at w0 with the quasi-static rate (the
    /// steady film there carries no squeeze), so a fraction of a period settles it
    /// (docs/contact.md). Otherwise, or if that solution fails: the steady solution at w0 with
    /// the quasi-static rate δ̇(0) = ε·w0·Ω/k (phase 0 of w0·(1 + ε·sin Ωt)).
    fn start_solver(
        &self,
        steady: &SteadyCentre,
        step_settings: &EhlSettings,
    ) -> Result<(TransientSolver, f64), Error> {
        let (c, s) = (self.c, self.s);
        let peak = if self.omega < 0.7 * self.omega_n {
            self.peak_start(&steady.centre, &steady.hi)
        } else {
            None
        };
        let phase = if peak.is_some() {
            0.5 * std::f64::consts::PI
        } else {
            0.0
        };
        let solver = match peak {
            Some((start, acceleration)) => TransientSolver::from_steady(
                c,
                step_settings,
                start,
                self.mass,
                self.dt,
                0.0,
                s.max_cycles_per_step,
            )?
            .with_initial_acceleration(acceleration)?,
            None => TransientSolver::from_steady(
                c,
                step_settings,
                steady.centre.clone(),
                self.mass,
                self.dt,
                s.amplitude * c.load * self.omega / self.k_lin,
                s.max_cycles_per_step,
            )?,
        }
        .with_deadline(self.deadline);
        Ok((solver, phase))
    }

    /// Runs `solver` under w0·(1 + ε·sin(Ωt + `phase`)) through the settling and the recorded
    /// periods. Settling: a quarter period, then a sixteenth of a period at a time while the
    /// measured periodicity exceeds its bound. The first quarter period's steps are never
    /// recorded: they run at the settling film tolerance.
    fn run_periodic(&self, solver: &mut TransientSolver, phase: f64) -> Result<Recording, Error> {
        let (c, s, n_per) = (self.c, self.s, self.n_per);
        let quarter = n_per.div_ceil(4);
        let increment = n_per.div_ceil(16);
        let max_settling = s.settling_periods * n_per;
        let recorded = s.recorded_periods * n_per;
        let mut settling = quarter.min(max_settling);
        let loose = settling;
        let mut history = Vec::with_capacity(max_settling + recorded);
        let mut advance = |history: &mut Vec<TransientStep>, upto: usize| -> Result<(), Error> {
            for k in history.len() + 1..=upto {
                let t = k as f64 * self.dt;
                let w = c.load * (1.0 + s.amplitude * (self.omega * t + phase).sin());
                solver.set_tol_film(if k <= loose {
                    s.settling_tol_film
                } else {
                    self.step_tol
                })?;
                history.push(solver.step(w)?);
            }
            Ok(())
        };
        advance(&mut history, settling + recorded)?;
        let mut periodicity = periodicity_of(&history, settling, quarter, n_per);
        let settled = |p: f64| p <= s.periodicity_tol;
        while !settled(periodicity) && settling < max_settling {
            settling = (settling + increment).min(max_settling);
            advance(&mut history, settling + recorded)?;
            periodicity = periodicity_of(&history, settling, quarter, n_per);
        }
        Ok(Recording {
            history,
            settling,
            periodicity,
        })
    }

    /// The law Q = K·δ^d + ΔF (+ c·δ̇) fitted to the recorded steps of `rec`; an error when a
    /// recorded approach is ≤ 0 (hydrodynamic contact; `centre` is the steady solution at w0).
    fn fit_recorded(
        &self,
        rec: &Recording,
        centre: &EhlSolution,
    ) -> Result<(PowerLawFit, FittedLaw), Error> {
        let steps = &rec.history[rec.settling..];
        if let Some(bad) = steps.iter().find(|x| x.approach <= 0.0) {
            return Err(crate::fit::FitError::HydrodynamicRegime {
                approach: bad.approach,
                load: bad.load,
                time: Some(bad.time),
                centre_load: self.c.load,
                centre_approach: centre.approach,
                amplitude: self.s.amplitude,
            }
            .into());
        }
        let delta: Vec<f64> = steps.iter().map(|x| x.approach).collect();
        let rate: Vec<f64> = steps.iter().map(|x| x.velocity).collect();
        let force: Vec<f64> = steps.iter().map(|x| x.film_force).collect();
        let fit = if self.s.damping_term {
            fit_power_law_damped(&delta, &rate, &force, &FitOptions::default())?
        } else {
            fit_power_law(&delta, &force, &FitOptions::default())?
        };
        let law = fit.law()?;
        Ok((fit, law))
    }

    /// The excitation's record: the settings, the frequencies (`omega_n_hertz` the dry Hertz
    /// contact's natural frequency, rad/s), the steps' settings as used, `dtt` the dimensionless
    /// time step, and what was measured of the run `rec`.
    fn excitation(
        &self,
        omega_n_hertz: f64,
        step_settings: &EhlSettings,
        dtt: f64,
        rec: &Recording,
    ) -> HarmonicExcitation {
        let s = self.s;
        let history = &rec.history;
        let not_converged = history.iter().filter(|x| !x.converged).count();
        let max_res = history.iter().map(|x| x.residual).fold(0.0, f64::max);
        let cycles: usize = history.iter().map(|x| x.cycles).sum();
        HarmonicExcitation {
            amplitude: s.amplitude,
            frequency_rad_s: self.omega,
            frequency_over_natural: self.omega / self.omega_n,
            natural_frequency_rad_s: self.omega_n,
            natural_frequency_hertz_rad_s: omega_n_hertz,
            linearized_stiffness_n_m: self.k_lin,
            mass_kg: self.mass,
            mass_group_psi_h: self.psi_h,
            settling_periods: s.settling_periods,
            settling_steps: rec.settling,
            periodicity_tol: s.periodicity_tol,
            settled: rec.periodicity <= s.periodicity_tol,
            recorded_periods: s.recorded_periods,
            steps_per_period: self.n_per,
            time_step_s: self.dt,
            time_step_over_transit: dtt,
            damping_term: s.damping_term,
            grid: s.ehl.grid,
            step_tol_film: self.step_tol,
            settling_tol_film: s.settling_tol_film,
            max_cycles_per_step: s.max_cycles_per_step,
            step_coarsest: step_settings.coarsest,
            step_coarse_sweeps: step_settings.coarse_sweeps,
            steps_not_converged: not_converged,
            max_step_residual: max_res,
            cycles_per_step: cycles as f64 / history.len() as f64,
            periodicity: rec.periodicity,
        }
    }
}

/// The harmonic law's mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) (dimensionless) from the Hertz
/// semi-width b along the rolling direction (m) and deflection δ_H (m) at the load w0 (N), the
/// sum velocity u_s (m/s) and the mass m (kg): the natural frequency of the mass on the Hertz
/// secant stiffness times the time the oil takes to cross b (docs/law_map.md §7).
pub(crate) fn mass_group(b: f64, delta_h: f64, w0: f64, u_s: f64, mass: f64) -> f64 {
    b / u_s * (w0 / (delta_h * mass)).sqrt()
}

/// Characterize a contact by the harmonic method (see the module documentation). `ball_mass` is
/// the mass of the ball in kg (used unless `s.mass` overrides it).
///
/// Errors: invalid settings or contact; a steady start that does not converge; a step that
/// diverges; approaches ≤ 0 in the recorded history (hydrodynamic contact). Steps that stop at
/// the cycle limit are counted in `excitation.steps_not_converged` and make the result
/// `converged: false`.
pub fn characterize_harmonic(
    c: &EhlContact,
    ball_mass: f64,
    s: &HarmonicSettings,
) -> Result<ContactFit, Error> {
    characterize_harmonic_within(c, ball_mass, s, None)
}

/// [`characterize_harmonic`] within a wall-time budget: every EHL solve and every transient
/// step checks `deadline` (None: no budget) and ends with [`crate::ehl::EhlError::TimeLimit`]
/// once it has passed.
pub fn characterize_harmonic_within(
    c: &EhlContact,
    ball_mass: f64,
    s: &HarmonicSettings,
    deadline: Option<Deadline>,
) -> Result<ContactFit, Error> {
    let t0 = Instant::now();
    s.validate()?;
    let mass = s.mass.unwrap_or(ball_mass);
    if !(mass.is_finite() && mass > 0.0) {
        return Err(crate::fit::FitError::BallMass { mass_kg: mass }.into());
    }
    let steady = steady_centre(c, s, deadline)?;
    let (centre, k_lin) = (&steady.centre, steady.k_lin);
    let omega_n = (k_lin / mass).sqrt();
    let omega_n_hertz = (1.5 * c.load / (mass * centre.approach_hertz)).sqrt();
    let omega = match s.frequency {
        ExcitationFrequency::FractionOfNatural(f) => f * omega_n,
        ExcitationFrequency::RadPerSecond(w) => w,
    };
    let period = 2.0 * std::f64::consts::PI / omega;
    let n_per = s.steps_per_period;
    let psi_h = crate::hertz::HertzGeometry::new(c.rx, c.ry, c.e_reduced).map_or(f64::NAN, |g| {
        let h = g.contact(c.load);
        mass_group(h.semi_minor, h.deflection, c.load, c.sum_velocity, mass)
    });
    let run = HarmonicRun {
        c,
        s,
        mass,
        k_lin,
        omega_n,
        omega,
        n_per,
        dt: period / n_per as f64,
        psi_h,
        step_tol: s.step_tol_film_at(psi_h),
        deadline,
    };
    let samples = vec![
        sample(&steady.lo, 0.95 * c.load),
        sample(centre, c.load),
        sample(&steady.hi, 1.05 * c.load),
    ];
    let step_settings = step_settings(s, run.step_tol);
    let (mut solver, phase) = run.start_solver(&steady, &step_settings)?;
    let rec = run.run_periodic(&mut solver, phase)?;
    let (fit, law) = run.fit_recorded(&rec, centre)?;
    let excitation = run.excitation(
        omega_n_hertz,
        &step_settings,
        solver.dt_dimensionless(),
        &rec,
    );
    Ok(ContactFit {
        method: "harmonic".into(),
        k: fit.k,
        d: fit.d,
        delta_f: fit.delta_f,
        c: fit.c,
        std_errors: fit.std_errors,
        r_squared: fit.r_squared,
        rms_residual: fit.rms_residual,
        delta_range: fit.delta_range,
        approach: centre.approach,
        load: c.load,
        moes_m: centre.moes_m,
        moes_l: centre.moes_l,
        ry_over_rx: centre.ry_over_rx,
        converged: fit.converged && excitation.steps_not_converged == 0,
        excitation: Excitation::Harmonic(excitation),
        seconds: t0.elapsed().as_secs_f64(),
        samples,
        history: rec.history,
        settling_steps: rec.settling,
        film: None,
        law,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default step tolerance is 7e-6·Ψ_H within [7e-8, 7e-5]; a setting overrides it; a
    /// mass group that is not a finite number > 0 gives the upper bound.
    #[test]
    fn the_default_step_tolerance_follows_the_mass_group() {
        let d = HarmonicSettings::default();
        assert_eq!(d.step_tol_film, None);
        for (psi, tol) in [
            (1.0, 7e-6),
            (0.1, 7e-7),
            (10.0, 7e-5),
            (100.0, 7e-5),
            (1e-3, 7e-8),
            (f64::NAN, 7e-5),
            (0.0, 7e-5),
        ] {
            let t = d.step_tol_film_at(psi);
            assert!((t - tol).abs() <= 1e-12 * tol, "Ψ_H {psi}: {t} ≠ {tol}");
        }
        let fixed = HarmonicSettings {
            step_tol_film: Some(2e-5),
            ..d
        };
        assert_eq!(fixed.step_tol_film_at(0.1), 2e-5);
    }
}
