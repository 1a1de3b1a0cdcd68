//! Where the smooth-surface, isothermal, fully flooded EHL model stands: per contact the central
//! and minimum film, the film parameter Λ, the estimated film reduction by inlet shear heating,
//! and the bearing's viscosity ratio κ of ISO 281. Estimates of the model's error, reported beside
//! its results; they change no force law.
//!
//! The formulas (docs/lubricant.md):
//! - film: Hamrock & Dowson (1977) central and minimum film for elliptical contacts
//!   ([`crate::ehl::formulas`]), at each contact's equilibrium load, curvature radii, sum velocity
//!   and Hertz ellipticity k = a/b; scatter against full numerical solutions ±10–20 %.
//! - Λ = h_min/σ with the composite roughness σ = √(Rq_ball² + Rq_race²): Λ < 1.5 is reported
//!   as mixed lubrication (the smooth-surface model overestimates the film and the law's ΔF), Λ <
//!   1 as a contact where asperities carry load and the smooth-surface model does not hold.
//! - κ = ν/ν1, ν the operating kinematic viscosity, ν1 the rated viscosity of ISO 281 (mm²/s, n
//!   the relative ring speed in rpm, d_m the pitch diameter in mm):
//!   ν1 = 45000·n^(−0.83)·d_m^(−0.5) for n < 1000 rpm, ν1 = 4500·n^(−0.5)·d_m^(−0.5) otherwise.
//! - inlet shear heating: the thermal reduction factor of Gupta, Cheng, Zhu, Forster & Schrand
//!   (1992, "Viscoelastic effects in MIL-L-7808-type lubricant, Part I", Tribology Transactions
//!   35:269), in the form reproduced by Kiekbusch et al. (Lubricants 2023, 11, 369, eqs. 12–14,
//!   where it is credited to Aramaki, Cheng & Zhu 1992):
//!   φ_T = [1 − 13.2·(p_h/E′)·L^0.42] / [1 + 0.213·(1 + 2.23·s^0.83)·L^0.64],
//!   L = (−∂η/∂T)·u²/k_f, u the mean entrainment velocity (u1 + u2)/2, k_f the oil's thermal
//!   conductivity, s the slide-to-roll ratio (0 here: the bearing model's contacts roll without
//!   slip), p_h the maximum Hertz pressure. A curve fit to thermal EHL solutions; its source gives
//!   no accuracy we could read. The reduction reported is 1 − φ_T; above
//!   [`THERMAL_WARN`] it is a warning.
//! - ring temperatures (`operating.inner_ring_temperature_c`, `outer_ring_temperature_c`): each
//!   raceway's film, Λ and thermal reduction use the described oil's constants at its ring's
//!   temperature, as do its contacts' EHL solves and laws ([`Case::lubricant_of`]); κ stays at
//!   the oil of `operating.temperature_c`.
//! - starvation (when `operating.inlet_meniscus_distance_mm` describes the oil supply): the
//!   starvation correlation of Hamrock & Dowson ("Isothermal elastohydrodynamic lubrication of
//!   point contacts, Part IV — Starvation results", ASME J. Lubr. Technol. 99 (1977) 15–23) with
//!   m = x_meniscus/b the meniscus distance from the contact centre in Hertz semi-widths along the
//!   rolling direction: the flooded–starved boundary m* = 1 + 3.06·[(Rx/b)²·h_c/Rx]^0.58 for the
//!   central film and 1 + 3.34·[(Rx/b)²·h_min/Rx]^0.56 for the minimum film, and below it
//!   h_s = h·((m − 1)/(m* − 1))^0.29 (central) and ^0.25 (minimum). A fit to starved EHL
//!   solutions; checked here against this crate's own steady solver with the inlet boundary at m
//!   (docs/lubricant.md §3: minimum films within 0.03 of the flooded film for m ≥ 1.5; at
//!   m ≤ 1.25 the solver reduces more). The reduction reported is that of the minimum film; above [`STARVATION_WARN`] it
//!   is a warning, at m ≤ 1 (the meniscus inside the Hertzian contact) the contact is flagged.

use crate::bearing::{ContactState, Race};
use crate::case::Case;
pub use crate::case::{RingOils, Roughness};
use crate::ehl::formulas::{hamrock_dowson_central, hamrock_dowson_min};
use crate::material::reduced_modulus;
use serde::{Deserialize, Serialize};

