//! Physical plausibility of valid inputs, checked before any expensive solve.
//!
//! A case can be made of valid numbers and still lie far outside what the models describe: a
//! contact pressure beyond what hardened bearing steel carries elastically (the Hertz and EHL
//! models assume an elastic half-space), a speed no rolling bearing reaches, or a lubricated
//! contact so heavily loaded that the EHL solver spends minutes before it fails. These checks
//! take a dry Hertz equilibrium (milliseconds) and refuse such inputs at once, naming the key,
//! its value and the range the models describe; milder excesses give warnings.
//!
//! The limits (docs/robustness.md):
//! - maximum Hertz pressure: warning above [`PRESSURE_WARN`] = 4.2 GPa, the ISO 76 static
//!   load-rating pressure of ball bearings (permanent deformation 1e-4 of the ball diameter);
//!   refused above [`PRESSURE_MAX`] = 5 GPa (beyond the compressive yield of hardened 52100
//!   steel under Hertzian contact: the elastic models no longer describe the contact);
//! - speed factor n·d_m (rpm · mm, the relative ring speed times the pitch diameter): warning
//!   above [`NDM_WARN`] = 2.5e6, the upper end of oil-lubricated super-precision angular-contact
//!   bearings in manufacturers' catalogues; refused above [`NDM_MAX`] = 4e6 (no rolling bearing
//!   runs there; the balls' centrifugal force outgrows the loads the model is meant for);
//! - Young's moduli: 0.1 to 1200 GPa in case and contact files (checked by the parsers; diamond,
//!   the stiffest solid, has about 1050–1200 GPa).

use crate::bearing::{solve_equilibrium, ContactLaws, Control, Race};
use crate::case::{Case, InputError};
use crate::ehl::EhlContact;
use crate::hertz::HertzGeometry;

/// Hertz pressure above which a warning is given, Pa (ISO 76 static limit of ball bearings).
pub const PRESSURE_WARN: f64 = 4.2e9;
/// Hertz pressure above which an input is refused, Pa.
pub const PRESSURE_MAX: f64 = 5.0e9;
/// Speed factor n·d_m (rpm·mm) above which a warning is given.
pub const NDM_WARN: f64 = 2.5e6;
/// Speed factor n·d_m (rpm·mm) above which an input is refused.
pub const NDM_MAX: f64 = 4.0e6;

/// The case file's load keys of the five DOFs (x, y, z, θy, θz), in the `[operating]` table.
const LOAD_KEYS: [&str; 5] = [
    "force_axial_n",
    "force_y_n",
    "force_z_n",
    "moment_y_nm",
    "moment_z_nm",
];

/// The load keys of a case's operating point that are given as loads, with their values, in
/// case-file units (for messages).
fn load_keys(case: &Case) -> (String, String) {
    let names = LOAD_KEYS;
    let mut keys = Vec::new();
    let mut values = Vec::new();
    for (k, c) in case.operating.dofs.iter().enumerate() {
        if let Control::Load(v) = c {
            if *v != 0.0 {
                keys.push(format!("operating.{}", names[k]));
                values.push(format!("{v}"));
            }
        }
    }
    if keys.is_empty() {
        ("operating (imposed displacements)".into(), String::new())
    } else {
        (keys.join(", "), values.join(", "))
    }
}

/// The largest load one ball's inner contact carries at [`PRESSURE_MAX`], N, at the contact
/// angle that lets it carry most (90°, the largest rolling radius Rx): no ball load can exceed
/// it while the dry Hertz pressure stays within the models. `None` if the Hertz constants fail.
fn inner_capacity(case: &Case) -> Option<f64> {
    let g = case
        .bearing
        .hertz(Race::Inner, std::f64::consts::FRAC_PI_2)
        .ok()?;
    let p1 = g.contact(1.0).max_pressure;
    let q = (PRESSURE_MAX / p1).powi(3);
    (q.is_finite() && q > 0.0).then_some(q)
}

/// A necessary bound on the given loads, checked before any equilibrium: every force the shaft
/// passes to the bearing goes through the Z inner contacts, so |F| ≤ Z·Q_cap and |M| ≤ Z·Q_cap·d_m
/// with Q_cap from [`inner_capacity`]. Loads beyond it (e.g. 1e300 N, which made the equilibrium's
/// residual NaN) are refused naming the key, the value and the bound.
fn check_load_bounds(case: &Case) -> Result<(), InputError> {
    let Some(cap) = inner_capacity(case) else {
        return Ok(());
    };
    let geo = &case.bearing.geometry;
    let z = geo.ball_count as f64;
    let names = LOAD_KEYS;
    for (k, c) in case.operating.dofs.iter().enumerate() {
        let Control::Load(v) = c else { continue };
        let (bound, unit, arm) = if k < 3 {
            (z * cap, "N", String::new())
        } else {
            (
                z * cap * geo.pitch_diameter,
                "N·m",
                format!(" times the pitch diameter {} mm", geo.pitch_diameter * 1e3),
            )
        };
        if v.is_nan() || v.abs() > bound {
            return Err(InputError::field(
                &format!("operating.{}", names[k]),
                crate::case::number_text(*v),
                format!(
                    "|value| ≤ {bound:.4e} {unit}: {} balls each at the {:.1} GPa limit of the \
                     inner contact ({cap:.4e} N per ball){arm} carry no more (docs/robustness.md)",
                    geo.ball_count,
                    PRESSURE_MAX * 1e-9
                ),
            ));
        }
    }
    Ok(())
}

