//! Linearized bearing coefficients over speed: the 5×5 stiffness K = ∂F/∂q and damping
//! C = ∂F/∂q̇ of the lubricated bearing at its equilibrium under the case's loads, at each of a
//! list of speeds — what critical-speed, stability and unbalance-response analyses consume — and
//! the same in the form of ROSS's speed-dependent `BearingElement` table.
//!
//! Sources: the coupled characterization at each speed ([`from_characterization`]: the fitted
//! laws of the final equilibrium, damping from the harmonic method's c·δ̇ terms), or a study's
//! trend curves ([`from_element`] with a [`crate::force_element::TrendForceElement`]: no EHL run; no damping, as the trends carry none). The dry
//! Hertz stiffness at the same loads is given beside, for comparison.
//!
//! Axes: ours x axial, y and z radial, θy and θz tilts about +y and +z. ROSS's are x and y
//! lateral, z axial, α and β tilts about x and y. The ROSS table maps ROSS x ← our y, ROSS y ←
//! our z, ROSS z ← our x, α ← θy, β ← θz (both frames right-handed: y × z = x), so
//! kxx = K_yy, kxy = K_yz, kyx = K_zy, kyy = K_zz, kzz = K_xx, and likewise for C.

use crate::bearing::{solve_equilibrium, ContactLaws, Control};
use crate::case::Case;
use crate::characterize::{
    characterize_bearing_with_control, CharacterizeSettings, ContactCharacterizer, Progress,
};
use crate::force_element::{ElementInput, ElementState, ForceElement, LawElement};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// The coefficients at one speed (SI).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpeedCoefficients {
    /// Inner-ring speed, rpm.
    pub inner_speed_rpm: f64,
    /// Inner-ring speed, rad/s.
    pub inner_speed_rad_s: f64,
    /// Equilibrium displacements x, y, z (m) and tilts θy, θz (rad).
    pub displacement: [f64; 5],
    /// Stiffness ∂F/∂q (N/m, N, N·m/rad), order x, y, z, θy, θz; not symmetrized.
    pub stiffness: [[f64; 5]; 5],
    /// Damping ∂F/∂q̇ (N·s/m, N·s, N·m·s/rad); zero where the laws carry no damping term.
    pub damping: [[f64; 5]; 5],
    /// Dry Hertz stiffness at the same loads and speed (its damping is zero).
    pub dry_stiffness: [[f64; 5]; 5],
    /// Whether the lubricated equilibrium (the coupled loop) converged.
    pub converged: bool,
    /// Where the coefficients come from: `characterization (<method>)` or `trends`.
    pub source: String,
}

/// The case at inner-ring speed `rpm`.
fn at_speed(case: &Case, rpm: f64) -> Case {
    let mut c = case.clone();
    c.operating.inner_speed = rpm * PI / 30.0;
    c
}

fn dry_stiffness(case: &Case) -> Result<[[f64; 5]; 5], crate::Error> {
    let laws = ContactLaws::hertz(&case.bearing)?;
    Ok(solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)?.stiffness)
}

/// Most speeds one call takes: each is a characterization (seconds to a minute with an EHL
/// method), and a coefficient table over speed needs tens; 200 000 speeds ran out of memory.
pub const MAX_SPEEDS: usize = 1000;

/// Each speed must be a finite number of rpm and, like the case's own speed, pass the
/// plausibility rules ([`check_case`](crate::plausibility::check_case)) at the case's loads: a
/// speed they refuse is named by its index in the list. At most [`MAX_SPEEDS`] speeds.
fn check_speeds(case: &Case, speeds_rpm: &[f64]) -> Result<(), crate::Error> {
    if speeds_rpm.is_empty() {
        return Err(
            crate::case::InputError::field("speeds", "[]", "at least one speed in rpm").into(),
        );
    }
    if speeds_rpm.len() > MAX_SPEEDS {
        return Err(crate::case::InputError::field(
            "speeds",
            format!("{} values", speeds_rpm.len()),
            format!("at most {MAX_SPEEDS} speeds (each is a characterization)"),
        )
        .into());
    }
    for (i, &n) in speeds_rpm.iter().enumerate() {
        if !(n.is_finite() && n.abs() <= 1e6) {
            return Err(crate::case::InputError::field(
                &format!("speeds[{i}]"),
                n,
                "a finite speed in rpm, |n| ≤ 1e6",
            )
            .into());
        }
        match crate::plausibility::check_case(&at_speed(case, n)) {
            Ok(_) => {}
            Err(crate::case::InputError::Field {
                field, expected, ..
            }) if field == "operating.inner_speed_rpm" => {
                return Err(
                    crate::case::InputError::field(&format!("speeds[{i}]"), n, expected).into(),
                )
            }
            Err(e) => return Err(e.into()),
        }
    }
    Ok(())
}