/// Λ below which a contact is reported as in mixed lubrication (warning).
pub const LAMBDA_WARN: f64 = 1.5;
/// Λ below which the smooth-surface model is flagged as not holding.
pub const LAMBDA_INVALID: f64 = 1.0;
/// Thermal film reduction above which a warning is given (fraction).
pub const THERMAL_WARN: f64 = 0.10;
/// Starvation film reduction above which a warning is given (fraction).
pub const STARVATION_WARN: f64 = 0.10;

/// Hamrock & Dowson's (1977) flooded–starved boundary m* (dimensionless inlet distance, in Hertz
/// semi-widths b along the rolling direction) for the flooded film `h_over_rx` = h/Rx of a
/// contact with `rx_over_b` = Rx/b: m* = 1 + 3.06·[(Rx/b)²·h/Rx]^0.58 for the central film
/// (`central`), 1 + 3.34·[(Rx/b)²·h/Rx]^0.56 for the minimum film.
pub fn starvation_boundary(h_over_rx: f64, rx_over_b: f64, central: bool) -> f64 {
    let x = rx_over_b * rx_over_b * h_over_rx;
    if central {
        1.0 + 3.06 * x.powf(0.58)
    } else {
        1.0 + 3.34 * x.powf(0.56)
    }
}

/// Hamrock & Dowson's (1977) starved-to-flooded film ratio at the dimensionless inlet distance
/// `m` (meniscus distance from the contact centre over the Hertz semi-width b) for the boundary
/// `m_star` ([`starvation_boundary`]): ((m − 1)/(m* − 1))^0.29 for the central film (`central`),
/// ^0.25 for the minimum film, 1 at m ≥ m* (flooded) and 0 at m ≤ 1 (the meniscus inside the
/// contact: no film is formed by the correlation).
pub fn starvation_factor(m: f64, m_star: f64, central: bool) -> f64 {
    if m >= m_star {
        1.0
    } else if m <= 1.0 {
        0.0
    } else {
        ((m - 1.0) / (m_star - 1.0)).powf(if central { 0.29 } else { 0.25 })
    }
}

/// A contact's starvation figures ([`starvation_boundary`], [`starvation_factor`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Starvation {
    /// Dimensionless inlet distance m = x_meniscus/b.
    pub inlet_distance_ratio: f64,
    /// Flooded–starved boundary of the minimum film m*.
    pub boundary_ratio: f64,
    /// Estimated reduction of the minimum film, 1 − h_min,s/h_min (fraction).
    pub reduction: f64,
    /// Estimated reduction of the central film (fraction).
    pub central_reduction: f64,
    /// Starved minimum film, m.
    pub min_film_m: f64,
}

/// The starvation figures of a contact with flooded films `hc`, `hmin` (m), curvature radius
/// `rx` (m) and Hertz semi-width along the rolling direction `b` (m), for the meniscus at
/// `meniscus_m` from its centre.
pub fn starvation(hc: f64, hmin: f64, rx: f64, b: f64, meniscus_m: f64) -> Starvation {
    let m = meniscus_m / b;
    let mc = starvation_boundary(hc / rx, rx / b, true);
    let mm = starvation_boundary(hmin / rx, rx / b, false);
    let fm = starvation_factor(m, mm, false);
    Starvation {
        inlet_distance_ratio: m,
        boundary_ratio: mm,
        reduction: 1.0 - fm,
        central_reduction: 1.0 - starvation_factor(m, mc, true),
        min_film_m: hmin * fm,
    }
}

/// Composite roughness σ = √(Rq1² + Rq2²), in the unit of its arguments.
pub fn composite_roughness(rq1: f64, rq2: f64) -> f64 {
    (rq1 * rq1 + rq2 * rq2).sqrt()
}

/// ISO 281 rated viscosity ν1, mm²/s, for a relative speed `n_rpm` > 0 rpm and pitch diameter
/// `dm_mm` mm (None for n ≤ 0, where it is undefined).
pub fn rated_viscosity_mm2_s(n_rpm: f64, dm_mm: f64) -> Option<f64> {
    if !(n_rpm > 0.0 && dm_mm > 0.0) {
        return None;
    }
    Some(if n_rpm < 1000.0 {
        45000.0 * n_rpm.powf(-0.83) * dm_mm.powf(-0.5)
    } else {
        4500.0 * n_rpm.powf(-0.5) * dm_mm.powf(-0.5)
    })
}

/// Thermal loading parameter L = (−∂η/∂T)·u²/k_f (dimensionless): `deta_dt` = −∂η/∂T in
/// Pa·s/K, `u` the mean entrainment velocity in m/s, `k_f` the oil's thermal conductivity in
/// W/(m·K).
pub fn thermal_loading(deta_dt: f64, u: f64, k_f: f64) -> f64 {
    deta_dt * u * u / k_f
}

