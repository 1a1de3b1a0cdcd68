//! The contact law in dimensionless form: the groups that fix it and the law made dimensionless.
//!
//! The steady EHL problem the solver works on ([`crate::ehl`], docs/ehl.md §1) contains the
//! contact's data only through a few dimensionless groups; the quasi-static method's family is a
//! set of such problems at the loads w0·(1 ± ε·…), and its least-squares fit is invariant under a
//! scaling of the approaches and of the forces. So the dimensionless law
//!
//!   Q/w0 = K̂·(δ/δ_H)^d + ΔF̂,   K̂ = K·δ_H^d/w0,   ΔF̂ = ΔF/w0,
//!
//! with δ_H the Hertz deflection at w0, is a function of the groups alone (and of the method's
//! dimensionless settings: ε, the number of solutions, the grid and the domain). The groups of
//! each viscosity and density model are derived in docs/law_map.md:
//!
//! | viscosity, density | groups |
//! |---|---|
//! | Roelands, Dowson–Higginson or incompressible | M, L, Ry/Rx, α·p0, ln(η0/η∞) |
//! | Barus, Dowson–Higginson | M, L, Ry/Rx, α·p0 (α·5.9e8 Pa, a fixed multiple) |
//! | Barus, incompressible | M, L, Ry/Rx |
//!
//! [`LawGroups::of`] computes them for a contact, [`LawGroups::contact`] builds a contact with
//! given groups at any curvature radius and reduced modulus (both are free: the groups fix the
//! problem up to a size and, with the oil fixed, a modulus), [`DimensionlessLaw`] converts a
//! fitted law to its dimensionless form and back.

use crate::contact::ContactFit;
use crate::ehl::EhlContact;
use crate::fit::FittedLaw;
use crate::hertz::{HertzContact, HertzGeometry};
use crate::material::{DensityModel, Lubricant, ViscosityModel, ROELANDS_LN_ETA_INF, ROELANDS_P0};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Errors of the dimensionless law and its map.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LawMapError {
    /// A group or a contact datum outside its valid range.
    #[error("{field} = {value} is invalid: expected {expected}")]
    Invalid {
        /// The group or field.
        field: String,
        /// Its value.
        value: f64,
        /// The valid range.
        expected: String,
    },
    /// A spec (TOML) or map (JSON text or binary) file that does not parse: the parser's
    /// message, or what of the binary form is wrong.
    #[error("law map: {message}")]
    Parse {
        /// The TOML or JSON parser's message, with line and column, or the binary form's
        /// length found and expected.
        message: String,
    },
    /// A group the spec's rheology models need, not given exactly once.
    #[error(
        "law map: group {group}: given {given} time(s) (as an axis {axes}, fixed {fixed}); the \
         models {viscosity_model:?}/{density_model:?} need it exactly once",
        given = axes + fixed
    )]
    GroupCount {
        /// The group's name.
        group: &'static str,
        /// Times given as an axis.
        axes: usize,
        /// Times given as a fixed value.
        fixed: usize,
        /// The spec's viscosity model.
        viscosity_model: ViscosityModel,
        /// The spec's density model.
        density_model: DensityModel,
    },
    /// A group given that the spec's rheology models do not depend on.
    #[error(
        "law map: group {group}: given, but the models {viscosity_model:?}/{density_model:?} do \
         not depend on it"
    )]
    GroupNotUsed {
        /// The group's name.
        group: &'static str,
        /// The spec's viscosity model.
        viscosity_model: ViscosityModel,
        /// The spec's density model.
        density_model: DensityModel,
    },
    /// A number of axes outside 1 to 5 (6 with the harmonic law's psi_h).
    #[error("law map: {axes} axes: expected 1 to 5 (6 with the harmonic law's psi_h)")]
    AxisCount {
        /// Axes given.
        axes: usize,
    },
    /// An axis whose range is not 0 < min < max.
    #[error("law map: axis {group}: min = {min}, max = {max}: expected 0 < min < max, finite")]
    AxisRange {
        /// The axis's group.
        group: &'static str,
        /// Its lower end.
        min: f64,
        /// Its upper end.
        max: f64,
    },
    /// The spec's EHL settings out of range.
    #[error("law map: {0}")]
    Ehl(crate::ehl::EhlError),
    /// A map file of another format.
    #[error("law map: format = {format:?}: expected {expected:?}")]
    Format {
        /// The format given.
        format: String,
        /// The format read.
        expected: &'static str,
    },
    /// A map file whose laws or quality entries do not match its nodes.
    #[error("law map: {laws} laws and {quality} quality entries for {nodes} nodes")]
    NodeCount {
        /// Laws given.
        laws: usize,
        /// Quality entries given.
        quality: usize,
        /// Nodes of the spec.
        nodes: usize,
    },
    /// A contact whose rheology models are not the map's.
    #[error("the contact's models {contact} are not the map's ({map})")]
    Models {
        /// The contact's viscosity/density models.
        contact: String,
        /// The map's.
        map: String,
    },
    /// A contact outside the map's envelope.
    #[error("{group} = {value} lies outside the map's envelope [{min}, {max}]")]
    OutsideEnvelope {
        /// The group.
        group: String,
        /// Its value.
        value: f64,
        /// The envelope's smallest value.
        min: f64,
        /// The envelope's largest value.
        max: f64,
    },
    /// A contact outside every embedded map.
    #[error("outside every embedded map: {reasons} (the map method's default, `fallback = true` in [method_options], characterizes such contacts by the {method} method)")]
    OutsideEveryMap {
        /// Each map's refusal.
        reasons: String,
        /// The EHL method of the maps' law, which the fallback uses: "quasi-static" or
        /// "harmonic".
        method: &'static str,
    },
    /// The store holds node files of another map under this map's names.
    #[error("{count} node file(s) hold nodes of a different map (first: {first}); nothing was overwritten — use another folder or overwrite")]
    ForeignNodes {
        /// How many.
        count: usize,
        /// The first.
        first: String,
    },
    /// Nodes missing or failed when the map is assembled.
    #[error("{missing} of {total} nodes are missing or failed (first: {first})")]
    Incomplete {
        /// Missing or failed nodes.
        missing: usize,
        /// Nodes of the map.
        total: usize,
        /// The first of them, with its groups and error.
        first: String,
    },
}