/// Coefficients at each inner-ring speed in `speeds_rpm` from the coupled characterization of
/// `case` at that speed with `method`: the fitted-law element ([`LawElement`]) linearized at the
/// final equilibrium (cage angle 0: the case's ball positions). `progress` receives the loop's
/// events (speed index, event); returning [`ControlFlow::Break`] stops the run
/// ([`crate::characterize::CharacterizeError::Cancelled`], as
/// [`crate::characterize::characterize_bearing_with_control`]).
pub fn from_characterization(
    case: &Case,
    speeds_rpm: &[f64],
    method: &dyn ContactCharacterizer,
    settings: &CharacterizeSettings,
    progress: &(dyn Fn(usize, Progress) -> ControlFlow<()> + Sync),
) -> Result<Vec<SpeedCoefficients>, crate::Error> {
    check_speeds(case, speeds_rpm)?;
    let mut out = Vec::with_capacity(speeds_rpm.len());
    for (i, &rpm) in speeds_rpm.iter().enumerate() {
        let c = at_speed(case, rpm);
        let ch =
            characterize_bearing_with_control(&c, method, settings, None, &|p| progress(i, p))?;
        let element = LawElement::from_characterization(&c, &ch)?;
        let input = ElementInput::at(
            ch.equilibrium.displacement,
            c.operating.inner_speed,
            c.operating.outer_speed,
        );
        let lin = element.evaluate(&input, &mut ElementState::default())?;
        out.push(SpeedCoefficients {
            inner_speed_rpm: rpm,
            inner_speed_rad_s: c.operating.inner_speed,
            displacement: ch.equilibrium.displacement,
            stiffness: lin.stiffness,
            damping: lin.damping,
            dry_stiffness: ch.dry.stiffness,
            converged: ch.converged,
            source: format!("characterization ({})", method.name()),
        });
    }
    Ok(out)
}

/// Coefficients at each speed from a force element (e.g. a study's
/// [`TrendForceElement`](crate::force_element::TrendForceElement)): the equilibrium of the
/// element under the case's loads ([`element_equilibrium`]), linearized there.
pub fn from_element(
    case: &Case,
    speeds_rpm: &[f64],
    element: &dyn ForceElement,
    source: &str,
) -> Result<Vec<SpeedCoefficients>, crate::Error> {
    check_speeds(case, speeds_rpm)?;
    let mut out = Vec::with_capacity(speeds_rpm.len());
    for &rpm in speeds_rpm {
        let c = at_speed(case, rpm);
        let laws = ContactLaws::hertz(&c.bearing)?;
        let dry = solve_equilibrium(&c.bearing, &laws, &c.operating, &c.settings)?;
        let (q, lin) = element_equilibrium(element, &c, dry.displacement)?;
        out.push(SpeedCoefficients {
            inner_speed_rpm: rpm,
            inner_speed_rad_s: c.operating.inner_speed,
            displacement: q,
            stiffness: lin.stiffness,
            damping: lin.damping,
            dry_stiffness: dry_stiffness(&c)?,
            converged: true,
            source: source.to_string(),
        });
    }
    Ok(out)
}