/// Gupta et al. (1992) thermal reduction factor φ_T (dimensionless, ≤ 1) for maximum Hertz
/// pressure `p_h` Pa, reduced modulus `e_reduced` Pa (E′), thermal loading `l` and slide-to-roll
/// ratio `s`.
pub fn thermal_factor(p_h: f64, e_reduced: f64, l: f64, s: f64) -> f64 {
    (1.0 - 13.2 * (p_h / e_reduced) * l.powf(0.42))
        / (1.0 + 0.213 * (1.0 + 2.23 * s.abs().powf(0.83)) * l.powf(0.64))
}

/// One contact's film and validity figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactFilm {
    /// Ball index.
    pub ball: usize,
    /// `inner` or `outer`.
    pub race: String,
    /// Equilibrium load Q, N.
    pub load_n: f64,
    /// Maximum Hertz pressure, Pa.
    pub max_pressure_pa: f64,
    /// Mean entrainment velocity (u1 + u2)/2, m/s.
    pub entrainment_velocity_m_s: f64,
    /// Hertz ellipticity k = a/b (transverse over rolling semi-axis).
    pub ellipticity: f64,
    /// Isothermal central film (Hamrock–Dowson), m (null: unloaded).
    pub central_film_m: Option<f64>,
    /// Isothermal minimum film (Hamrock–Dowson), m (null: unloaded).
    pub min_film_m: Option<f64>,
    /// Film parameter Λ = h_min/σ (null: no roughness given or unloaded).
    pub lambda: Option<f64>,
    /// Thermal loading parameter L (null: the oil's temperature–viscosity coefficient is unknown).
    pub thermal_loading: Option<f64>,
    /// Estimated film reduction by inlet shear heating, 1 − φ_T (fraction).
    pub thermal_reduction: Option<f64>,
    /// Minimum film with the thermal reduction applied, m (an estimate beside the isothermal film).
    pub min_film_thermal_m: Option<f64>,
    /// Starvation figures (absent: no oil supply described, i.e. fully flooded, or no film).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub starvation: Option<Starvation>,
    /// Where the films come from: `ehl-solution` (a converged steady EHL solution of the contact)
    /// or `hamrock-dowson-1977` (the formula); empty when unloaded.
    #[serde(default)]
    pub film_source: String,
    /// The oil temperature these figures are at, °C: the contact's ring temperature (absent
    /// when no ring temperatures are given: the oil's `operating.temperature_c`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oil_temperature_c: Option<f64>,
    /// What the figures say about the model at this contact (empty: nothing to flag).
    pub flags: Vec<String>,
}

/// The bearing's lubrication figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LubricationReport {
    /// The described oil's derived constants and their sources (null: given as constants).
    pub oil: Option<crate::oil::OilProperties>,
    /// The oil's constants at the ring temperatures (absent when not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring_oils: Option<RingOils>,
    /// η0 used, Pa·s.
    pub viscosity_pa_s: f64,
    /// α used, 1/Pa.
    pub pressure_viscosity_1_pa: f64,
    /// ρ0 used, kg/m³.
    pub density_kg_m3: f64,
    /// Operating kinematic viscosity ν = η0/ρ0, mm²/s.
    pub kinematic_viscosity_mm2_s: f64,
    /// Relative ring speed n, rpm.
    pub relative_speed_rpm: f64,
    /// ISO 281 rated viscosity ν1, mm²/s (null at rest).
    pub rated_viscosity_mm2_s: Option<f64>,
    /// Viscosity ratio κ = ν/ν1 (null at rest).
    pub kappa: Option<f64>,
    /// Surface roughness (null: not given).
    pub roughness: Option<Roughness>,
    /// Composite roughness σ, m (null: not given).
    pub composite_roughness_m: Option<f64>,
    /// Where the films come from (per contact: `film_source`).
    pub film_formula: String,
    /// Per-contact figures, in the order given.
    pub contacts: Vec<ContactFilm>,
    /// Smallest Λ of the loaded contacts.
    pub min_lambda: Option<f64>,
    /// Largest thermal film reduction of the loaded contacts (fraction).
    pub max_thermal_reduction: Option<f64>,
    /// The oil supply: distance from each contact's centre to the upstream meniscus, m (absent:
    /// fully flooded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inlet_meniscus_distance_m: Option<f64>,
    /// Largest starvation reduction of the minimum film over the loaded contacts (absent: no
    /// oil supply described).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_starvation_reduction: Option<f64>,
    /// Warnings (Λ < 1.5, thermal reduction above 10 %, κ < 1), each naming its contacts.
    pub warnings: Vec<String>,
    /// What is not estimated, and why.
    pub notes: Vec<String>,
}

