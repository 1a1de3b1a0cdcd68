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
//! [operating]
//! inner_speed_rpm = 5000.0       # default 0
//! outer_speed_rpm = 0.0          # default 0
//! force_axial_n = 1000.0         # or displacement_axial_mm; default force 0
//! force_y_n = 1000.0             # or displacement_y_mm
//! force_z_n = 1000.0             # or displacement_z_mm
//! tilt_y_deg = 0.001             # or moment_y_nm; default moment 0
//! tilt_z_deg = 0.001             # or moment_z_nm
//! race_control = "outer"         # "inner", "none", "no-gyroscopic"; default "outer"
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

use super::InputError;
use crate::bearing::{
    Bearing, BearingGeometry, Control, EquilibriumSettings, Kinematics, OperatingPoint, RaceControl,
};
use crate::material::{DensityModel, Lubricant, Solid, ViscosityModel};
use serde::Deserialize;
use std::f64::consts::PI;
use std::path::Path;

/// A validated bearing case, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Optional bearing name.
    pub name: Option<String>,
    /// Geometry and materials.
    pub bearing: Bearing,
    /// Lubricant (the default mineral oil when the file has no `[lubricant]`).
    pub lubricant: Lubricant,
    /// Whether the lubricant was given in the file (false: the default was used).
    pub lubricant_given: bool,
    /// Speeds, loads and race control.
    pub operating: OperatingPoint,
    /// Equilibrium solver settings.
    pub settings: EquilibriumSettings,
    /// Characterization method given in the file (`method`, `[method_options]`), if any.
    pub method: Option<crate::method::Method>,
    /// The file's `[method_options]` table as given (so that a command-line override of the
    /// method name can apply the same options).
    pub method_options: Option<toml::Table>,
}

impl Case {
    /// The method to characterize this case with: `name` if given (with the file's
    /// `[method_options]` when `name` is the file's own method), else the file's method, else the
    /// default (quasi-static).
    pub fn method_or(
        &self,
        name: Option<&str>,
    ) -> Result<crate::method::Method, crate::method::MethodError> {
        match (name, &self.method) {
            (Some(n), Some(m)) if n == m.name() => Ok(*m),
            (Some(n), _) => crate::method::Method::parse(n, None),
            (None, Some(m)) => Ok(*m),
            (None, None) => Ok(crate::method::Method::default()),
        }
    }
}

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
        MethodError::Law(m) => InputError::field("method", "", m),
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
    let raw: RawCase = super::from_toml(text, origin)?;
    let method = match (&raw.method, &raw.method_options) {
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
    };
    let b = &raw.bearing;
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
    let geometry = BearingGeometry::new(ball_count as usize, d * 1e-3, dm * 1e-3, fi, fo, alpha0)
        .map_err(|e| InputError::field("bearing", "", e.to_string()))?;
    let ball_material = solid(raw.ball_material.as_ref(), "ball_material")?;
    let ring_material = solid(raw.ring_material.as_ref(), "ring_material")?;
    let (lubricant, lubricant_given) = match raw.lubricant.as_ref() {
        Some(l) => (lubricant(l, "lubricant")?, true),
        None => (Lubricant::DEFAULT_MINERAL_OIL, false),
    };
    let operating = operating(raw.operating.as_ref())?;
    let mut settings = EquilibriumSettings::default();
    if b.diametral_clearance_mm.is_some() {
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
    Ok(Case {
        name: b.name.clone(),
        bearing: Bearing {
            geometry,
            ball_material,
            ring_material,
        },
        lubricant,
        lubricant_given,
        operating,
        settings,
        method,
        method_options: raw.method_options.clone(),
    })
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

/// A lubricant from its case-file table (default mineral oil for absent keys).
pub(crate) fn lubricant(r: &RawLubricant, table: &str) -> Result<Lubricant, InputError> {
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
    };
    let o = raw.unwrap_or(&empty);
    let rpm = PI / 30.0;
    let speed = |v: Option<f64>, key: &str| -> Result<f64, InputError> {
        let s = v.unwrap_or(0.0);
        if s.is_finite() && s.abs() <= 1e6 {
            Ok(s * rpm)
        } else {
            Err(InputError::field(key, s, "a speed from −1e6 to 1e6 rpm"))
        }
    };
    // (load key, load unit, load→SI factor, displacement key, unit, displacement→SI factor)
    let dof = |load: Option<f64>,
               lkey: &str,
               lunit: &str,
               disp: Option<f64>,
               dkey: &str,
               dunit: &str,
               dfac: f64|
     -> Result<Control, InputError> {
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
    };
    let tilt_limit = |c: Control, key: &str| match c {
        Control::Displacement(t) if t.abs() > 1f64.to_radians() => Err(InputError::field(
            &format!("operating.{key}"),
            t.to_degrees(),
            "a tilt within ±1 degree (the model assumes small rotations)",
        )),
        _ => Ok(c),
    };
    let disp_limit = |c: Control, key: &str| match c {
        Control::Displacement(x) if x.abs() > 1e-3 => Err(InputError::field(
            &format!("operating.{key}"),
            x * 1e3,
            "a displacement within ±1 mm",
        )),
        _ => Ok(c),
    };
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