/// The displacement at which `element`'s reactions equal the loads of `case`'s load-controlled
/// DOFs (the others imposed), by Newton with backtracking from `start`, to the case's equilibrium
/// tolerance; with the element's output there. An error carries the residual if it does not
/// converge in the case's iteration limit.
pub fn element_equilibrium(
    element: &dyn ForceElement,
    case: &Case,
    start: [f64; 5],
) -> Result<([f64; 5], crate::force_element::ElementOutput), crate::Error> {
    let op = &case.operating;
    let lever = 0.5 * case.bearing.geometry.pitch_diameter;
    let unit = |k: usize| if k >= 3 { 1.0 / lever } else { 1.0 };
    let mut q = start;
    let mut free = Vec::new();
    let mut target = [0.0; 5];
    for (k, c) in op.dofs.iter().enumerate() {
        match *c {
            Control::Load(f) => {
                target[k] = f;
                free.push(k);
            }
            Control::Displacement(v) => q[k] = v,
        }
    }
    let scale = free
        .iter()
        .map(|&k| (target[k] * unit(k)).abs())
        .fold(1.0_f64, f64::max);
    let tol = case.settings.tolerance.max(1e-12) * scale;
    let mut state = ElementState::default();
    let eval = |q: [f64; 5], state: &mut ElementState| {
        element.evaluate(&ElementInput::at(q, op.inner_speed, op.outer_speed), state)
    };
    let residual = |out: &crate::force_element::ElementOutput| -> (Vec<f64>, f64) {
        let r: Vec<f64> = free
            .iter()
            .map(|&k| (out.reaction[k] - target[k]) * unit(k))
            .collect();
        let n = r.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        (r, n)
    };
    let mut out = eval(q, &mut state)?;
    let (mut r, mut rn) = residual(&out);
    let mut iterations = 0;
    while rn > tol {
        if iterations >= case.settings.max_iterations {
            return Err(crate::bearing::BearingError::NotConverged {
                iterations,
                residual: rn,
                tolerance: tol,
            }
            .into());
        }
        iterations += 1;
        let n = free.len();
        let mut jac = vec![0.0; n * n];
        for (a, &ka) in free.iter().enumerate() {
            for (b, &kb) in free.iter().enumerate() {
                jac[a * n + b] = out.stiffness[ka][kb] * unit(ka);
            }
        }
        let mut step: Vec<f64> = r.iter().map(|x| -x).collect();
        if crate::bearing::linalg_solve(&mut jac, &mut step, n).is_none() {
            return Err(crate::bearing::BearingError::NotConverged {
                iterations,
                residual: rn,
                tolerance: tol,
            }
            .into());
        }
        let mut lam = 1.0;
        let mut accepted = false;
        for _ in 0..30 {
            let mut qn = q;
            for (a, &k) in free.iter().enumerate() {
                qn[k] += lam * step[a];
            }
            if let Ok(on) = eval(qn, &mut state) {
                let (rv, rnn) = residual(&on);
                if rnn < rn {
                    (q, out, r, rn) = (qn, on, rv, rnn);
                    accepted = true;
                    break;
                }
            }
            lam *= 0.5;
        }
        if !accepted {
            return Err(crate::bearing::BearingError::NotConverged {
                iterations,
                residual: rn,
                tolerance: tol,
            }
            .into());
        }
    }
    Ok((q, out))
}

fn cell(x: f64) -> String {
    serde_json::to_string(&x).unwrap_or_default()
}

/// Long-format CSV: one row per speed, matrix (`K`, `C`, `K_dry`) and entry, with the DOF names
/// (x, y, z, theta_y, theta_z) and SI values.
pub fn coefficients_csv(c: &[SpeedCoefficients]) -> String {
    let dofs = crate::bearing::DOF_NAMES;
    let mut out = String::from("inner_speed_rpm,inner_speed_rad_s,matrix,row,column,value_si\n");
    for s in c {
        for (name, m) in [
            ("K", &s.stiffness),
            ("C", &s.damping),
            ("K_dry", &s.dry_stiffness),
        ] {
            for (r, row) in m.iter().enumerate() {
                for (k, v) in row.iter().enumerate() {
                    out.push_str(&format!(
                        "{},{},{name},{},{},{}\n",
                        cell(s.inner_speed_rpm),
                        cell(s.inner_speed_rad_s),
                        dofs[r],
                        dofs[k],
                        cell(*v)
                    ));
                }
            }
        }
    }
    out
}

/// The table of ROSS's speed-dependent `BearingElement` (its `from_table` columns: `frequency`
/// in rad/s — the rotor speed the coefficients belong to — then kxx, kxy, kyx, kyy, cxx, cxy,
/// cyx, cyy, and the axial kzz, czz), in ROSS's axes (module documentation). The tilt terms
/// (ROSS α, β) are not part of ROSS's bearing element; they are in the JSON and CSV outputs.
pub fn ross_table_csv(c: &[SpeedCoefficients]) -> String {
    // ROSS index ← ours: x ← y (1), y ← z (2), z ← x (0).
    let (x, y, z) = (1, 2, 0);
    let mut out = String::from("frequency,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy,kzz,czz\n");
    for s in c {
        let (k, d) = (&s.stiffness, &s.damping);
        let cells = [
            s.inner_speed_rad_s,
            k[x][x],
            k[x][y],
            k[y][x],
            k[y][y],
            d[x][x],
            d[x][y],
            d[y][x],
            d[y][y],
            k[z][z],
            d[z][z],
        ];
        out.push_str(&cells.map(cell).join(","));
        out.push('\n');
    }
    out
}
