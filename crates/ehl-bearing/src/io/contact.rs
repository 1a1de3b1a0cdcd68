//! Contact files (TOML) for one EHL contact, in engineering units with the unit in every key.
//!
//! Keys: `load_n` (N), `rx_mm`, `ry_mm` (mm, x = rolling direction, Rx ≤ Ry), `sum_velocity_m_s`
//! (u1 + u2, m/s), either `reduced_modulus_gpa` (E′, GPa, 2/E′ = Σ(1−ν²)/E) or the tables
//! `[ball_material]`, `[ring_material]` (`youngs_modulus_gpa`, `poisson_ratio`, `density_kg_m3`;
//! default AISI 52100: 208 GPa, 0.3, 7850 kg/m³), and an optional `[lubricant]` table
//! (`viscosity_pa_s` default 0.04, `pressure_viscosity_1_pa` default 2.2e-8, `density_kg_m3`
//! default 870, `viscosity_model` = "roelands" (default) | "barus", `density_model` =
//! "dowson-higginson" (default) | "incompressible"). For the harmonic method (contact dynamics)
//! the ball's mass comes from `ball_mass_kg` (kg) or from `ball_diameter_mm` (mm) and the ball
//! material's density (both optional; not both). Unknown keys are rejected; invalid values give
//! an error naming the key, the value and the valid range.

use super::case::{self, RawLubricant, RawSolid};
use crate::ehl::{EhlContact, EhlError};
use crate::material::{reduced_modulus, Lubricant, Solid};
use serde::Deserialize;

macro_rules! fail {
    ($($t:tt)*) => {
        return Err(EhlError::File(format!($($t)*)))
    };
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ContactToml {
    load_n: f64,
    rx_mm: f64,
    ry_mm: f64,
    sum_velocity_m_s: f64,
    reduced_modulus_gpa: Option<f64>,
    ball_material: Option<RawSolid>,
    ring_material: Option<RawSolid>,
    lubricant: Option<RawLubricant>,
    ball_mass_kg: Option<f64>,
    ball_diameter_mm: Option<f64>,
}

/// A parsed contact file: the contact and, if the file gives it, the ball's mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFile {
    /// The contact, SI units.
    pub contact: EhlContact,
    /// Mass of the ball, kg (from `ball_mass_kg`, or from `ball_diameter_mm` and the ball
    /// material's density); `None` when the file gives neither.
    pub ball_mass: Option<f64>,
}

fn positive(field: &str, v: f64) -> Result<f64, EhlError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        fail!("{field} = {v} is invalid: must be finite and > 0")
    }
}

/// The material and lubricant tables are those of case files, read by the case parser (one
/// parser, one set of ranges per table).
fn solid(name: &str, m: &Option<RawSolid>) -> Result<Solid, EhlError> {
    if let Some(rq) = m.as_ref().and_then(|m| m.roughness_rq_um) {
        return Err(EhlError::File(format!(
            "{name}.roughness_rq_um = {rq}: expected no roughness in a contact file (the film \
             parameter is reported for bearing cases)"
        )));
    }
    case::solid(m.as_ref(), name).map_err(|e| EhlError::File(e.to_string()))
}

fn lubricant(l: &Option<RawLubricant>) -> Result<Lubricant, EhlError> {
    match l {
        None => Ok(Lubricant::DEFAULT_MINERAL_OIL),
        Some(l) => case::lubricant(l, "lubricant").map_err(|e| EhlError::File(e.to_string())),
    }
}

/// Parses and validates a contact file's text (the contact only; see [`parse_contact_file`]).
pub fn parse_contact_toml(text: &str) -> Result<EhlContact, EhlError> {
    parse_contact_file(text).map(|f| f.contact)
}

/// Parses and validates a contact file's text, with the ball's mass if the file gives it.
pub fn parse_contact_file(text: &str) -> Result<ContactFile, EhlError> {
    let t: ContactToml = super::from_toml(text, "contact file").map_err(|e| match e {
        crate::case::InputError::Syntax { path, message } => {
            EhlError::File(format!("{path}: {message}"))
        }
        e => EhlError::File(e.to_string()),
    })?;
    let load = positive("load_n", t.load_n)?;
    let rx = positive("rx_mm", t.rx_mm)? * 1e-3;
    let ry = positive("ry_mm", t.ry_mm)? * 1e-3;
    let ratio = ry / rx;
    if !(1.0..=1000.0).contains(&ratio) {
        fail!(
            "ry_mm/rx_mm = {ratio} is invalid: valid range 1 to 1000 (x is the rolling direction with the smaller radius)"
        );
    }
    let us = positive("sum_velocity_m_s", t.sum_velocity_m_s)?;
    let e_reduced = match (t.reduced_modulus_gpa, &t.ball_material, &t.ring_material) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            fail!("give either reduced_modulus_gpa or [ball_material]/[ring_material], not both")
        }
        (Some(e), None, None) => {
            // Two solids of 0.1 to 1200 GPa (case files) with 0 ≤ ν < 0.5.
            if !(e.is_finite() && (0.1..=2400.0).contains(&e)) {
                fail!(
                    "reduced_modulus_gpa = {e} is invalid: valid range 0.1 to 2400 GPa (steel on \
                     steel 228.6; the moduli of real solids)"
                );
            }
            e * 1e9
        }
        (None, b, r) => reduced_modulus(&solid("ball_material", b)?, &solid("ring_material", r)?),
    };
    let ball_mass = match (t.ball_mass_kg, t.ball_diameter_mm) {
        (Some(_), Some(_)) => fail!("give either ball_mass_kg or ball_diameter_mm, not both"),
        (Some(m), None) => Some(positive("ball_mass_kg", m)?),
        (None, Some(d)) => {
            let d = positive("ball_diameter_mm", d)? * 1e-3;
            let rho = solid("ball_material", &t.ball_material)?.density;
            let m = rho * std::f64::consts::PI / 6.0 * d * d * d;
            if !(m.is_finite() && m > 0.0) {
                fail!(
                    "ball_diameter_mm = {} is invalid: the ball mass ρ·π/6·D³ = {m} kg must be \
                     finite and > 0 (give a physically sized ball, e.g. 1 to 100 mm)",
                    d * 1e3
                );
            }
            Some(m)
        }
        (None, None) => None,
    };
    Ok(ContactFile {
        contact: EhlContact {
            load,
            rx,
            ry,
            sum_velocity: us,
            e_reduced,
            lubricant: lubricant(&t.lubricant)?,
        },
        ball_mass,
    })
}
