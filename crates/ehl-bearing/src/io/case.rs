//! Bearing case files.
//!
//! ```toml
//! method = "quasi-static"        # optional: the method `characterize` uses unless --method is
//!                                # given ("quasi-static" default, "harmonic", "hertz")
//! [method_options]               # optional, its options (Method::parse), e.g. grid = 257
//!
//! [bearing]
//! name = "7006 15°"              # optional
//! ball_count = 11
//! ball_diameter_mm = 7.0
//! pitch_diameter_mm = 42.5
//! inner_conformity = 0.51        # f_i = r_i/D, > 0.5
//! outer_conformity = 0.54
//! contact_angle_deg = 15.0       # or diametral_clearance_mm
//!
//! [ball_material]                # optional, default AISI 52100 (also [ring_material])
//! youngs_modulus_gpa = 208.0
//! poisson_ratio = 0.3
//! density_kg_m3 = 7850.0
//!
//! [lubricant]                    # optional, default mineral oil (see Lubricant::DEFAULT_MINERAL_OIL)
//! viscosity_pa_s = 0.04
//! pressure_viscosity_1_pa = 2.2e-8
//! density_kg_m3 = 870.0
//! viscosity_model = "roelands"   # or "barus"
//! density_model = "dowson-higginson"  # or "incompressible"
//!
//! # or described (crate::oil; docs/lubricant.md), with operating.temperature_c:
//! # iso_vg = 32                  # or viscosity_40c_mm2_s = 32.0
//! # viscosity_index = 100.0      # or viscosity_100c_mm2_s = 5.4
//! # base_oil = "mineral"         # default; "pao", "ester", "other" need Z or α below
//! # density_15c_kg_m3 = 870.0
//! # pressure_viscosity_index_z = 0.72     # optional: Roelands' Z (default for mineral oils)
//! # pressure_viscosity_1_pa = 2.0e-8      # optional: α at the operating temperature
//! # thermal_conductivity_w_m_k = 0.1      # optional (inlet shear heating estimate)
//!
//! # ball_material and ring_material also take roughness_rq_um (RMS roughness, µm; both or
//! # neither): the film parameter Λ (crate::lubrication).
//!
//! [operating]
//! inner_speed_rpm = 5000.0       # default 0
//! outer_speed_rpm = 0.0          # default 0
//! force_axial_n = 1000.0         # or displacement_axial_mm; default force 0
//! force_y_n = 1000.0             # or displacement_y_mm
//! force_z_n = 1000.0             # or displacement_z_mm
//! tilt_y_deg = 0.001             # or moment_y_nm; default moment 0
//! tilt_z_deg = 0.001             # or moment_z_nm
//! race_control = "outer"         # "inner", "none", "no-gyroscopic"; default "outer"
//! temperature_c = 60.0           # operating oil temperature, °C (described lubricant only)
//! # inner_ring_temperature_c = 70.0  # optional, both or neither (described lubricant only):
//! # outer_ring_temperature_c = 55.0  # each raceway's lubrication figures at its ring's oil
//! # inlet_meniscus_distance_mm = 0.3 # optional: an oil supply that starves the contacts; the
//! #                                  # distance from each contact's centre to the upstream oil
//! #                                  # meniscus, mm (the starvation estimate, crate::lubrication)
//!
//! [equilibrium]                  # optional solver settings
//! tolerance = 1e-11              # relative force tolerance
//! max_iterations = 100
//! min_contact_angle_deg = -5.0   # shoulder limit of the inner contact angle; -90 with
//!                                # diametral_clearance_mm (deep-groove bearings)
//! kinematics = "operating-angles" # ball speeds and Hertz constants at each contact's operating
//!                                # angle (textbook, default) or "groove-line" (the earlier
//!                                # model; README, "Modelling choices of the bearing model")
//! ```

use crate::bearing::{
    Bearing, BearingGeometry, Control, EquilibriumSettings, Kinematics, OperatingPoint, RaceControl,
};
use crate::case::{Case, InputError, RingOils, Roughness};
use crate::material::{DensityModel, Lubricant, Solid, ViscosityModel};
use crate::oil::{BaseOil, OilDescription, OilProperties};
use serde::Deserialize;
use std::f64::consts::PI;
use std::path::Path;