impl LubricationReport {
    /// The figures of contact (`ball`, `race`: `inner` or `outer`), if assessed.
    pub fn contact(&self, ball: usize, race: &str) -> Option<&ContactFilm> {
        self.contacts
            .iter()
            .find(|c| c.ball == ball && c.race == race)
    }
}

fn race_name(r: Race) -> &'static str {
    match r {
        Race::Inner => "inner",
        Race::Outer => "outer",
    }
}

/// Whether the case gives any of the inputs this report is about (a described oil or roughness):
/// the outputs carry the report only then, so that results of cases without them are unchanged.
pub fn wanted(case: &Case) -> bool {
    case.oil.is_some() || case.roughness.is_some() || case.inlet_meniscus_distance_m.is_some()
}

/// The lubrication figures of `case` at the contact states `contacts` (ball index, race, state).
pub fn assess(case: &Case, contacts: &[(usize, Race, ContactState)]) -> LubricationReport {
    assess_with_films(case, contacts, &[])
}

/// As [`assess`], with the central and minimum film (m) of a converged EHL solution where
/// `solved[i]` gives one for `contacts[i]` (e.g. `equilibrium --film`); the Hamrock–Dowson formula
/// elsewhere.
pub fn assess_with_films(
    case: &Case,
    contacts: &[(usize, Race, ContactState)],
    solved: &[Option<(f64, f64)>],
) -> LubricationReport {
    let lub = &case.lubricant;
    let rpm = 30.0 / std::f64::consts::PI;
    let n = (case.operating.inner_speed - case.operating.outer_speed).abs() * rpm;
    let dm_mm = case.bearing.geometry.pitch_diameter * 1e3;
    let nu = lub.viscosity / lub.density * 1e6;
    let nu1 = rated_viscosity_mm2_s(n, dm_mm);
    let kappa = nu1.map(|v| nu / v);
    let cx = Context::of(case);
    let rows: Vec<ContactFilm> = contacts
        .iter()
        .enumerate()
        .map(|(i, (ball, race, st))| {
            contact_film(&cx, *ball, *race, st, solved.get(i).copied().flatten())
        })
        .collect();
    let from_solution = rows
        .iter()
        .filter(|r| r.film_source == "ehl-solution")
        .count();
    let extreme = |f: &dyn Fn(&ContactFilm) -> Option<f64>, max: bool| {
        rows.iter().filter_map(f).fold(None, |m: Option<f64>, v| {
            Some(m.map_or(v, |m| if max { m.max(v) } else { m.min(v) }))
        })
    };
    let min_lambda = extreme(&|c| c.lambda, false);
    let max_thermal_reduction = extreme(&|c| c.thermal_reduction, true);
    let max_starvation_reduction = extreme(&|c| c.starvation.map(|s| s.reduction), true);
    let mut warnings = contact_warnings(case, &rows, min_lambda);
    if let Some(k) = kappa.filter(|k| *k < 1.0) {
        warnings.push(format!(
            "viscosity ratio κ = ν/ν1 = {nu:.2}/{:.2} = {k:.2} < 1 (ISO 281): the oil is thinner \
             than the rated viscosity at {n:.0} rpm",
            nu1.unwrap_or(f64::NAN)
        ));
    }
    LubricationReport {
        oil: case.oil.clone(),
        ring_oils: case.ring_oils.clone(),
        viscosity_pa_s: lub.viscosity,
        pressure_viscosity_1_pa: lub.pressure_viscosity,
        density_kg_m3: lub.density,
        kinematic_viscosity_mm2_s: nu,
        relative_speed_rpm: n,
        rated_viscosity_mm2_s: nu1,
        kappa,
        roughness: case.roughness,
        composite_roughness_m: cx.sigma,
        film_formula: if from_solution > 0 {
            "ehl-solution where solved, hamrock-dowson-1977 elsewhere".into()
        } else {
            "hamrock-dowson-1977".into()
        },
        contacts: rows,
        min_lambda,
        max_thermal_reduction,
        inlet_meniscus_distance_m: case.inlet_meniscus_distance_m,
        max_starvation_reduction,
        warnings,
        notes: report_notes(case, from_solution, nu1.is_none()),
    }
}