fn invalid(field: &str, value: f64, expected: &str) -> LawMapError {
    LawMapError::Invalid {
        field: field.into(),
        value,
        expected: expected.into(),
    }
}

fn positive(field: &str, v: f64) -> Result<f64, LawMapError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(field, v, "finite and > 0"))
    }
}

/// The dimensionless groups that fix a steady EHL contact and its quasi-static law, for the
/// contact's viscosity and density models (docs/law_map.md §2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LawGroups {
    /// Moes' load parameter M = W·U^(−3/4), W = w/(E′Rx²), U = η0·u_s/(E′Rx).
    pub m: f64,
    /// Moes' lubricant parameter L = α·E′·U^(1/4).
    pub l: f64,
    /// Radius ratio Ry/Rx (1 to 1000).
    pub ry_over_rx: f64,
    /// α·p0 with Roelands' p0 = 1.96e8 Pa; a group for Roelands (with ln(η0/η∞) it fixes z and
    /// p_h/p0) and for Dowson–Higginson (p_h/5.9e8 Pa); `None` for Barus with incompressible
    /// density, where α enters only through L.
    pub alpha_p0: Option<f64>,
    /// ln(η0/η∞) = ln η0 + 9.67 (η0 in Pa·s); a group for Roelands only.
    pub ln_eta0_ratio: Option<f64>,
    /// Viscosity model.
    pub viscosity: ViscosityModel,
    /// Density model.
    pub density: DensityModel,
}

/// Reference density of the contacts built from groups, kg/m³ (it does not enter the steady
/// problem: only ρ/ρ0 does).
const REFERENCE_DENSITY: f64 = 870.0;
/// α and η0 of the contacts built from groups where the models leave them free (the project's
/// default oil), 1/Pa and Pa·s.
const FREE_ALPHA: f64 = 2.2e-8;
const FREE_ETA0: f64 = 0.04;