/// A method error as an input error naming the key of the file.
pub(crate) fn method_input_error(e: crate::method::MethodError) -> InputError {
    use crate::method::{Method, MethodError};
    match e {
        MethodError::Setting {
            field,
            value,
            expected,
        } => InputError::Field {
            field,
            value,
            expected,
        },
        MethodError::UnknownMethod { name } => InputError::Field {
            field: "method".into(),
            value: name,
            expected: format!("one of {}", Method::NAMES.join(", ")),
        },
        e @ (MethodError::LawShortOfLoad { .. }
        | MethodError::NoPredictor { .. }
        | MethodError::Cancelled) => InputError::field("method", "", e.to_string()),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCase {
    method: Option<String>,
    method_options: Option<toml::Table>,
    bearing: RawBearing,
    ball_material: Option<RawSolid>,
    ring_material: Option<RawSolid>,
    lubricant: Option<RawLubricant>,
    operating: Option<RawOperating>,
    equilibrium: Option<RawEquilibrium>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBearing {
    name: Option<String>,
    ball_count: Option<i64>,
    ball_diameter_mm: Option<f64>,
    pitch_diameter_mm: Option<f64>,
    inner_conformity: Option<f64>,
    outer_conformity: Option<f64>,
    contact_angle_deg: Option<f64>,
    diametral_clearance_mm: Option<f64>,
}

/// A solid in case-file units.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSolid {
    youngs_modulus_gpa: Option<f64>,
    poisson_ratio: Option<f64>,
    density_kg_m3: Option<f64>,
    /// RMS surface roughness Rq, µm (case files only).
    pub(crate) roughness_rq_um: Option<f64>,
}

/// A lubricant in case-file units.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLubricant {
    viscosity_pa_s: Option<f64>,
    pressure_viscosity_1_pa: Option<f64>,
    density_kg_m3: Option<f64>,
    viscosity_model: Option<ViscosityModel>,
    density_model: Option<DensityModel>,
    iso_vg: Option<i64>,
    viscosity_40c_mm2_s: Option<f64>,
    viscosity_100c_mm2_s: Option<f64>,
    viscosity_index: Option<f64>,
    base_oil: Option<String>,
    density_15c_kg_m3: Option<f64>,
    pressure_viscosity_index_z: Option<f64>,
    thermal_conductivity_w_m_k: Option<f64>,
}

impl RawLubricant {
    /// The first description key given (the lubricant is described rather than given by its
    /// constants), if any.
    fn description_key(&self) -> Option<&'static str> {
        [
            ("iso_vg", self.iso_vg.is_some()),
            ("viscosity_40c_mm2_s", self.viscosity_40c_mm2_s.is_some()),
            ("viscosity_100c_mm2_s", self.viscosity_100c_mm2_s.is_some()),
            ("viscosity_index", self.viscosity_index.is_some()),
            ("base_oil", self.base_oil.is_some()),
            ("density_15c_kg_m3", self.density_15c_kg_m3.is_some()),
            (
                "pressure_viscosity_index_z",
                self.pressure_viscosity_index_z.is_some(),
            ),
            (
                "thermal_conductivity_w_m_k",
                self.thermal_conductivity_w_m_k.is_some(),
            ),
        ]
        .into_iter()
        .find(|(_, given)| *given)
        .map(|(k, _)| k)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOperating {
    inner_speed_rpm: Option<f64>,
    outer_speed_rpm: Option<f64>,
    force_axial_n: Option<f64>,
    displacement_axial_mm: Option<f64>,
    force_y_n: Option<f64>,
    displacement_y_mm: Option<f64>,
    force_z_n: Option<f64>,
    displacement_z_mm: Option<f64>,
    moment_y_nm: Option<f64>,
    tilt_y_deg: Option<f64>,
    moment_z_nm: Option<f64>,
    tilt_z_deg: Option<f64>,
    race_control: Option<RaceControl>,
    temperature_c: Option<f64>,
    inner_ring_temperature_c: Option<f64>,
    outer_ring_temperature_c: Option<f64>,
    inlet_meniscus_distance_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEquilibrium {
    tolerance: Option<f64>,
    max_iterations: Option<i64>,
    min_contact_angle_deg: Option<f64>,
    kinematics: Option<String>,
}

/// Read and validate a case file.
pub fn read_case(path: &Path) -> Result<Case, InputError> {
    let text = super::read_text(path)?;
    parse_case(&text, &path.display().to_string())
}

/// Parse and validate case-file text; `origin` names the source in messages.
pub fn parse_case(text: &str, origin: &str) -> Result<Case, InputError> {
    case_from_raw(&super::from_toml(text, origin)?)
}

/// Validate a case given as the file's tables already parsed (keys and units as in the file,
/// e.g. built from a Python dict); `origin` names the source in messages. The same checks and
/// messages as [`parse_case`].
pub fn case_from_table(table: toml::Table, origin: &str) -> Result<Case, InputError> {
    case_from_raw(&super::from_toml_value(toml::Value::Table(table), origin)?)
}

fn case_from_raw(raw: &RawCase) -> Result<Case, InputError> {
    let method = case_method(raw)?;
    let b = &raw.bearing;
    let geometry = geometry(b)?;
    let ball_material = solid(raw.ball_material.as_ref(), "ball_material")?;
    let ring_material = solid(raw.ring_material.as_ref(), "ring_material")?;
    let (lubricant, lubricant_given, oil, ring_oils) = case_lubricant(raw)?;
    let roughness = roughness(raw.ball_material.as_ref(), raw.ring_material.as_ref())?;
    let inlet_meniscus_distance_m = inlet_meniscus_distance(raw.operating.as_ref())?;
    let operating = operating(raw.operating.as_ref())?;
    let settings = equilibrium_settings(raw)?;
    Ok(Case {
        name: b.name.clone(),
        bearing: Bearing {
            geometry,
            ball_material,
            ring_material,
        },
        lubricant,
        lubricant_given,
        oil,
        roughness,
        ring_oils,
        inlet_meniscus_distance_m,
        operating,
        settings,
        method,
    })
}

/// The method of a case file (`method`, `[method_options]`), if given.
fn case_method(raw: &RawCase) -> Result<Option<crate::method::Method>, InputError> {
    Ok(match (&raw.method, &raw.method_options) {
        (Some(name), options) => Some(
            crate::method::Method::parse(name, options.as_ref()).map_err(method_input_error)?,
        ),
        (None, Some(_)) => {
            return Err(InputError::Missing {
                field: "method".into(),
                hint: "[method_options] is given: name its method (method = \"quasi-static\", \"harmonic\" or \"hertz\")".into(),
            })
        }
        (None, None) => None,
    })
}

/// The bearing's geometry from `[bearing]`.
fn geometry(b: &RawBearing) -> Result<BearingGeometry, InputError> {
    let ball_count = require(
        b.ball_count,
        "bearing.ball_count",
        "the number of balls, ≥ 3",
    )?;
    if !(3..=1000).contains(&ball_count) {
        return Err(InputError::field(
            "bearing.ball_count",
            ball_count,
            "an integer from 3 to 1000",
        ));
    }
    let d = size(
        require(
            b.ball_diameter_mm,
            "bearing.ball_diameter_mm",
            "the ball diameter in mm",
        )?,
        "bearing.ball_diameter_mm",
    )?;
    let dm = size(
        require(
            b.pitch_diameter_mm,
            "bearing.pitch_diameter_mm",
            "the pitch diameter in mm",
        )?,
        "bearing.pitch_diameter_mm",
    )?;
    if d >= dm {
        return Err(InputError::field(
            "bearing.ball_diameter_mm",
            d,
            format!(
                "less than bearing.pitch_diameter_mm = {dm} (are ball and pitch diameter swapped?)"
            ),
        ));
    }
    let conformity = |v: Option<f64>, key: &str| -> Result<f64, InputError> {
        let f = require(v, key, "groove radius over ball diameter, e.g. 0.52")?;
        if f.is_finite() && (CONFORMITY_MIN..5.0).contains(&f) {
            Ok(f)
        } else {
            Err(InputError::field(
                key,
                f,
                "groove radius over ball diameter, at least 0.501 and less than 5 (ball-bearing \
                 grooves: about 0.505 to 0.54; closer to 0.5 the groove wraps the ball and the \
                 Hertz point contact no longer describes it)",
            ))
        }
    };
    let fi = conformity(b.inner_conformity, "bearing.inner_conformity")?;
    let fo = conformity(b.outer_conformity, "bearing.outer_conformity")?;
    let alpha0 = match (b.contact_angle_deg, b.diametral_clearance_mm) {
        (Some(_), Some(_)) => {
            return Err(InputError::Conflict {
                first: "bearing.contact_angle_deg".into(),
                second: "bearing.diametral_clearance_mm".into(),
            })
        }
        (None, None) => {
            return Err(InputError::Missing {
                field: "bearing.contact_angle_deg".into(),
                hint: "give the free contact angle in degrees or bearing.diametral_clearance_mm"
                    .into(),
            })
        }
        (Some(a), None) => {
            if !(a.is_finite() && (0.0..=85.0).contains(&a)) {
                return Err(InputError::field(
                    "bearing.contact_angle_deg",
                    a,
                    "0 to 85 degrees",
                ));
            }
            a.to_radians()
        }
        (None, Some(pd)) => {
            let max = 2.0 * (fi + fo - 1.0) * d;
            if !(pd.is_finite() && pd >= 0.0 && pd < max) {
                return Err(InputError::field(
                    "bearing.diametral_clearance_mm",
                    pd,
                    format!("0 ≤ P_d < 2(f_i + f_o − 1)·D = {max:.6} mm"),
                ));
            }
            BearingGeometry::contact_angle_from_clearance(d * 1e-3, fi, fo, pd * 1e-3).map_err(
                |e| InputError::field("bearing.diametral_clearance_mm", pd, e.to_string()),
            )?
        }
    };
    let chord = dm * (PI / ball_count as f64).sin();
    if chord <= d {
        return Err(InputError::field(
            "bearing.ball_count",
            ball_count,
            format!(
                "few enough balls to fit: {ball_count} balls of bearing.ball_diameter_mm = {d} overlap on bearing.pitch_diameter_mm = {dm} (neighbour spacing {chord:.3} mm)"
            ),
        ));
    }
    BearingGeometry::new(ball_count as usize, d * 1e-3, dm * 1e-3, fi, fo, alpha0)
        .map_err(|e| InputError::field("bearing", "", e.to_string()))
}

/// The lubricant (given, described at `operating.temperature_c`, or the default), whether the
/// file gives it, the described oil's constants and those at the ring temperatures.
#[allow(clippy::type_complexity)]
fn case_lubricant(
    raw: &RawCase,
) -> Result<(Lubricant, bool, Option<OilProperties>, Option<RingOils>), InputError> {
    let temperature = raw.operating.as_ref().and_then(|o| o.temperature_c);
    let ring_temperatures = ring_temperatures(raw.operating.as_ref())?;
    let (lubricant, lubricant_given, oil, ring_oils) = match raw.lubricant.as_ref() {
        Some(l) if l.description_key().is_some() => {
            let t = temperature.ok_or_else(|| InputError::Missing {
                field: "operating.temperature_c".into(),
                hint: "the lubricant is described (by grade or viscosities): give the operating \
                       oil temperature in °C"
                    .into(),
            })?;
            let (lub, oil, desc) = described_lubricant(l, t)?;
            // A given α holds at temperature_c: at the rings, its Z (Roelands, constant with
            // temperature) carries it, as for a given Z.
            let ring_desc = OilDescription {
                pressure_viscosity_1_pa: None,
                pressure_viscosity_index_z: Some(oil.roelands_z),
                ..desc
            };
            let at_ring = |t: f64, key: &str| -> Result<OilProperties, InputError> {
                let mut o = oil_at(&ring_desc, t, key)?;
                if desc.pressure_viscosity_1_pa.is_some() {
                    for s in o.sources.iter_mut().filter(|s| s.quantity == "roelands_z") {
                        s.source = "Z = α·p0/(ln η0 + 9.67) of the α given at \
                                    operating.temperature_c, Roelands (1966), constant with \
                                    temperature"
                            .into();
                    }
                } else if desc.pressure_viscosity_index_z.is_none() {
                    // The built-in Z: the same sources as at temperature_c.
                    o.sources.clone_from(&oil.sources);
                }
                Ok(o)
            };
            let ring_oils = match ring_temperatures {
                None => None,
                Some((ti, to)) => Some(RingOils {
                    inner: at_ring(ti, "operating.inner_ring_temperature_c")?,
                    outer: at_ring(to, "operating.outer_ring_temperature_c")?,
                }),
            };
            (lub, true, Some(oil), ring_oils)
        }
        Some(l) => (lubricant(l, "lubricant")?, true, None, None),
        None => (Lubricant::DEFAULT_MINERAL_OIL, false, None, None),
    };
    if let (Some((ti, _)), None) = (ring_temperatures, &oil) {
        return Err(InputError::field(
            "operating.inner_ring_temperature_c",
            ti,
            "no ring temperatures with a lubricant given by its constants (or the default): \
             describe the lubricant (lubricant.iso_vg or lubricant.viscosity_40c_mm2_s, …; \
             docs/lubricant.md) for the temperatures to matter",
        ));
    }
    if let (Some(t), None) = (temperature, &oil) {
        return Err(InputError::field(
            "operating.temperature_c",
            t,
            "no temperature with a lubricant given by its constants (or the default): describe \
             the lubricant (lubricant.iso_vg or lubricant.viscosity_40c_mm2_s, …; \
             docs/lubricant.md) for the temperature to matter",
        ));
    }
    Ok((lubricant, lubricant_given, oil, ring_oils))
}

/// The equilibrium solver's settings from `[equilibrium]` (a bearing given by its clearance is a
/// deep-groove bearing: shoulders on both sides).
fn equilibrium_settings(raw: &RawCase) -> Result<EquilibriumSettings, InputError> {
    let mut settings = EquilibriumSettings::default();
    if raw.bearing.diametral_clearance_mm.is_some() {
        // Given by its clearance: a deep-groove bearing, shoulders on both sides.
        settings.min_contact_angle = -PI / 2.0;
    }
    if let Some(e) = &raw.equilibrium {
        if let Some(k) = &e.kinematics {
            settings.kinematics = match k.as_str() {
                "operating-angles" => Kinematics::OperatingAngles,
                "groove-line" => Kinematics::GrooveLine,
                _ => {
                    return Err(InputError::field(
                        "equilibrium.kinematics",
                        format!("\"{k}\""),
                        "\"operating-angles\" (default) or \"groove-line\"",
                    ))
                }
            };
        }
        if let Some(a) = e.min_contact_angle_deg {
            if !(a.is_finite() && (-90.0..=0.0).contains(&a)) {
                return Err(InputError::field(
                    "equilibrium.min_contact_angle_deg",
                    a,
                    "−90 to 0 degrees",
                ));
            }
            settings.min_contact_angle = a.to_radians();
        }
        if let Some(t) = e.tolerance {
            if !(t.is_finite() && t > 0.0 && t < 1e-2) {
                return Err(InputError::field(
                    "equilibrium.tolerance",
                    t,
                    "a relative tolerance between 0 and 1e-2",
                ));
            }
            settings.tolerance = t;
        }
        if let Some(n) = e.max_iterations {
            if !(1..=100_000).contains(&n) {
                return Err(InputError::field(
                    "equilibrium.max_iterations",
                    n,
                    "an integer from 1 to 100000",
                ));
            }
            settings.max_iterations = n as usize;
        }
    }
    Ok(settings)
}

fn require<T>(v: Option<T>, key: &str, hint: &str) -> Result<T, InputError> {
    v.ok_or_else(|| InputError::Missing {
        field: key.to_string(),
        hint: hint.to_string(),
    })
}

/// A bearing dimension in mm: 0.01 mm (miniature balls are ≥ 0.3 mm) to 20 m (the largest
/// slewing bearings).
fn size(v: f64, key: &str) -> Result<f64, InputError> {
    if v.is_finite() && (0.01..=20_000.0).contains(&v) {
        Ok(v)
    } else {
        Err(InputError::field(
            key,
            v,
            "a dimension from 0.01 to 20000 mm",
        ))
    }
}

/// Smallest race conformity f = r/D accepted (dimensionless). The tightest ball-bearing grooves
/// are about 0.505; at f → 0.5 the transverse radius Ry = f·D/(2f − 1) diverges (Ry/Rx ≈ 300 at
/// 0.502 for the seed bearing, beyond 1000 below 0.5005) and the Hertz constant over the contact
/// angle cannot be represented (f = 0.5001).
pub const CONFORMITY_MIN: f64 = 0.501;

/// Density range of solids (balls and rings), kg/m³: from polymer balls (≈ 1000) past tungsten
/// carbide (≈ 15 600) to above osmium, the densest element (22 590).
pub const SOLID_DENSITY_RANGE: [f64; 2] = [500.0, 25_000.0];

fn positive(v: f64, key: &str, unit: &str) -> Result<f64, InputError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(InputError::field(
            key,
            v,
            format!("a positive finite number in {unit}"),
        ))
    }
}

fn finite(v: f64, key: &str, unit: &str) -> Result<f64, InputError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(InputError::field(
            key,
            v,
            format!("a finite number in {unit}"),
        ))
    }
}

