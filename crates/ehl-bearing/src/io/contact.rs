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
use crate::case::InputError;
use crate::ehl::EhlContact;
use crate::material::{reduced_modulus, Lubricant, Solid};
use serde::Deserialize;
use thiserror::Error;

/// An invalid contact file: the key, the value and the valid range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ContactFileError {
    /// Not TOML of a contact file, or a material or lubricant table out of range (the tables
    /// are those of case files, with their messages).
    #[error(transparent)]
    Input(#[from] InputError),
    /// A number that must be finite and positive.
    #[error("{field} = {value} is invalid: must be finite and > 0")]
    NotPositive {
        /// The key.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// Curvature radii in the wrong order or too far apart.
    #[error(
        "ry_mm/rx_mm = {ratio} is invalid: valid range 1 to 1000 (x is the rolling direction \
         with the smaller radius)"
    )]
    RadiusRatio {
        /// Ry/Rx.
        ratio: f64,
    },
    /// Two keys that exclude each other.
    #[error("give either {first} or {second}, not both")]
    Conflict {
        /// One key (or table).
        first: &'static str,
        /// The other.
        second: &'static str,
    },
    /// A reduced modulus outside that of real solids.
    #[error(
        "reduced_modulus_gpa = {value} is invalid: valid range 0.1 to 2400 GPa (steel on steel \
         228.6; the moduli of real solids)"
    )]
    ReducedModulus {
        /// E′ given, GPa.
        value: f64,
    },
    /// A roughness, which contact files do not take.
    #[error(
        "{table}.roughness_rq_um = {value}: expected no roughness in a contact file (the film \
         parameter is reported for bearing cases)"
    )]
    Roughness {
        /// `ball_material` or `ring_material`.
        table: &'static str,
        /// Rq given, µm.
        value: f64,
    },
    /// A ball diameter whose mass is not finite and positive.
    #[error(
        "ball_diameter_mm = {diameter_mm} is invalid: the ball mass ρ·π/6·D³ = {mass_kg} kg must \
         be finite and > 0 (give a physically sized ball, e.g. 1 to 100 mm)"
    )]
    BallMass {
        /// D given, mm.
        diameter_mm: f64,
        /// ρ·π/6·D³, kg.
        mass_kg: f64,
    },
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

fn positive(field: &'static str, value: f64) -> Result<f64, ContactFileError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ContactFileError::NotPositive { field, value })
    }
}

/// The material and lubricant tables are those of case files, read by the case parser (one
/// parser, one set of ranges per table).
fn solid(name: &'static str, m: &Option<RawSolid>) -> Result<Solid, ContactFileError> {
    if let Some(rq) = m.as_ref().and_then(|m| m.roughness_rq_um) {
        return Err(ContactFileError::Roughness {
            table: name,
            value: rq,
        });
    }
    Ok(case::solid(m.as_ref(), name)?)
}

fn lubricant(l: &Option<RawLubricant>) -> Result<Lubricant, ContactFileError> {
    match l {
        None => Ok(Lubricant::DEFAULT_MINERAL_OIL),
        Some(l) => Ok(case::lubricant(l, "lubricant")?),
    }
}

/// Parses and validates a contact file's text (the contact only; see [`parse_contact_file`]).
pub fn parse_contact_toml(text: &str) -> Result<EhlContact, ContactFileError> {
    parse_contact_file(text).map(|f| f.contact)
}

/// Parses and validates a contact file's text, with the ball's mass if the file gives it.
pub fn parse_contact_file(text: &str) -> Result<ContactFile, ContactFileError> {
    let t: ContactToml = super::from_toml(text, "contact file")?;
    let load = positive("load_n", t.load_n)?;
    let rx = positive("rx_mm", t.rx_mm)? * 1e-3;
    let ry = positive("ry_mm", t.ry_mm)? * 1e-3;
    let ratio = ry / rx;
    if !(1.0..=1000.0).contains(&ratio) {
        return Err(ContactFileError::RadiusRatio { ratio });
    }
    let us = positive("sum_velocity_m_s", t.sum_velocity_m_s)?;
    let e_reduced = match (t.reduced_modulus_gpa, &t.ball_material, &t.ring_material) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            return Err(ContactFileError::Conflict {
                first: "reduced_modulus_gpa",
                second: "[ball_material]/[ring_material]",
            })
        }
        (Some(e), None, None) => {
            // Two solids of 0.1 to 1200 GPa (case files) with 0 ≤ ν < 0.5.
            if !(e.is_finite() && (0.1..=2400.0).contains(&e)) {
                return Err(ContactFileError::ReducedModulus { value: e });
            }
            e * 1e9
        }
        (None, b, r) => reduced_modulus(&solid("ball_material", b)?, &solid("ring_material", r)?),
    };
    let ball_mass = match (t.ball_mass_kg, t.ball_diameter_mm) {
        (Some(_), Some(_)) => {
            return Err(ContactFileError::Conflict {
                first: "ball_mass_kg",
                second: "ball_diameter_mm",
            })
        }
        (Some(m), None) => Some(positive("ball_mass_kg", m)?),
        (None, Some(d)) => {
            let d = positive("ball_diameter_mm", d)? * 1e-3;
            let rho = solid("ball_material", &t.ball_material)?.density;
            let m = rho * std::f64::consts::PI / 6.0 * d * d * d;
            if !(m.is_finite() && m > 0.0) {
                return Err(ContactFileError::BallMass {
                    diameter_mm: d * 1e3,
                    mass_kg: m,
                });
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
