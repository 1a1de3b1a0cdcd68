//! Characterization of one lubricated contact: the nonlinear law Q = K·δ^d + ΔF fitted to EHL
//! solutions.
//!
//! The **quasi-static method** solves a family of steady EHL problems at loads
//! w_k = w0·(1 + ε·(2k/(n−1) − 1)), k = 0…n−1, each warm-started from its neighbour, and fits the
//! law to the (approach, load) pairs with Levenberg–Marquardt ([`crate::fit`]). It is the limit of
//! the harmonic method (transient EHL under w0·(1 + ε·sin Ωt)) for slow excitation, where the
//! squeeze term vanishes. The harmonic method is not implemented yet.

use crate::ehl::{solve_steady, solve_steady_from, EhlContact, EhlSettings, EhlSolution};
use crate::fit::{fit_power_law, FitOptions, FittedLaw, PowerLawStdErrors};
use crate::Error;
use serde::Serialize;
use std::time::Instant;

/// Settings of the quasi-static method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QuasiStaticSettings {
    /// Relative load amplitude ε: loads span w0·(1 ± ε) (dimensionless, in (0, 0.9]; default 0.2).
    pub amplitude: f64,
    /// Number of steady solutions n (≥ 4 for three parameters with one degree of freedom;
    /// default 7).
    pub points: usize,
    /// Steady EHL solver settings (default: 129 × 129 grid, see `docs/contact.md`).
    pub ehl: EhlSettings,
}

impl Default for QuasiStaticSettings {
    fn default() -> Self {
        QuasiStaticSettings {
            amplitude: 0.2,
            points: 7,
            ehl: EhlSettings {
                grid: 129,
                ..EhlSettings::default()
            },
        }
    }
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
    /// Method settings (amplitude, points, grid, …) as written into every result.
    pub excitation: serde_json::Value,
    /// True when every EHL solution converged and the fit converged.
    pub converged: bool,
    /// Wall time, s.
    pub seconds: f64,
    /// The steady solutions the law was fitted to.
    pub samples: Vec<ContactSample>,
    /// The fitted law, ready for the bearing model.
    #[serde(skip)]
    pub law: FittedLaw,
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
    let t0 = Instant::now();
    if !(s.amplitude.is_finite() && s.amplitude > 0.0 && s.amplitude <= 0.9) {
        return Err(crate::fit::FitError::Invalid(format!(
            "amplitude = {}: expected 0 < ε ≤ 0.9",
            s.amplitude
        ))
        .into());
    }
    if !(4..=101).contains(&s.points) {
        return Err(crate::fit::FitError::Invalid(format!(
            "points = {}: expected 4 to 101 steady solutions",
            s.points
        ))
        .into());
    }
    let n = s.points;
    let loads: Vec<f64> = (0..n)
        .map(|k| c.load * (1.0 + s.amplitude * (2.0 * k as f64 / (n - 1) as f64 - 1.0)))
        .collect();
    // Solve from the operating load outward in both directions, warm-starting each solution from
    // its neighbour (cheaper, and the discretization error varies smoothly along the family).
    let mid = n / 2;
    let mut sols: Vec<Option<EhlSolution>> = vec![None; n];
    let centre = solve_steady(
        &EhlContact {
            load: loads[mid],
            ..*c
        },
        &s.ehl,
    )?;
    sols[mid] = Some(centre);
    for k in (0..mid).rev().chain(mid + 1..n) {
        let from = if k < mid { k + 1 } else { k - 1 };
        let prev = sols[from].as_ref().expect("neighbour solved first");
        let sol = solve_steady_from(
            &EhlContact {
                load: loads[k],
                ..*c
            },
            &s.ehl,
            prev,
        )?;
        sols[k] = Some(sol);
    }
    let sols: Vec<EhlSolution> = sols.into_iter().map(|x| x.expect("all solved")).collect();
    let samples: Vec<ContactSample> = sols
        .iter()
        .zip(&loads)
        .map(|(s, &w)| sample(s, w))
        .collect();
    if let Some(bad) = samples.iter().find(|x| x.approach <= 0.0) {
        return Err(crate::fit::FitError::Invalid(format!(
            "the EHL approach is {:.3e} m (≤ 0) at load {:.4} N: the contact runs in the \
             hydrodynamic regime, where Q = K·δ^d + ΔF is not defined; raise the load or lower \
             the amplitude",
            bad.approach, bad.load
        ))
        .into());
    }
    let delta: Vec<f64> = samples.iter().map(|x| x.approach).collect();
    let fit = fit_power_law(&delta, &loads, &FitOptions::default())?;
    let law = fit.law()?;
    let centre = &sols[mid];
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
        excitation: serde_json::json!({
            "method": "quasi-static",
            "amplitude": s.amplitude,
            "points": s.points,
            "grid": s.ehl.grid,
        }),
        converged: fit.converged && samples.iter().all(|x| x.converged),
        seconds: t0.elapsed().as_secs_f64(),
        samples,
        law,
    })
}