/// A solid from its case-file table `table` (default AISI 52100 for absent keys).
pub(crate) fn solid(raw: Option<&RawSolid>, table: &str) -> Result<Solid, InputError> {
    let mut s = Solid::AISI_52100;
    if let Some(r) = raw {
        if let Some(e) = r.youngs_modulus_gpa {
            // Diamond, the stiffest solid, has about 1050–1200 GPa; below 0.1 GPa (rubbers) the
            // contact is soft EHL, which the piezoviscous models here do not describe.
            if !(e.is_finite() && (0.1..=1200.0).contains(&e)) {
                return Err(InputError::field(
                    &format!("{table}.youngs_modulus_gpa"),
                    e,
                    "0.1 to 1200 GPa (a solid's modulus: steel 208, silicon nitride 310, \
                     diamond ≈ 1100)",
                ));
            }
            s.youngs_modulus = e * 1e9;
        }
        if let Some(nu) = r.poisson_ratio {
            if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
                return Err(InputError::field(
                    &format!("{table}.poisson_ratio"),
                    nu,
                    "−1 < ν < 0.5",
                ));
            }
            s.poisson_ratio = nu;
        }
        if let Some(rho) = r.density_kg_m3 {
            let [lo, hi] = SOLID_DENSITY_RANGE;
            if !(rho.is_finite() && (lo..=hi).contains(&rho)) {
                return Err(InputError::field(
                    &format!("{table}.density_kg_m3"),
                    rho,
                    "500 to 25000 kg/m³ (polymer balls ≈ 1000, silicon nitride 3200, steel 7850, \
                     tungsten carbide ≈ 15600; osmium, the densest element, 22590)",
                ));
            }
            s.density = rho;
        }
    }
    Ok(s)
}

