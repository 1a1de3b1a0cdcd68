//! Figures of one characterized contact: the force–approach law with its residuals
//! (`force_approach`) and the harmonic method's time history (`time_history`).

use super::{stacked_charts_with, Series, SeriesStyle, StackedOptions};
use anyhow::Result;
use ehl_bearing::contact::ContactFit;
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::ContactLaw;
use std::path::Path;

/// The case in a title: load, Hertz semi-axes and pressure, Moes parameters.
fn case_tag(f: &ContactFit, c: &EhlContact) -> String {
    let hz = ehl_bearing::hertz::HertzGeometry::new(c.rx, c.ry, c.e_reduced)
        .map(|g| g.contact(c.load))
        .ok();
    match hz {
        Some(h) => format!(
            "w0 = {:.1} N, u_s = {:.2} m/s, a = {:.3} mm, b = {:.3} mm, p_h = {:.2} GPa (M = {:.0}, L = {:.1})",
            c.load,
            c.sum_velocity,
            h.semi_major * 1e3,
            h.semi_minor * 1e3,
            h.max_pressure * 1e-9,
            f.moes_m,
            f.moes_l
        ),
        None => format!("w0 = {:.1} N (M = {:.0}, L = {:.1})", c.load, f.moes_m, f.moes_l),
    }
}

/// Q against δ (top) and the fit residual (bottom): the EHL samples, the fitted law drawn over
/// the sampled approaches and, marked as such, 15 % of the span beyond them, and the dry Hertz
/// law of the same contact. K, d, ΔF with their standard errors are in the legend.
pub fn force_approach(f: &ContactFit, c: &EhlContact, dir: &Path) -> Result<()> {
    let um = 1e6;
    let [lo, hi] = f.delta_range;
    let span = hi - lo;
    let grid = |a: f64, b: f64, n: usize| -> Vec<f64> {
        (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
    };
    let inside = grid(lo, hi, 120);
    let below = grid(lo - 0.15 * span, lo, 20);
    let above = grid(hi, hi + 0.15 * span, 20);
    let hertz = ehl_bearing::hertz::HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
    let damping = f.c.unwrap_or(0.0);
    // (approach, rate, force) of the fitted data.
    let data: Vec<(f64, f64, f64)> = if f.method == "harmonic" {
        f.history[f.settling_steps..]
            .iter()
            .map(|s| (s.approach, s.velocity, s.film_force))
            .collect()
    } else {
        f.samples
            .iter()
            .map(|s| (s.approach, 0.0, s.load))
            .collect()
    };
    let law = |x: &[f64]| -> Vec<f64> { x.iter().map(|&d| f.law.force(d).0).collect() };
    let to_um = |x: &[f64]| -> Vec<f64> { x.iter().map(|v| v * um).collect() };
    let se = &f.std_errors;
    let fit_label = format!(
        "fit Q = K·δ^d + ΔF{}: K = {:.4e} ± {:.1e} N/m^d, d = {:.4} ± {:.4}, ΔF = {:.2} ± {:.2} N",
        if f.c.is_some() { " (δ̇ = 0)" } else { "" },
        f.k,
        se.k,
        f.d,
        se.d,
        f.delta_f,
        se.delta_f
    );
    let mut extrapolated = Series::line(
        "fit extrapolated beyond the samples (±15 % of their span)",
        to_um(&below),
        law(&below),
    );
    // One series, broken between the two sides by a NaN.
    extrapolated.x.push(f64::NAN);
    extrapolated.y.push(f64::NAN);
    extrapolated.x.extend(to_um(&above));
    extrapolated.y.extend(law(&above));
    extrapolated.style = SeriesStyle::Dashed;
    let all: Vec<f64> = below.iter().chain(&inside).chain(&above).copied().collect();
    let top = vec![
        Series::markers(
            if f.method == "harmonic" {
                "transient EHL, film force ∬p dA (recorded)"
            } else {
                "EHL steady solutions"
            },
            data.iter().map(|d| d.0 * um).collect(),
            data.iter().map(|d| d.2).collect(),
        ),
        Series::line(fit_label, to_um(&inside), law(&inside)),
        extrapolated,
        Series::line(
            "dry Hertz K_H·δ^1.5",
            to_um(&all),
            all.iter().map(|&x| hertz.load_at(x)).collect(),
        ),
    ];
    let residual = Series::markers(
        format!(
            "EHL − fit{} (rms {:.3} N, R² = {:.7})",
            if f.c.is_some() { " (with c·δ̇)" } else { "" },
            f.rms_residual,
            f.r_squared
        ),
        data.iter().map(|d| d.0 * um).collect(),
        data.iter()
            .map(|d| d.2 - f.law.force(d.0).0 - damping * d.1)
            .collect(),
    );
    let zero = Series::line(
        "",
        to_um(&[lo - 0.15 * span, hi + 0.15 * span]),
        vec![0.0, 0.0],
    );
    stacked_charts_with(
        &dir.join("force_approach"),
        &format!("Contact law, {} method — {}", f.method, case_tag(f, c)),
        "approach δ (µm)",
        &[
            ("contact force Q (N)".to_string(), top),
            ("residual (N)".to_string(), vec![residual, zero]),
        ],
        &StackedOptions {
            heights: vec![2.0, 1.0],
            ..StackedOptions::default()
        },
    )
}

/// δ(t) above Q(t) (film force and external load) of the harmonic method.
pub fn time_history(f: &ContactFit, c: &EhlContact, dir: &Path) -> Result<()> {
    let t: Vec<f64> = f.history.iter().map(|s| s.time * 1e3).collect();
    let panels = vec![
        (
            "approach δ (µm)".to_string(),
            vec![Series::line(
                "δ(t)",
                t.clone(),
                f.history.iter().map(|s| s.approach * 1e6).collect(),
            )],
        ),
        (
            "force (N)".to_string(),
            vec![
                Series::line(
                    "film force ∬p dA",
                    t.clone(),
                    f.history.iter().map(|s| s.film_force).collect(),
                ),
                Series::line(
                    "external load w(t)",
                    t,
                    f.history.iter().map(|s| s.load).collect(),
                ),
            ],
        ),
    ];
    let periods = match &f.excitation {
        ehl_bearing::contact::Excitation::Harmonic(h) => (h.settling_steps, h.recorded_periods),
        _ => (0, 0),
    };
    stacked_charts_with(
        &dir.join("time_history"),
        &format!(
            "Harmonic excitation, {} + {} — {}",
            count(periods.0, "settling step"),
            count(periods.1, "recorded period"),
            case_tag(f, c)
        ),
        "time t (ms)",
        &panels,
        &StackedOptions::default(),
    )
}

/// `n` and `noun`, plural unless n = 1: "1 recorded period", "24 settling steps".
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("{n} {noun}")
    } else {
        format!("{n} {noun}s")
    }
}