impl LawGroups {
    /// The groups of a contact (SI data; the rheology groups its models need).
    pub fn of(c: &EhlContact) -> Result<LawGroups, LawMapError> {
        let e = positive("e_reduced [Pa]", c.e_reduced)?;
        let rx = positive("rx [m]", c.rx)?;
        let ry = positive("ry [m]", c.ry)?;
        let w = positive("load [N]", c.load)? / (e * rx * rx);
        let eta0 = positive("lubricant.viscosity [Pa s]", c.lubricant.viscosity)?;
        let u = eta0 * positive("sum_velocity [m/s]", c.sum_velocity)? / (e * rx);
        let alpha = c.lubricant.pressure_viscosity;
        if !(alpha.is_finite() && alpha >= 0.0) {
            return Err(invalid(
                "lubricant.pressure_viscosity [1/Pa]",
                alpha,
                "finite and ≥ 0",
            ));
        }
        let roelands = c.lubricant.viscosity_model == ViscosityModel::Roelands;
        let dh = c.lubricant.density_model == DensityModel::DowsonHigginson;
        Ok(LawGroups {
            m: w * u.powf(-0.75),
            l: alpha * e * u.powf(0.25),
            ry_over_rx: ry / rx,
            alpha_p0: (roelands || dh).then_some(alpha * ROELANDS_P0),
            ln_eta0_ratio: roelands.then_some(eta0.ln() + ROELANDS_LN_ETA_INF),
            viscosity: c.lubricant.viscosity_model,
            density: c.lubricant.density_model,
        })
    }

    /// Checks the groups: M, L > 0, 1 ≤ Ry/Rx ≤ 1000, and the rheology groups present exactly
    /// where the models need them, positive.
    pub fn validate(&self) -> Result<(), LawMapError> {
        positive("M", self.m)?;
        positive("L", self.l)?;
        if !(self.ry_over_rx.is_finite() && (1.0..=1000.0).contains(&self.ry_over_rx)) {
            return Err(invalid("Ry/Rx", self.ry_over_rx, "1 ≤ Ry/Rx ≤ 1000"));
        }
        let roelands = self.viscosity == ViscosityModel::Roelands;
        let dh = self.density == DensityModel::DowsonHigginson;
        match (roelands || dh, self.alpha_p0) {
            (true, Some(a)) => {
                positive("alpha_p0", a)?;
            }
            (true, None) => {
                return Err(invalid(
                    "alpha_p0",
                    f64::NAN,
                    "a value: Roelands and Dowson–Higginson need α·p0",
                ))
            }
            (false, Some(a)) => {
                return Err(invalid(
                    "alpha_p0",
                    a,
                    "none: with Barus and incompressible density α enters only through L",
                ))
            }
            (false, None) => {}
        }
        match (roelands, self.ln_eta0_ratio) {
            (true, Some(c)) => {
                positive("ln_eta0_ratio", c)?;
            }
            (true, None) => {
                return Err(invalid(
                    "ln_eta0_ratio",
                    f64::NAN,
                    "a value: Roelands needs ln(η0/η∞)",
                ))
            }
            (false, Some(c)) => {
                return Err(invalid(
                    "ln_eta0_ratio",
                    c,
                    "none: Barus does not depend on η0 apart from U",
                ))
            }
            (false, None) => {}
        }
        Ok(())
    }

    /// α·p_h (dimensionless), which M, L and Ry/Rx fix: p_h = E′·W^(1/3)·g(Ry/Rx) and
    /// W^(1/3) = M^(1/3)·L/(αE′), so α·p_h = M^(1/3)·L·g(Ry/Rx), independent of the size and of
    /// E′ (docs/law_map.md §2).
    pub fn alpha_ph(&self) -> Result<f64, LawMapError> {
        self.validate()?;
        // Evaluate on the unit contact E′ = 1 Pa, Rx = 1 m with U = 1: W = M, G = L.
        let g = HertzGeometry::new(1.0, self.ry_over_rx, 1.0)
            .map_err(|_| invalid("Ry/Rx", self.ry_over_rx, "1 ≤ Ry/Rx ≤ 1000"))?;
        Ok(self.l * g.contact(self.m).max_pressure)
    }