/// Ball and ring roughness from the material tables (both or neither).
fn roughness(
    ball: Option<&RawSolid>,
    ring: Option<&RawSolid>,
) -> Result<Option<Roughness>, InputError> {
    let rq = |r: Option<&RawSolid>, key: &str| -> Result<Option<f64>, InputError> {
        match r.and_then(|r| r.roughness_rq_um) {
            None => Ok(None),
            Some(v) if v.is_finite() && v > 0.0 && v <= 10.0 => Ok(Some(v * 1e-6)),
            Some(v) => Err(InputError::field(
                key,
                v,
                "an RMS roughness Rq from 0 (exclusive) to 10 µm (bearing balls about 0.01–0.05, \
                 ground or honed raceways 0.05–0.3)",
            )),
        }
    };
    let b = rq(ball, "ball_material.roughness_rq_um")?;
    let r = rq(ring, "ring_material.roughness_rq_um")?;
    match (b, r) {
        (Some(b), Some(r)) => Ok(Some(Roughness {
            ball_rq_m: b,
            ring_rq_m: r,
        })),
        (None, None) => Ok(None),
        (Some(_), None) => Err(InputError::Missing {
            field: "ring_material.roughness_rq_um".into(),
            hint: "ball_material.roughness_rq_um is given: give the raceways' RMS roughness too \
                   (the film parameter uses both)"
                .into(),
        }),
        (None, Some(_)) => Err(InputError::Missing {
            field: "ball_material.roughness_rq_um".into(),
            hint: "ring_material.roughness_rq_um is given: give the balls' RMS roughness too (the \
                   film parameter uses both)"
                .into(),
        }),
    }
}