/// What every contact's figures share: the case, E′, σ and the described oil's thermal inputs.
struct Context<'a> {
    case: &'a Case,
    /// E′, Pa.
    e: f64,
    /// Composite roughness σ, m.
    sigma: Option<f64>,
    /// −∂η/∂T, Pa·s/K, and k_f, W/(m·K), where the oil is described.
    thermal: Option<(f64, f64)>,
}

impl<'a> Context<'a> {
    fn of(case: &'a Case) -> Self {
        Context {
            case,
            e: reduced_modulus(&case.bearing.ball_material, &case.bearing.ring_material),
            sigma: case.roughness.map(|r| r.composite()),
            thermal: case.oil.as_ref().map(|o| {
                (
                    o.temperature_viscosity_1_k * o.viscosity_pa_s,
                    o.thermal_conductivity_w_m_k,
                )
            }),
        }
    }
}

/// One contact's figures: film (the solved one, else Hamrock–Dowson), Λ, thermal reduction and
/// starvation, with its flags; at its ring's oil when ring temperatures are given.
fn contact_film(
    cx: &Context,
    ball: usize,
    race: Race,
    st: &ContactState,
    solved: Option<(f64, f64)>,
) -> ContactFilm {
    let (case, e) = (cx.case, cx.e);
    let mut flags = Vec::new();
    // η0, α and the thermal inputs at this contact's oil temperature.
    let ring_oil = case.ring_oils.as_ref().map(|r| r.of(race));
    let lub = case.lubricant_of(race);
    let (eta0, alpha) = (lub.viscosity, lub.pressure_viscosity);
    let thermal = ring_oil
        .map(|o| {
            (
                o.temperature_viscosity_1_k * o.viscosity_pa_s,
                o.thermal_conductivity_w_m_k,
            )
        })
        .or(cx.thermal);
    let u = 0.5 * st.sum_velocity.abs();
    let loaded = st.load > 0.0 && st.semi_minor > 0.0 && st.rx > 0.0 && st.sum_velocity != 0.0;
    let k = if st.semi_minor > 0.0 {
        st.semi_major / st.semi_minor
    } else {
        0.0
    };
    let solution = solved.filter(|_| loaded);
    let (hc, hmin) = if let Some((c, m)) = solution {
        (Some(c), Some(m))
    } else if loaded {
        let u_sum = eta0 * st.sum_velocity.abs() / (e * st.rx);
        let w = st.load / (e * st.rx * st.rx);
        if !(1.0..=8.0).contains(&k) {
            flags.push(format!(
                "ellipticity k = {k:.2} outside Hamrock–Dowson's 1–8: the film is extrapolated"
            ));
        }
        (
            Some(st.rx * hamrock_dowson_central(u_sum, alpha * e, w, k)),
            Some(st.rx * hamrock_dowson_min(u_sum, alpha * e, w, k)),
        )
    } else {
        flags.push("unloaded or not rolling: no film estimate".into());
        (None, None)
    };
    let lambda = match (hmin, cx.sigma) {
        (Some(h), Some(s)) if s > 0.0 => Some(h / s),
        _ => None,
    };
    if let Some(l) = lambda {
        if l < LAMBDA_INVALID {
            flags.push(format!(
                "Λ = {l:.2} < {LAMBDA_INVALID}: asperities carry load; the smooth-surface EHL \
                 model (film, law, ΔF) does not hold here"
            ));
        } else if l < LAMBDA_WARN {
            flags.push(format!(
                "Λ = {l:.2} < {LAMBDA_WARN}: mixed lubrication; the smooth-surface model \
                 overestimates the film and the law's ΔF"
            ));
        }
    }
    let (tl, red) = match (thermal, loaded) {
        (Some((deta, kf)), true) => {
            let (l, r) =
                thermal_figures(st.max_pressure, e, thermal_loading(deta, u, kf), &mut flags);
            (Some(l), Some(r))
        }
        _ => (None, None),
    };
    let starved = match (case.inlet_meniscus_distance_m, hc, hmin) {
        (Some(x), Some(c), Some(m)) => Some(starvation_figures(c, m, st, x, &mut flags)),
        _ => None,
    };
    ContactFilm {
        ball,
        race: race_name(race).into(),
        load_n: st.load,
        max_pressure_pa: st.max_pressure,
        entrainment_velocity_m_s: u,
        ellipticity: k,
        central_film_m: hc,
        min_film_m: hmin,
        lambda,
        thermal_loading: tl,
        thermal_reduction: red,
        min_film_thermal_m: match (hmin, red) {
            (Some(h), Some(r)) => Some(h * (1.0 - r)),
            _ => None,
        },
        starvation: starved,
        film_source: if solution.is_some() {
            "ehl-solution".into()
        } else if hmin.is_some() {
            "hamrock-dowson-1977".into()
        } else {
            String::new()
        },
        oil_temperature_c: ring_oil.map(|o| o.temperature_c),
        flags,
    }
}