/// Checks a validated case: refuses inputs outside what the models describe (an
/// [`InputError::Field`] naming the key, its value and the range) and returns warnings for
/// milder excesses. A dry equilibrium that fails is not an error here (the solve that follows
/// reports it with its own message).
pub fn check_case(case: &Case) -> Result<Vec<String>, InputError> {
    let mut warnings = Vec::new();
    let rpm = 30.0 / std::f64::consts::PI;
    let op = &case.operating;
    let dm_mm = case.bearing.geometry.pitch_diameter * 1e3;
    let relative_rpm = (op.inner_speed - op.outer_speed).abs() * rpm;
    let ndm = relative_rpm * dm_mm;
    let speed_key = if op.inner_speed.abs() >= op.outer_speed.abs() {
        ("operating.inner_speed_rpm", op.inner_speed * rpm)
    } else {
        ("operating.outer_speed_rpm", op.outer_speed * rpm)
    };
    if ndm > NDM_MAX {
        return Err(InputError::field(
            speed_key.0,
            crate::case::number_text(speed_key.1),
            format!(
                "a speed factor n·d_m ≤ {NDM_MAX:.1e} rpm·mm (here {ndm:.3e} with d_m = {dm_mm} mm, \
                 i.e. at most {:.0} rpm relative ring speed): beyond any rolling bearing, where \
                 centrifugal force dominates the contacts (docs/robustness.md)",
                NDM_MAX / dm_mm
            ),
        ));
    }
    check_load_bounds(case)?;
    if ndm > NDM_WARN {
        warnings.push(format!(
            "{} = {}: speed factor n·d_m = {ndm:.3e} rpm·mm is above {NDM_WARN:.1e}, the upper end \
             of oil-lubricated angular-contact bearings; the results are extrapolations",
            speed_key.0, speed_key.1
        ));
    }
    let Ok(laws) = ContactLaws::hertz(&case.bearing) else {
        return Ok(warnings);
    };
    let Ok(eq) = solve_equilibrium(&case.bearing, &laws, op, &case.settings) else {
        return Ok(warnings);
    };
    let mut pmax = 0.0f64;
    let mut at = "";
    for b in &eq.balls {
        if b.inner.max_pressure > pmax {
            pmax = b.inner.max_pressure;
            at = "inner";
        }
        if b.outer.max_pressure > pmax {
            pmax = b.outer.max_pressure;
            at = "outer";
        }
    }
    let (keys, values) = load_keys(case);
    let stiff = |m: &crate::material::Solid| m.youngs_modulus * 1e-9;
    if !pmax.is_finite() || pmax > PRESSURE_MAX {
        return Err(InputError::field(
            &keys,
            values,
            format!(
                "loads under which the dry maximum Hertz pressure stays ≤ {:.1} GPa: they give \
                 {:.2} GPa at the {at} race (moduli {} and {} GPa), beyond the compressive yield \
                 of bearing steel, where the elastic contact models do not apply (ISO 76 rates \
                 ball bearings at 4.2 GPa; docs/robustness.md)",
                PRESSURE_MAX * 1e-9,
                pmax * 1e-9,
                stiff(&case.bearing.ball_material),
                stiff(&case.bearing.ring_material)
            ),
        ));
    }
    if pmax > PRESSURE_WARN {
        warnings.push(format!(
            "{keys} = {values}: dry maximum Hertz pressure {:.2} GPa at the {at} race is above the \
             ISO 76 static limit of ball bearings, {:.1} GPa (permanent deformation)",
            pmax * 1e-9,
            PRESSURE_WARN * 1e-9
        ));
    }
    Ok(warnings)
}

/// Checks one lubricated contact (contact files of `ehl` and `contact`): refuses a Hertz
/// pressure above [`PRESSURE_MAX`], warns above [`PRESSURE_WARN`].
pub fn check_contact(c: &EhlContact) -> Result<Vec<String>, InputError> {
    let mut warnings = Vec::new();
    let Ok(g) = HertzGeometry::new(c.rx, c.ry, c.e_reduced) else {
        return Ok(warnings);
    };
    let p = g.contact(c.load).max_pressure;
    if !p.is_finite() || p > PRESSURE_MAX {
        return Err(InputError::field(
            "load_n",
            c.load,
            format!(
                "a load whose maximum Hertz pressure stays ≤ {:.1} GPa: it gives {:.2} GPa \
                 (reduced modulus {} GPa), beyond the compressive yield of bearing steel, where \
                 the elastic contact models do not apply (docs/robustness.md)",
                PRESSURE_MAX * 1e-9,
                p * 1e-9,
                c.e_reduced * 1e-9
            ),
        ));
    }
    if p > PRESSURE_WARN {
        warnings.push(format!(
            "load_n = {}: maximum Hertz pressure {:.2} GPa is above the ISO 76 static limit of \
             ball bearings, {:.1} GPa",
            c.load,
            p * 1e-9,
            PRESSURE_WARN * 1e-9
        ));
    }
    Ok(warnings)
}