    /// A contact with these groups, curvature radius `rx` (m) and reduced modulus `e_reduced`
    /// (Pa): α and η0 from the rheology groups (the project's default oil's where the models
    /// leave them free), U = (L/(αE′))⁴, W = M·U^(3/4), so u_s = U·E′·Rx/η0 and
    /// w = W·E′·Rx².
    pub fn contact(&self, rx: f64, e_reduced: f64) -> Result<EhlContact, LawMapError> {
        self.validate()?;
        positive("rx [m]", rx)?;
        positive("e_reduced [Pa]", e_reduced)?;
        let alpha = self.alpha_p0.map_or(FREE_ALPHA, |a| a / ROELANDS_P0);
        let eta0 = self
            .ln_eta0_ratio
            .map_or(FREE_ETA0, |c| (c - ROELANDS_LN_ETA_INF).exp());
        let u = (self.l / (alpha * e_reduced)).powi(4);
        let w = self.m * u.powf(0.75);
        Ok(EhlContact {
            load: w * e_reduced * rx * rx,
            rx,
            ry: rx * self.ry_over_rx,
            sum_velocity: u * e_reduced * rx / eta0,
            e_reduced,
            lubricant: Lubricant {
                viscosity: eta0,
                pressure_viscosity: alpha,
                density: REFERENCE_DENSITY,
                viscosity_model: self.viscosity,
                density_model: self.density,
            },
        })
    }
}

/// The Hertz deflection δ_H of a contact at its load, m: the approach scale of the
/// dimensionless law.
pub fn hertz_deflection(c: &EhlContact) -> Result<f64, LawMapError> {
    Ok(hertz_at_load(c)?.deflection)
}

/// The dry Hertz contact of `c` at its load (the scales of the dimensionless laws).
fn hertz_at_load(c: &EhlContact) -> Result<HertzContact, LawMapError> {
    let g = HertzGeometry::new(c.rx, c.ry, c.e_reduced)
        .map_err(|e| invalid("rx, ry, e_reduced", c.ry / c.rx, &e.to_string()))?;
    Ok(g.contact(positive("load [N]", c.load)?))
}

/// The damping scale w0·b/(δ_H·u_s) of a contact, N·s/m: c = ĉ·w0·b/(δ_H·u_s), with b the
/// Hertz semi-width along the rolling direction and δ_H the Hertz deflection at w0 (the time
/// the oil takes to cross b, b/u_s, over the Hertz secant compliance δ_H/w0).
pub fn damping_scale(c: &EhlContact) -> Result<f64, LawMapError> {
    let h = hertz_at_load(c)?;
    Ok(c.load * h.semi_minor / (h.deflection * positive("sum_velocity [m/s]", c.sum_velocity)?))
}

/// The harmonic law's mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) of a contact and the mass `m`
/// (kg) on it: the natural frequency of the mass on the Hertz secant stiffness w0/δ_H times
/// the time the oil takes to cross the Hertz semi-width b (docs/law_map.md §7). Computable
/// without an EHL solution; at fixed other groups it is in one-to-one relation with
/// Ψ = ω_n·b/u_s of the lubricated contact's linearized stiffness.
pub fn mass_group(c: &EhlContact, mass: f64) -> Result<f64, LawMapError> {
    let m = positive("ball mass [kg]", mass)?;
    let h = hertz_at_load(c)?;
    let u_s = positive("sum_velocity [m/s]", c.sum_velocity)?;
    Ok(crate::contact::mass_group(
        h.semi_minor,
        h.deflection,
        c.load,
        u_s,
        m,
    ))
}