/// The inner and outer ring temperatures of `[operating]`, °C: both or neither.
fn ring_temperatures(raw: Option<&RawOperating>) -> Result<Option<(f64, f64)>, InputError> {
    let Some(o) = raw else { return Ok(None) };
    match (o.inner_ring_temperature_c, o.outer_ring_temperature_c) {
        (None, None) => Ok(None),
        (Some(ti), Some(to)) => Ok(Some((ti, to))),
        (Some(_), None) => Err(InputError::Missing {
            field: "operating.outer_ring_temperature_c".into(),
            hint: "operating.inner_ring_temperature_c is given: give both ring temperatures, °C"
                .into(),
        }),
        (None, Some(_)) => Err(InputError::Missing {
            field: "operating.inner_ring_temperature_c".into(),
            hint: "operating.outer_ring_temperature_c is given: give both ring temperatures, °C"
                .into(),
        }),
    }
}

/// The distance to the upstream oil meniscus of `[operating]`, m (None: fully flooded).
fn inlet_meniscus_distance(raw: Option<&RawOperating>) -> Result<Option<f64>, InputError> {
    match raw.and_then(|o| o.inlet_meniscus_distance_mm) {
        None => Ok(None),
        Some(x) if x.is_finite() && x > 0.0 && x <= 100.0 => Ok(Some(x * 1e-3)),
        Some(x) => Err(InputError::field(
            "operating.inlet_meniscus_distance_mm",
            x,
            "a distance from 0 (exclusive) to 100 mm from each contact's centre to the upstream oil \
             meniscus (a contact starves when it is within a few Hertz semi-widths, typically \
             0.1–1 mm; leave the key out for a fully flooded inlet)",
        )),
    }
}