/// The thermal loading L (given) and the film reduction 1 − φ_T of Gupta et al. at maximum Hertz
/// pressure `p_h` and E′ `e`, flagging a reduction above [`THERMAL_WARN`] and L beyond the
/// correlation.
fn thermal_figures(p_h: f64, e: f64, l: f64, flags: &mut Vec<String>) -> (f64, f64) {
    let phi = thermal_factor(p_h, e, l, 0.0);
    if phi <= 0.0 {
        flags.push(format!(
            "thermal loading L = {l:.3} beyond the Gupta et al. correlation (φ_T = {phi:.3} ≤ 0): \
             the isothermal film does not describe this contact"
        ));
    }
    let r = (1.0 - phi).min(1.0);
    if r > THERMAL_WARN {
        flags.push(format!(
            "inlet shear heating reduces the film by about {:.0} % (isothermal model)",
            100.0 * r
        ));
    }
    (l, r)
}

/// The starvation figures of a contact with flooded films `hc`, `hmin` (m) for the meniscus at
/// `x` m, flagging the meniscus inside the contact and a reduction above [`STARVATION_WARN`].
fn starvation_figures(
    hc: f64,
    hmin: f64,
    st: &ContactState,
    x: f64,
    flags: &mut Vec<String>,
) -> Starvation {
    let sv = starvation(hc, hmin, st.rx, st.semi_minor, x);
    if sv.inlet_distance_ratio <= 1.0 {
        flags.push(format!(
            "oil meniscus inside the Hertzian contact (m = {:.2} ≤ 1): no film is formed; the \
             fully flooded EHL model (film, law, ΔF) does not hold here",
            sv.inlet_distance_ratio
        ));
    } else if sv.reduction > STARVATION_WARN {
        flags.push(format!(
            "starvation reduces the minimum film by about {:.0} % (m = {:.2} < m* = {:.2}; fully \
             flooded model)",
            100.0 * sv.reduction,
            sv.inlet_distance_ratio,
            sv.boundary_ratio
        ));
    }
    sv
}