/// The mass (kg) that gives contact `c` the mass group `psi_h` ([`mass_group`] inverted):
/// m = (w0/δ_H)·(b/(u_s·Ψ_H))².
pub fn mass_for_group(c: &EhlContact, psi_h: f64) -> Result<f64, LawMapError> {
    let psi = positive("psi_h", psi_h)?;
    let h = hertz_at_load(c)?;
    let t = h.semi_minor / (positive("sum_velocity [m/s]", c.sum_velocity)? * psi);
    Ok(c.load / h.deflection * t * t)
}

/// A quasi-static law Q = K·δ^d + ΔF made dimensionless with the operating load w0 and the
/// Hertz deflection δ_H at w0: Q/w0 = K̂·(δ/δ_H)^d + ΔF̂.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DimensionlessLaw {
    /// K̂ = K·δ_H^d/w0.
    pub k_hat: f64,
    /// The index d.
    pub d: f64,
    /// ΔF̂ = ΔF/w0.
    pub delta_f_hat: f64,
    /// The approach at w0 over δ_H (of the steady solution at w0).
    pub approach_hat: f64,
    /// The fitted range of approaches over δ_H.
    pub range_hat: [f64; 2],
    /// The harmonic law's damping made dimensionless, ĉ = c·δ_H·u_s/(w0·b) (b the Hertz
    /// semi-width along the rolling direction at w0); None for the quasi-static law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c_hat: Option<f64>,
}

impl DimensionlessLaw {
    /// The dimensionless form of a fit of contact `c` (its load is the fit's w0).
    /// A harmonic fit's damping c becomes ĉ = c·δ_H·u_s/(w0·b) ([`damping_scale`]).
    pub fn of_fit(fit: &ContactFit, c: &EhlContact) -> Result<DimensionlessLaw, LawMapError> {
        let dh = hertz_deflection(c)?;
        let w0 = c.load;
        let c_hat = match fit.c {
            Some(damping) => Some(damping / damping_scale(c)?),
            None => None,
        };
        Ok(DimensionlessLaw {
            k_hat: fit.k * dh.powf(fit.d) / w0,
            d: fit.d,
            delta_f_hat: fit.delta_f / w0,
            approach_hat: fit.approach / dh,
            range_hat: [fit.delta_range[0] / dh, fit.delta_range[1] / dh],
            c_hat,
        })
    }

    /// The damping c of contact `c`, N·s/m (None for the quasi-static law).
    pub fn damping(&self, c: &EhlContact) -> Result<Option<f64>, LawMapError> {
        match self.c_hat {
            Some(ch) => Ok(Some(ch * damping_scale(c)?)),
            None => Ok(None),
        }
    }

    /// Q/w0 at δ/δ_H = `approach_hat` (the power law, no extension).
    pub fn force_hat(&self, approach_hat: f64) -> f64 {
        self.k_hat * approach_hat.powf(self.d) + self.delta_f_hat
    }

    /// (K in N/m^d, d, ΔF in N, fitted range in m) of contact `c`.
    pub fn dimensional(&self, c: &EhlContact) -> Result<(f64, f64, f64, [f64; 2]), LawMapError> {
        let dh = hertz_deflection(c)?;
        let w0 = c.load;
        Ok((
            self.k_hat * w0 / dh.powf(self.d),
            self.d,
            self.delta_f_hat * w0,
            [self.range_hat[0] * dh, self.range_hat[1] * dh],
        ))
    }

    /// The law of contact `c`, ready for the bearing model (the fitted law with its extension
    /// below the fitted range).
    /// With ĉ (harmonic law) the law carries the damping c ([`DimensionlessLaw::damping`]).
    pub fn law(&self, c: &EhlContact) -> Result<FittedLaw, crate::Error> {
        let (k, d, df, [lo, hi]) = self.dimensional(c)?;
        let law = FittedLaw::new(k, d, df, lo, hi)?;
        Ok(match self.damping(c)? {
            Some(damping) => law.with_damping(damping)?,
            None => law,
        })
    }
}

mod file;
mod map;
mod sparse;
mod summary;

pub use file::BINARY_MAGIC;
pub use summary::MapSummary;

pub use map::{
    tightened, Group, LawKind, LawMap, LawMapSpec, MapAxis, MapQuery, NodeQuality, FORMAT,
};