/// The described oil's constants at `t_c` °C, a ring temperature given by `key`.
fn oil_at(desc: &OilDescription, t_c: f64, key: &str) -> Result<OilProperties, InputError> {
    crate::oil::derive(desc, t_c).map_err(|e| match e {
        crate::oil::OilError::Range {
            quantity,
            value,
            expected,
        } => InputError::field(
            if quantity == "operating.temperature_c" {
                key
            } else {
                &quantity
            },
            value,
            expected,
        ),
        crate::oil::OilError::Missing { quantity, hint } => InputError::Missing {
            field: quantity,
            hint,
        },
    })
}

/// An oil error of a described lubricant's key `lubricant.{k}`.
fn oil_err(e: crate::oil::OilError, k: &str) -> InputError {
    match e {
        crate::oil::OilError::Range {
            value, expected, ..
        } => InputError::field(&format!("lubricant.{k}"), value, expected),
        crate::oil::OilError::Missing { quantity, hint } => InputError::Missing {
            field: quantity,
            hint,
        },
    }
}

/// A described lubricant's kinematic viscosities at 40 °C and 100 °C, mm²/s: ν40 from the ISO
/// grade or given, ν100 given or from the viscosity index (ASTM D2270).
fn described_viscosities(r: &RawLubricant) -> Result<(f64, f64), InputError> {
    let key = |k: &str| format!("lubricant.{k}");
    let nu40 = match (r.iso_vg, r.viscosity_40c_mm2_s) {
        (Some(_), Some(_)) => {
            return Err(InputError::Conflict {
                first: key("iso_vg"),
                second: key("viscosity_40c_mm2_s"),
            })
        }
        (None, None) => {
            return Err(InputError::Missing {
                field: key("iso_vg"),
                hint: "give the ISO 3448 viscosity grade or lubricant.viscosity_40c_mm2_s".into(),
            })
        }
        (Some(g), None) => u32::try_from(g)
            .ok()
            .and_then(crate::oil::iso_vg_midpoint)
            .ok_or_else(|| {
                InputError::field(
                    &key("iso_vg"),
                    g,
                    format!(
                        "an ISO 3448 grade: {}",
                        crate::oil::ISO_VG
                            .iter()
                            .map(|(g, _)| g.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?,
        (None, Some(v)) => {
            if !(v.is_finite() && v > 2.0 && v <= 10_000.0) {
                return Err(InputError::field(
                    &key("viscosity_40c_mm2_s"),
                    v,
                    "more than 2 and at most 10000 mm²/s (ISO VG 3 to beyond VG 3200)",
                ));
            }
            v
        }
    };
    let nu100 = match (r.viscosity_100c_mm2_s, r.viscosity_index) {
        (Some(_), Some(_)) => {
            return Err(InputError::Conflict {
                first: key("viscosity_100c_mm2_s"),
                second: key("viscosity_index"),
            })
        }
        (None, None) => {
            return Err(InputError::Missing {
                field: key("viscosity_index"),
                hint: "give the viscosity index (e.g. 95–105 for a solvent-refined mineral oil) \
                       or lubricant.viscosity_100c_mm2_s: the temperature dependence needs one"
                    .into(),
            })
        }
        (Some(v), None) => {
            if !(v.is_finite() && v >= 2.0 && v < nu40) {
                return Err(InputError::field(
                    &key("viscosity_100c_mm2_s"),
                    v,
                    format!("at least 2 mm²/s (ASTM D2270) and less than ν40 = {nu40} mm²/s"),
                ));
            }
            v
        }
        (None, Some(vi)) => {
            crate::oil::nu100_from_vi(nu40, vi).map_err(|e| oil_err(e, "viscosity_index"))?
        }
    };
    Ok((nu40, nu100))
}

/// A described lubricant (grade or viscosities, base oil, density at 15 °C) at `t_c` °C: the
/// constants for the models and their derivation.
fn described_lubricant(
    r: &RawLubricant,
    t_c: f64,
) -> Result<(Lubricant, OilProperties, OilDescription), InputError> {
    let key = |k: &str| format!("lubricant.{k}");
    let first = r.description_key().unwrap_or("iso_vg");
    if r.viscosity_pa_s.is_some() {
        return Err(InputError::Conflict {
            first: key("viscosity_pa_s"),
            second: key(first),
        });
    }
    if r.density_kg_m3.is_some() {
        return Err(InputError::Conflict {
            first: key("density_kg_m3"),
            second: key(first),
        });
    }
    let (nu40, nu100) = described_viscosities(r)?;
    let base_oil = match &r.base_oil {
        None => BaseOil::Mineral,
        Some(b) => BaseOil::parse(b).ok_or_else(|| {
            InputError::field(
                &key("base_oil"),
                format!("\"{b}\""),
                format!("one of {}", BaseOil::NAMES.join(", ")),
            )
        })?,
    };
    let rho15 = require(
        r.density_15c_kg_m3,
        &key("density_15c_kg_m3"),
        "the oil's density at 15 °C in kg/m³ (data sheet; mineral oils about 850–900)",
    )?;
    if !(rho15.is_finite() && (700.0..=2000.0).contains(&rho15)) {
        return Err(InputError::field(
            &key("density_15c_kg_m3"),
            rho15,
            "700 to 2000 kg/m³ (lubricating oils: PAO about 820, mineral 850–900, esters \
             900–1000, perfluoropolyethers up to 1900)",
        ));
    }
    if let Some(z) = r.pressure_viscosity_index_z {
        if !(z.is_finite() && z > 0.0 && z <= 2.0) {
            return Err(InputError::field(
                &key("pressure_viscosity_index_z"),
                z,
                "Roelands' pressure–viscosity index, more than 0 and at most 2 (mineral oils \
                 about 0.6–0.8)",
            ));
        }
    }
    if let Some(a) = r.pressure_viscosity_1_pa {
        if !(a.is_finite() && a > 0.0 && a < 1e-6) {
            return Err(InputError::field(
                &key("pressure_viscosity_1_pa"),
                a,
                "0 < α < 1e-6 1/Pa at the operating temperature (mineral oils: about 1e-8 to 3e-8)",
            ));
        }
    }
    let k_f = match r.thermal_conductivity_w_m_k {
        None => crate::oil::DEFAULT_THERMAL_CONDUCTIVITY,
        Some(k) if k.is_finite() && k > 0.01 && k <= 1.0 => k,
        Some(k) => {
            return Err(InputError::field(
                &key("thermal_conductivity_w_m_k"),
                k,
                "more than 0.01 and at most 1 W/(m·K) (oils about 0.1–0.15)",
            ))
        }
    };
    let desc = OilDescription {
        iso_vg: r.iso_vg.and_then(|g| u32::try_from(g).ok()),
        viscosity_40c_mm2_s: nu40,
        viscosity_100c_mm2_s: nu100,
        base_oil,
        density_15c_kg_m3: rho15,
        pressure_viscosity_index_z: r.pressure_viscosity_index_z,
        pressure_viscosity_1_pa: r.pressure_viscosity_1_pa,
        thermal_conductivity_w_m_k: k_f,
    };
    let props = crate::oil::derive(&desc, t_c).map_err(|e| match e {
        crate::oil::OilError::Range {
            quantity,
            value,
            expected,
        } if quantity.starts_with("operating.") => InputError::field(&quantity, value, expected),
        e => oil_err(e, "viscosity_40c_mm2_s"),
    })?;
    let lub = Lubricant {
        viscosity: props.viscosity_pa_s,
        pressure_viscosity: props.pressure_viscosity_1_pa,
        density: props.density_kg_m3,
        viscosity_model: r.viscosity_model.unwrap_or_default(),
        density_model: r.density_model.unwrap_or_default(),
    };
    Ok((lub, props, desc))
}

/// A lubricant from its case-file table (default mineral oil for absent keys).
pub(crate) fn lubricant(r: &RawLubricant, table: &str) -> Result<Lubricant, InputError> {
    if let Some(k) = r.description_key() {
        return Err(InputError::Field {
            field: format!("{table}.{k}"),
            value: "(given)".into(),
            expected: "a lubricant given by its constants (viscosity_pa_s, \
                       pressure_viscosity_1_pa, density_kg_m3) in contact files, which have no \
                       operating temperature; a described lubricant belongs in a bearing case"
                .into(),
        });
    }
    let mut l = Lubricant::DEFAULT_MINERAL_OIL;
    if let Some(v) = r.viscosity_pa_s {
        let key = format!("{table}.viscosity_pa_s");
        if !(v.is_finite() && v > 1e-5 && v < 1e4) {
            return Err(InputError::field(&key, v, "1e-5 to 1e4 Pa·s"));
        }
        l.viscosity = v;
    }
    if let Some(a) = r.pressure_viscosity_1_pa {
        let key = format!("{table}.pressure_viscosity_1_pa");
        if !(a.is_finite() && (0.0..1e-6).contains(&a)) {
            return Err(InputError::field(
                &key,
                a,
                "0 ≤ α < 1e-6 1/Pa (0: isoviscous; mineral oils: about 1e-8 to 3e-8)",
            ));
        }
        l.pressure_viscosity = a;
    }
    if let Some(rho) = r.density_kg_m3 {
        l.density = positive(rho, &format!("{table}.density_kg_m3"), "kg/m³")?;
    }
    if let Some(m) = r.viscosity_model {
        l.viscosity_model = m;
    }
    if let Some(m) = r.density_model {
        l.density_model = m;
    }
    Ok(l)
}

fn operating(raw: Option<&RawOperating>) -> Result<OperatingPoint, InputError> {
    let empty = RawOperating {
        inner_speed_rpm: None,
        outer_speed_rpm: None,
        force_axial_n: None,
        displacement_axial_mm: None,
        force_y_n: None,
        displacement_y_mm: None,
        force_z_n: None,
        displacement_z_mm: None,
        moment_y_nm: None,
        tilt_y_deg: None,
        moment_z_nm: None,
        tilt_z_deg: None,
        race_control: None,
        temperature_c: None,
        inner_ring_temperature_c: None,
        outer_ring_temperature_c: None,
        inlet_meniscus_distance_mm: None,
    };
    let o = raw.unwrap_or(&empty);
    Ok(OperatingPoint {
        inner_speed: speed(o.inner_speed_rpm, "operating.inner_speed_rpm")?,
        outer_speed: speed(o.outer_speed_rpm, "operating.outer_speed_rpm")?,
        dofs: [
            disp_limit(
                dof(
                    o.force_axial_n,
                    "force_axial_n",
                    "N",
                    o.displacement_axial_mm,
                    "displacement_axial_mm",
                    "mm",
                    1e-3,
                )?,
                "displacement_axial_mm",
            )?,
            disp_limit(
                dof(
                    o.force_y_n,
                    "force_y_n",
                    "N",
                    o.displacement_y_mm,
                    "displacement_y_mm",
                    "mm",
                    1e-3,
                )?,
                "displacement_y_mm",
            )?,
            disp_limit(
                dof(
                    o.force_z_n,
                    "force_z_n",
                    "N",
                    o.displacement_z_mm,
                    "displacement_z_mm",
                    "mm",
                    1e-3,
                )?,
                "displacement_z_mm",
            )?,
            tilt_limit(
                dof(
                    o.moment_y_nm,
                    "moment_y_nm",
                    "N·m",
                    o.tilt_y_deg,
                    "tilt_y_deg",
                    "degrees",
                    PI / 180.0,
                )?,
                "tilt_y_deg",
            )?,
            tilt_limit(
                dof(
                    o.moment_z_nm,
                    "moment_z_nm",
                    "N·m",
                    o.tilt_z_deg,
                    "tilt_z_deg",
                    "degrees",
                    PI / 180.0,
                )?,
                "tilt_z_deg",
            )?,
        ],
        race_control: o.race_control.unwrap_or_default(),
    })
}

/// A ring speed of `[operating]` in rpm (absent: 0) → rad/s.
fn speed(v: Option<f64>, key: &str) -> Result<f64, InputError> {
    let rpm = PI / 30.0;
    let s = v.unwrap_or(0.0);
    if s.is_finite() && s.abs() <= 1e6 {
        Ok(s * rpm)
    } else {
        Err(InputError::field(key, s, "a speed from −1e6 to 1e6 rpm"))
    }
}

/// One degree of freedom of `[operating]`: its load (key `lkey`, unit `lunit`) or its
/// displacement (key `dkey`, unit `dunit`, `dfac` to SI), not both; neither is a load of 0.
fn dof(
    load: Option<f64>,
    lkey: &str,
    lunit: &str,
    disp: Option<f64>,
    dkey: &str,
    dunit: &str,
    dfac: f64,
) -> Result<Control, InputError> {
    match (load, disp) {
        (Some(_), Some(_)) => Err(InputError::Conflict {
            first: format!("operating.{lkey}"),
            second: format!("operating.{dkey}"),
        }),
        (Some(f), None) => Ok(Control::Load(finite(
            f,
            &format!("operating.{lkey}"),
            lunit,
        )?)),
        (None, Some(x)) => {
            let x = finite(x, &format!("operating.{dkey}"), dunit)?;
            Ok(Control::Displacement(x * dfac))
        }
        (None, None) => Ok(Control::Load(0.0)),
    }
}

/// An imposed tilt within ±1 degree (the model assumes small rotations).
fn tilt_limit(c: Control, key: &str) -> Result<Control, InputError> {
    match c {
        Control::Displacement(t) if t.abs() > 1f64.to_radians() => Err(InputError::field(
            &format!("operating.{key}"),
            t.to_degrees(),
            "a tilt within ±1 degree (the model assumes small rotations)",
        )),
        _ => Ok(c),
    }
}

/// An imposed displacement within ±1 mm.
fn disp_limit(c: Control, key: &str) -> Result<Control, InputError> {
    match c {
        Control::Displacement(x) if x.abs() > 1e-3 => Err(InputError::field(
            &format!("operating.{key}"),
            x * 1e3,
            "a displacement within ±1 mm",
        )),
        _ => Ok(c),
    }
}