/// The report's warnings about its contacts: Λ < [`LAMBDA_WARN`], thermal reduction above
/// [`THERMAL_WARN`], starvation above [`STARVATION_WARN`], each naming its contacts.
fn contact_warnings(case: &Case, rows: &[ContactFilm], min_lambda: Option<f64>) -> Vec<String> {
    let list = |f: &dyn Fn(&ContactFilm) -> Option<String>| {
        rows.iter()
            .filter_map(|c| f(c).map(|v| format!("ball {} {} ({v})", c.ball, c.race)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let low_lambda = list(&|c| {
        c.lambda
            .filter(|l| *l < LAMBDA_WARN)
            .map(|l| format!("{l:.2}"))
    });
    let hot = list(&|c| {
        c.thermal_reduction
            .filter(|r| *r > THERMAL_WARN)
            .map(|r| format!("{:.0} %", 100.0 * r))
    });
    let starved = list(&|c| {
        c.starvation
            .map(|s| s.reduction)
            .filter(|r| *r > STARVATION_WARN)
            .map(|r| format!("{:.0} %", 100.0 * r))
    });
    let mut warnings = Vec::new();
    if !low_lambda.is_empty() {
        warnings.push(format!(
            "film parameter Λ = h_min/σ < {LAMBDA_WARN} (mixed lubrication; the smooth-surface \
             model overestimates the film and the law's ΔF{}) at {low_lambda}",
            if min_lambda.is_some_and(|l| l < LAMBDA_INVALID) {
                "; below 1 it does not hold"
            } else {
                ""
            },
        ));
    }
    if !hot.is_empty() {
        warnings.push(format!(
            "inlet shear heating reduces the isothermal film by more than {:.0} % (Gupta et al. \
             1992) at {hot}",
            100.0 * THERMAL_WARN,
        ));
    }
    if !starved.is_empty() {
        warnings.push(format!(
            "starvation reduces the minimum film by more than {:.0} % (Hamrock & Dowson 1977; the \
             oil meniscus at {:.3} mm from the contact centres) at {starved}",
            100.0 * STARVATION_WARN,
            case.inlet_meniscus_distance_m.unwrap_or(f64::NAN) * 1e3,
        ));
    }
    warnings
}

/// The report's notes: where the films come from, what is not estimated and why.
fn report_notes(case: &Case, from_solution: usize, at_rest: bool) -> Vec<String> {
    let mut notes = vec![
        if from_solution > 0 {
            format!(
                "film: the steady EHL solution at {from_solution} contacts, the Hamrock–Dowson \
                 (1977) formula elsewhere (film_source)"
            )
        } else {
            "film: Hamrock–Dowson (1977) formula at the equilibrium contact states (±10–20 % \
             against full numerical solutions), not the EHL samples of the law fit"
                .to_string()
        },
        match case.inlet_meniscus_distance_m {
            None => "starvation: not estimated (no oil supply is described); the model assumes \
                     a fully flooded inlet"
                .to_string(),
            Some(x) => format!(
                "starvation: Hamrock & Dowson (1977) correlation with the oil meniscus at {:.3} mm \
                 from each contact's centre, an estimate beside the fully flooded films (the EHL \
                 solves and laws are fully flooded)",
                x * 1e3
            ),
        },
    ];
    if let (Some(r), Some(o)) = (&case.ring_oils, &case.oil) {
        notes.push(format!(
            "ring temperatures: the inner contacts are characterized and get their film, Λ and \
             thermal reduction with the oil at {} °C (η0 = {:.5} Pa·s), the outer contacts at {} \
             °C (η0 = {:.5} Pa·s); κ and the η0, α above are at operating.temperature_c = {} °C",
            r.inner.temperature_c,
            r.inner.viscosity_pa_s,
            r.outer.temperature_c,
            r.outer.viscosity_pa_s,
            o.temperature_c
        ));
    }
    if case.roughness.is_none() {
        notes.push(
            "Λ: not computed (give ball_material.roughness_rq_um and ring_material.roughness_rq_um)"
                .into(),
        );
    }
    if case.oil.is_none() {
        notes.push(
            "thermal reduction: not computed (needs the oil's temperature–viscosity coefficient: \
             describe the lubricant by grade and operating.temperature_c)"
                .into(),
        );
    }
    if at_rest {
        notes.push("κ: undefined with the rings at the same speed".into());
    }
    notes
}

/// The report as an engineering-units table (films in µm; the warnings are not included).
pub fn table(r: &LubricationReport) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    if let Some(o) = &r.oil {
        let _ = writeln!(
            s,
            "lubricant: {}{} oil, ν40 = {:.2}, ν100 = {:.3} mm²/s, VI {:.1}; at {} °C: ν = {:.3} \
             mm²/s, ρ = {:.1} kg/m³, η0 = {:.5} Pa·s, α = {:.3e} 1/Pa (Z = {:.3}), β = {:.4} 1/K",
            o.iso_vg.map(|g| format!("ISO VG {g} ")).unwrap_or_default(),
            o.base_oil.name(),
            o.viscosity_40c_mm2_s,
            o.viscosity_100c_mm2_s,
            o.viscosity_index,
            o.temperature_c,
            o.kinematic_viscosity_mm2_s,
            o.density_kg_m3,
            o.viscosity_pa_s,
            o.pressure_viscosity_1_pa,
            o.roelands_z,
            o.temperature_viscosity_1_k
        );
    }
    if let Some(rings) = &r.ring_oils {
        for (name, o) in [("inner", &rings.inner), ("outer", &rings.outer)] {
            let _ = writeln!(
                s,
                "{name} ring at {} °C: ν = {:.3} mm²/s, η0 = {:.5} Pa·s, α = {:.3e} 1/Pa (its \
                 contacts' EHL solves, laws, films, Λ and thermal reduction)",
                o.temperature_c,
                o.kinematic_viscosity_mm2_s,
                o.viscosity_pa_s,
                o.pressure_viscosity_1_pa
            );
        }
    }
    let _ = writeln!(
        s,
        "lubrication: ν = {:.3} mm²/s, ν1 (ISO 281) = {}, κ = {}; σ = {}",
        r.kinematic_viscosity_mm2_s,
        r.rated_viscosity_mm2_s
            .map_or("-".into(), |v| format!("{v:.3} mm²/s")),
        r.kappa.map_or("-".into(), |v| format!("{v:.3}")),
        r.composite_roughness_m
            .map_or("not given".into(), |v| format!("{:.4} µm", v * 1e6))
    );
    let supplied = r.inlet_meniscus_distance_m.is_some();
    if let Some(x) = r.inlet_meniscus_distance_m {
        let _ = writeln!(
            s,
            "oil supply: meniscus at {:.3} mm from the contact centres (starvation: Hamrock & \
             Dowson 1977; m = distance/b, m* the flooded–starved boundary)",
            x * 1e3
        );
    }
    let _ = write!(
        s,
        "{:>4} {:>5} {:>9} {:>9} {:>9} {:>7} {:>8}",
        "ball", "race", "h_c µm", "h_min µm", "Λ", "thermal", "h_min,T"
    );
    if supplied {
        let _ = write!(
            s,
            " {:>6} {:>6} {:>7} {:>8}",
            "m", "m*", "starved", "h_min,S"
        );
    }
    s.push('\n');
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or("-".to_string(), f);
    for c in &r.contacts {
        let _ = write!(
            s,
            "{:>4} {:>5} {:>9} {:>9} {:>9} {:>7} {:>8}",
            c.ball,
            c.race,
            opt(c.central_film_m, &|v| format!("{:.4}", v * 1e6)),
            opt(c.min_film_m, &|v| format!("{:.4}", v * 1e6)),
            opt(c.lambda, &|v| format!("{v:.3}")),
            opt(c.thermal_reduction, &|v| format!("{:.1}%", 100.0 * v)),
            opt(c.min_film_thermal_m, &|v| format!("{:.4}", v * 1e6)),
        );
        if supplied {
            let sv = c.starvation;
            let _ = write!(
                s,
                " {:>6} {:>6} {:>7} {:>8}",
                opt(sv.map(|v| v.inlet_distance_ratio), &|v| format!("{v:.2}")),
                opt(sv.map(|v| v.boundary_ratio), &|v| format!("{v:.2}")),
                opt(sv.map(|v| v.reduction), &|v| format!("{:.1}%", 100.0 * v)),
                opt(sv.map(|v| v.min_film_m), &|v| format!("{:.4}", v * 1e6)),
            );
        }
        s.push('\n');
    }
    s
}

/// The per-contact figures as CSV (SI units, the names carry them; empty fields where a figure is
/// not computed).
pub fn contacts_csv(r: &LubricationReport) -> String {
    let supplied = r.inlet_meniscus_distance_m.is_some();
    let mut s = String::from(
        "ball,race,load_n,max_pressure_pa,entrainment_velocity_m_s,ellipticity,central_film_m,\
         min_film_m,lambda,thermal_loading,thermal_reduction,min_film_thermal_m,",
    );
    if supplied {
        s.push_str("inlet_distance_ratio,starvation_boundary_ratio,starvation_reduction,min_film_starved_m,");
    }
    s.push_str("flags\n");
    let o = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for c in &r.contacts {
        s.push_str(&format!(
            "{},{},{:e},{:e},{:e},{:e},{},{},{},{},{},{},",
            c.ball,
            c.race,
            c.load_n,
            c.max_pressure_pa,
            c.entrainment_velocity_m_s,
            c.ellipticity,
            o(c.central_film_m),
            o(c.min_film_m),
            o(c.lambda),
            o(c.thermal_loading),
            o(c.thermal_reduction),
            o(c.min_film_thermal_m),
        ));
        if supplied {
            let sv = c.starvation;
            s.push_str(&format!(
                "{},{},{},{},",
                o(sv.map(|v| v.inlet_distance_ratio)),
                o(sv.map(|v| v.boundary_ratio)),
                o(sv.map(|v| v.reduction)),
                o(sv.map(|v| v.min_film_m)),
            ));
        }
        s.push_str(&format!("\"{}\"\n", c.flags.join("; ").replace('"', "'")));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rated_viscosity_branches() {
        assert_eq!(rated_viscosity_mm2_s(0.0, 42.5), None);
        let lo = rated_viscosity_mm2_s(999.0, 42.5).unwrap();
        let hi = rated_viscosity_mm2_s(1000.0, 42.5).unwrap();
        assert!((lo - 45000.0 * 999f64.powf(-0.83) / 42.5f64.sqrt()).abs() < 1e-9);
        assert!((hi - 4500.0 / (1000f64 * 42.5).sqrt()).abs() < 1e-9);
    }

    #[test]
    fn thermal_factor_is_one_without_heating() {
        assert_eq!(thermal_factor(1e9, 2.3e11, 0.0, 0.0), 1.0);
        assert!(thermal_factor(1e9, 2.3e11, 1.0, 0.0) < 1.0);
    }
}
