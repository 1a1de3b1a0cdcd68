//! Quasi-static 5-DOF equilibrium of an angular-contact ball bearing (Jones 1960; Harris,
//! *Rolling Bearing Analysis*), with centrifugal force and gyroscopic moment.
//!
//! # Coordinates and signs
//! Right-handed: x axial (positive along the applied axial force), y and z radial, θy about +y,
//! θz about +z. Ball j sits at azimuth ψ_j = 2πj/Z measured from +y toward +z (ball 0 on +y).
//! In the plane of a ball, r̂ = (0, cos ψ, sin ψ) points radially outward and t̂ = x̂ × r̂ =
//! (0, −sin ψ, cos ψ) along increasing ψ.
//!
//! Displacements are those of the inner ring relative to the fixed outer ring, from the position
//! where the unloaded balls touch both raceways at the free contact angle α0. The inner groove
//! curvature centre of ball j moves axially by A1 − A sin α0 = x + ℜ_i(θy sin ψ − θz cos ψ) and
//! radially by A2 − A cos α0 = y cos ψ + z sin ψ (ℜ_i: radius of the inner groove-centre locus).
//!
//! # Ball equilibrium
//! Unknowns per ball: the ball centre (X1, X2) relative to the outer groove centre. The inner race
//! pushes the ball along n̂_i = (sin α_i, cos α_i) (axial, radial), the outer race along
//! −(sin α_o, cos α_o). The gyroscopic moment is derived from dH/dt = ω_m x̂ × J·Ω_ball: with the
//! ball's rolling axis ê = (cos β, −sin β) and its signed roll speed ω_R (negative for a rotating
//! inner ring), the races must apply G·t̂ with G = −J·ω_m·ω_R·sin β, through friction forces
//! F_i = λ_i·G/D at the inner contact and F_o = −λ_o·G/D at the outer contact, along the contact
//! tangents τ̂ = (cos α, −sin α). λ_i + λ_o = 2 (outer-race control: λ_i = 0, λ_o = 2).
//!
//! # Kinematics
//! By default ([`Kinematics::OperatingAngles`], the textbook model of Jones and Harris) the ball's
//! speeds ω_m, ω_R and pitch angle β follow from pure rolling at both contact centres at their own
//! operating angles α_i, α_o and zero spin at the controlling race, and dry Hertz constants are
//! evaluated at the operating angles; a separated contact's kinematic angle falls back to the
//! angle of the line of groove-curvature centres. [`Kinematics::GrooveLine`] is the earlier model.
//! Equations: docs/bearing.md §1.

// Index loops mirror the matrix formulas here; iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]

use super::geometry::{Bearing, Race};
use super::hertz_law::OperatingAngleHertzLaw;
use super::linalg;
use super::{dual::D4, BearingError};
use crate::contact_law::ContactLaw;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::Arc;

/// Race-control hypothesis for the ball's spin axis and the sharing of the gyroscopic moment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum RaceControl {
    /// Outer-race control: no spin at the outer contact, λ_i = 0, λ_o = 2 (Harris' default).
    #[default]
    Outer,
    /// Inner-race control: no spin at the inner contact, λ_i = 2, λ_o = 0.
    Inner,
    /// Neither race controls: λ_i = λ_o = 1; the rolling axis is the bisector of the outer- and
    /// inner-control axes.
    None,
    /// No gyroscopic moment (kinematics as outer-race control, G = 0).
    NoGyroscopic,
}

impl RaceControl {
    fn lambdas(self) -> (f64, f64) {
        match self {
            RaceControl::Outer => (0.0, 2.0),
            RaceControl::Inner => (2.0, 0.0),
            RaceControl::None => (1.0, 1.0),
            RaceControl::NoGyroscopic => (0.0, 0.0),
        }
    }
}

/// Where the ball kinematics (orbital speed ω_m, roll speed ω_R, pitch angle β) are evaluated,
/// and whether dry Hertz constants follow the operating contact angle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Kinematics {
    /// The textbook model (Jones 1960; Harris, *Rolling Bearing Analysis*): the inner rolling
    /// condition at the inner contact angle α_i, the outer one and the race-control axis at α_o
    /// (at α_i for inner-race control), and Hertz constants of laws that follow the angle
    /// ([`super::OperatingAngleHertzLaw`]) at each contact's operating angle. A separated
    /// contact's kinematic angle falls back smoothly to the angle of the line of groove-curvature
    /// centres (README, "Modelling choices").
    #[default]
    OperatingAngles,
    /// The earlier model, kept to reproduce earlier results: both contacts' kinematics at the
    /// angle of the line of groove-curvature centres, and every contact law used as given (dry
    /// Hertz constants at the free contact angle). Close to the textbook model only while the contact angles split by
    /// about a degree or less (n·d_m below about 0.3 million mm/min).
    GrooveLine,
}

/// How one degree of freedom is driven.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Control {
    /// Load-controlled: applied force (N) or moment (N·m); the displacement is solved for.
    Load(f64),
    /// Displacement-controlled: imposed displacement (m) or tilt (rad); the reaction is computed.
    Displacement(f64),
}

/// Names of the five degrees of freedom, in the order used everywhere.
pub const DOF_NAMES: [&str; 5] = ["x", "y", "z", "theta_y", "theta_z"];

/// An operating point: speeds and the control of each DOF.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct OperatingPoint {
    /// Inner ring speed about +x, rad/s.
    pub inner_speed: f64,
    /// Outer ring speed about +x, rad/s.
    pub outer_speed: f64,
    /// Control of x, y, z (N or m) and θy, θz (N·m or rad).
    pub dofs: [Control; 5],
    /// Race-control hypothesis.
    pub race_control: RaceControl,
}

/// The contact law of every ball at the inner and the outer raceway.
#[derive(Debug, Clone)]
pub struct ContactLaws {
    /// Inner-race laws, one per ball (index = ball number).
    pub inner: Vec<Arc<dyn ContactLaw>>,
    /// Outer-race laws, one per ball.
    pub outer: Vec<Arc<dyn ContactLaw>>,
}

impl ContactLaws {
    /// Dry Hertz laws Q = K_H(α)·δ^1.5 ([`super::OperatingAngleHertzLaw`]): K_H at the free
    /// contact angle α0 as given, and at each contact's operating angle in the textbook model
    /// ([`Kinematics::OperatingAngles`], the default). The groove-line model uses K_H(α0).
    pub fn hertz(bearing: &Bearing) -> Result<Self, BearingError> {
        bearing.validate()?;
        let li: Arc<dyn ContactLaw> = Arc::new(OperatingAngleHertzLaw::new(bearing, Race::Inner)?);
        let lo: Arc<dyn ContactLaw> = Arc::new(OperatingAngleHertzLaw::new(bearing, Race::Outer)?);
        let z = bearing.geometry.ball_count;
        Ok(ContactLaws {
            inner: (0..z).map(|_| li.clone()).collect(),
            outer: (0..z).map(|_| lo.clone()).collect(),
        })
    }
}

/// Gap (fraction of the groove offset (f − 1/2)·D) over which a separated contact's kinematic
/// angle blends from its operating angle to the groove-line angle (textbook model).
const SEPARATION_BAND: f64 = 0.01;

/// The angle atan2(s, c) of a unit vector (s, c) given as dual numbers.
fn angle_of(s: D4, c: D4) -> D4 {
    let mut d = [0.0; 4];
    let n2 = s.v * s.v + c.v * c.v;
    for k in 0..4 {
        d[k] = (c.v * s.d[k] - s.v * c.d[k]) / n2;
    }
    D4 {
        v: s.v.atan2(c.v),
        d,
    }
}

/// Kinematic angle of a contact with approach `delta`: `alpha` at contact (δ ≥ 0), `theta` at a
/// gap of `band` or more, a C¹ smoothstep in between.
fn blend(alpha: D4, theta: D4, delta: D4, band: f64) -> D4 {
    if delta.v >= 0.0 {
        return alpha;
    }
    if delta.v <= -band {
        return theta;
    }
    let t = (delta + band) / band; // 0 at −band, 1 at contact
    let w = t.chain(t.v * t.v * (3.0 - 2.0 * t.v), 6.0 * t.v * (1.0 - t.v));
    theta + w * (alpha - theta)
}

/// Largest friction coefficient available to resist the gyroscopic moment (a typical EHL
/// traction limit).
pub const MU_MAX: f64 = 0.1;

/// Fraction of the friction limit μ_max·Q up to which the friction force the gyroscopic moment
/// needs is transmitted in full ([`friction_limit_shape`]).
pub const FRICTION_FULL_CONTROL: f64 = 0.95;

/// The friction limit's shape: G(r) for r = F^H/(μ_max·Q) ≥ 0 and its derivative dG/dr.
/// G(r) = r up to r0 = [`FRICTION_FULL_CONTROL`] (full race control, exact), then
/// G = 1 − (1 − r0)/(1 + t + t²), t = (r − r0)/(1 − r0): continuous with its first and second
/// derivatives at r0 (G′ = 1, G″ = 0 on both sides), increasing, below 1 and tending to 1 (the
/// limit μ_max·Q) as r grows. Public for the table of docs/bearing.md §2.5.
pub fn friction_limit_shape(r: f64) -> (f64, f64) {
    let r0 = FRICTION_FULL_CONTROL;
    if r <= r0 {
        return (r, 1.0);
    }
    let w = 1.0 - r0;
    let t = (r - r0) / w;
    let p = 1.0 + t + t * t;
    (1.0 - w / p, (1.0 + 2.0 * t) / (p * p))
}

/// The friction force transmitted when `f` is needed at a contact with limit `limit` ≥ 0:
/// F = μQ·G(|F^H|/μQ)·sign(F^H) with G of [`friction_limit_shape`]: exactly `f` while
/// |f| ≤ [`FRICTION_FULL_CONTROL`]·limit (the textbook's full race control), a C² approach to
/// ±limit above.
fn saturate(f: D4, limit: D4) -> D4 {
    if f.v == 0.0 {
        return f;
    }
    if limit.v <= 0.0 {
        return D4::cst(0.0);
    }
    if f.v.abs() <= FRICTION_FULL_CONTROL * limit.v {
        return f;
    }
    let r = f / limit;
    let (g, dg) = friction_limit_shape(r.v.abs());
    limit * r.chain(g.copysign(r.v), dg)
}

/// Convergence settings of the equilibrium solver.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct EquilibriumSettings {
    /// Relative force tolerance: converged when every load-controlled residual (moments divided
    /// by d_m/2) is below `tolerance`·max(largest applied load, 1 N).
    pub tolerance: f64,
    /// Newton iteration limit.
    pub max_iterations: usize,
    /// Largest deflection accepted, as a fraction of the ball diameter; beyond it the load is
    /// reported as one the bearing cannot carry.
    pub max_deflection_ratio: f64,
    /// Smallest inner contact angle a loaded ball may take, rad. An angular-contact bearing has
    /// its low shoulder (counterbore) on one side of the groove: a load that drives the contacts
    /// past it is one the bearing cannot carry. Default −5° (a little past the groove bottom);
    /// case files that give the bearing by its clearance (deep-groove bearings, shoulders on both
    /// sides) default to −90°, i.e. no limit.
    pub min_contact_angle: f64,
    /// Kinematics model (default: the textbook model at the operating contact angles).
    pub kinematics: Kinematics,
}

impl Default for EquilibriumSettings {
    fn default() -> Self {
        EquilibriumSettings {
            tolerance: 1e-11,
            max_iterations: 100,
            max_deflection_ratio: 0.02,
            min_contact_angle: -5f64.to_radians(),
            kinematics: Kinematics::OperatingAngles,
        }
    }
}

/// State of one ball/raceway contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactState {
    /// Normal load Q, N.
    pub load: f64,
    /// Contact angle α, rad.
    pub contact_angle: f64,
    /// Approach (deflection) δ, m; negative when separated.
    pub deflection: f64,
    /// Hertz semi-axis along the larger curvature radius (transverse), m (0 when unloaded).
    pub semi_major: f64,
    /// Hertz semi-axis in the rolling direction, m.
    pub semi_minor: f64,
    /// Hertz maximum pressure, Pa.
    pub max_pressure: f64,
    /// Curvature radius in the rolling direction at the current contact angle, m.
    pub rx: f64,
    /// Transverse curvature radius, m.
    pub ry: f64,
    /// Sum velocity u_s = u1 + u2 of ball and race surfaces relative to the contact, m/s.
    pub sum_velocity: f64,
    /// Spin-to-roll ratio ω_s/ω_roll (dimensionless): the ball's angular velocity relative to
    /// the race, Ω_rel = ω_R·ê − (ω_race − ω_m)·x̂, resolved along the contact normal
    /// n̂ = (sin α, cos α) (spin) and along the contact tangent τ̂ = (cos α, −sin α) (roll), at
    /// the operating contact angle; 0 when the roll component vanishes (rings at rest).
    pub spin_to_roll: f64,
    /// Friction force the gyroscopic moment needs at this contact, λ·|G|/D, N (before the
    /// μ_max·Q limit).
    pub friction_needed: f64,
    /// Friction the contact can transmit, μ_max·Q, N ([`MU_MAX`]).
    pub friction_limit: f64,
}

/// State of one ball.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallState {
    /// Azimuth ψ, rad, from +y toward +z.
    pub azimuth: f64,
    /// Orbital (cage) speed ω_m, rad/s.
    pub orbital_speed: f64,
    /// Signed roll speed ω_R of the ball about its rolling axis, relative to the cage, rad/s
    /// (negative for a rotating inner ring).
    pub spin_speed: f64,
    /// Pitch angle β of the rolling axis, rad.
    pub pitch_angle: f64,
    /// Angle of the line of groove-curvature centres, rad (equal to both contact angles at
    /// rest): where the groove-line model evaluates the ball speeds, and the fallback of a
    /// separated contact in the textbook model.
    pub kinematic_angle: f64,
    /// Centrifugal force F_c = ½·m·d_m·ω_m², N.
    pub centrifugal_force: f64,
    /// Gyroscopic moment the ball's motion requires, G = dH/dt along t̂, N·m.
    pub gyroscopic_moment: f64,
    /// Friction force of the inner race on the ball along τ̂_i = (cos α_i, −sin α_i), N.
    pub inner_friction: f64,
    /// Friction force of the outer race on the ball along τ̂_o = (cos α_o, −sin α_o), N.
    pub outer_friction: f64,
    /// Inner contact.
    pub inner: ContactState,
    /// Outer contact.
    pub outer: ContactState,
}

/// Result of an equilibrium solve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Equilibrium {
    /// Whether the residual met the tolerance (always true for a returned result; a failed
    /// solve is an error).
    pub converged: bool,
    /// Newton iterations used.
    pub iterations: usize,
    /// Final largest load-controlled residual, N (moments divided by d_m/2).
    pub residual: f64,
    /// Residual after each iteration, N.
    pub residual_history: Vec<f64>,
    /// Inner ring displacements x, y, z (m) and tilts θy, θz (rad).
    pub displacement: [f64; 5],
    /// Load on the inner ring in equilibrium with the balls: F_x, F_y, F_z (N), M_y, M_z (N·m).
    /// The bearing acts on the shaft with the opposite.
    pub reaction: [f64; 5],
    /// Stiffness matrix ∂reaction/∂displacement, order x, y, z, θy, θz (N/m, N, N·m/rad).
    /// Not symmetrized.
    pub stiffness: [[f64; 5]; 5],
    /// Per-ball states, ball 0 on +y.
    pub balls: Vec<BallState>,
    /// Conditions under which the result is approximate (kinematic angle far from the contact
    /// angles, gyroscopic friction at its limit), in words.
    pub warnings: Vec<String>,
}

impl Equilibrium {
    /// Every contact as (ball index, raceway, state), ball-major, inner before outer (the order
    /// of characterizations and of [`crate::lubrication::assess`]).
    pub fn contact_states(&self) -> Vec<(usize, Race, super::ContactState)> {
        self.balls
            .iter()
            .enumerate()
            .flat_map(|(i, b)| [(i, Race::Inner, b.inner), (i, Race::Outer, b.outer)])
            .collect()
    }

    /// The cage speed at this equilibrium, rad/s: the load-weighted mean of the balls' orbital
    /// speeds ([`cage_speed_of`]). The ball-pass frequency is Z times it over 2π.
    pub fn cage_speed(&self) -> f64 {
        let w: Vec<f64> = self.balls.iter().map(|b| b.orbital_speed).collect();
        let q: Vec<[f64; 2]> = self
            .balls
            .iter()
            .map(|b| [b.inner.load, b.outer.load])
            .collect();
        cage_speed_of(&w, &q)
    }
}

/// Bearing reactions and their Jacobian at given ring displacements: the bearing as a force
/// element for rotor simulations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ForceResult {
    /// Load on the inner ring in equilibrium with the balls (N, N·m); the bearing acts on the
    /// shaft with the opposite.
    pub reaction: [f64; 5],
    /// ∂reaction/∂displacement (N/m, N, N·m/rad).
    pub jacobian: [[f64; 5]; 5],
}

/// Per-ball evaluation: terms as dual numbers seeded in (X1, X2, A1, A2).
struct Terms {
    r: [D4; 2],
    /// Force on the ball from the inner race: axial, radial; and the friction-moment term f_i·λ_i·G.
    g: [D4; 3],
    qi: f64,
    qo: f64,
    di: f64,
    dout: f64,
    /// ∂δ_i and ∂δ_o with respect to (X1, X2, A1, A2).
    ddi: [f64; 4],
    ddo: [f64; 4],
    sin_ai: f64,
    cos_ai: f64,
    sin_ao: f64,
    cos_ao: f64,
    om_m: f64,
    om_r: f64,
    beta: f64,
    fc: f64,
    gyro: f64,
    fi: f64,
    fo: f64,
}

impl Terms {
    /// The ball's residual |R|, N.
    fn residual(&self) -> f64 {
        self.r[0].v.hypot(self.r[1].v)
    }

    /// The force scale the residual is measured against, N: |Q_i| + |Q_o| + |F_c| + 1e-6.
    fn scale(&self) -> f64 {
        self.qi.abs() + self.qo.abs() + self.fc.abs() + 1e-6
    }

    /// Whether the ball is in equilibrium: |R| ≤ 1e-9 × the force scale.
    fn converged(&self) -> bool {
        self.residual() <= 1e-9 * self.scale()
    }
}

/// What one ball's equilibrium is solved for: ball `j` at inner groove-centre offsets `a`
/// (axial, radial; m), with the inner contact taken into account or ignored (the separated-ball
/// start of `solve_ball`), and the kinematics model the ball's speeds follow.
#[derive(Debug, Clone, Copy)]
struct BallProblem {
    j: usize,
    a: [f64; 2],
    ignore_inner: bool,
    kin: Kinematics,
}

/// One contact of a ball as dual numbers: the direction (sin α, cos α) from the groove centre
/// to the ball centre and the approach δ, m.
#[derive(Clone, Copy)]
struct ContactLine {
    sin: D4,
    cos: D4,
    delta: D4,
}

/// Sine and cosine of the angles at which the ball's speeds are evaluated, at the inner and
/// the outer contact.
#[derive(Clone, Copy)]
struct KinematicAngles {
    sin_i: D4,
    cos_i: D4,
    sin_o: D4,
    cos_o: D4,
}

/// The ball's motion as dual numbers: rolling axis (cos β, sin β), orbital speed ω_m and signed
/// roll speed ω_R (rad/s), centrifugal force F_c (N) and gyroscopic moment G (N·m).
struct BallMotion {
    cos_b: D4,
    sin_b: D4,
    om_m: D4,
    om_r: D4,
    fc: D4,
    gyro: D4,
}

/// The ball centre X = ρ·(sin φ, cos φ) from its polar coordinates about the outer groove
/// centre (m, rad).
fn cart(rho: f64, phi: f64) -> [f64; 2] {
    [rho * phi.sin(), rho * phi.cos()]
}

/// The bearing model at one operating speed and set of contact laws. Owns its data (the laws are
/// shared through `Arc`), so it can live in a rotor model or another thread.
#[derive(Debug, Clone)]
pub struct BearingModel {
    bearing: Bearing,
    laws: ContactLaws,
    inner_speed: f64,
    outer_speed: f64,
    race_control: RaceControl,
    kinematics: Kinematics,
    ri: f64,
    ro: f64,
    a0: f64,
    frak_ri: f64,
    psi: Vec<f64>,
    cage_angle: f64,
    mass: f64,
    inertia: f64,
}

/// Per-ball solution at given groove-centre offsets.
#[derive(Clone, Copy)]
struct BallSolution {
    x: [f64; 2],
    /// g = (v_x, v_r, f_i λ_i G) and dg/dA (3×2).
    g: [f64; 3],
    dg: [[f64; 2]; 3],
    /// Loads (N) and approaches (m) of the inner and outer contacts.
    q: [f64; 2],
    delta: [f64; 2],
    /// d(δ_i, δ_o)/dA with the ball at its equilibrium (rows inner, outer).
    ddelta: [[f64; 2]; 2],
    /// Orbital speed ω_m of the ball at its equilibrium, rad/s.
    orbital_speed: f64,
}

impl BallSolution {
    /// The solution at the ball's equilibrium `x` with terms `t`, with its derivatives by the
    /// implicit function theorem: dX/dA = −R_X⁻¹·R_A, dg/dA = g_A + g_X·dX/dA and likewise
    /// d(δ_i, δ_o)/dA.
    fn at(x: [f64; 2], t: &Terms) -> Self {
        let rx = [[t.r[0].d[0], t.r[0].d[1]], [t.r[1].d[0], t.r[1].d[1]]];
        let det = rx[0][0] * rx[1][1] - rx[0][1] * rx[1][0];
        let mut dx_da = [[0.0; 2]; 2];
        if det.abs() > 0.0 {
            for k in 0..2 {
                let ra = [t.r[0].d[2 + k], t.r[1].d[2 + k]];
                dx_da[0][k] = -(rx[1][1] * ra[0] - rx[0][1] * ra[1]) / det;
                dx_da[1][k] = -(-rx[1][0] * ra[0] + rx[0][0] * ra[1]) / det;
            }
        }
        let mut dg = [[0.0; 2]; 3];
        for (m, row) in dg.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                *v = t.g[m].d[2 + k] + t.g[m].d[0] * dx_da[0][k] + t.g[m].d[1] * dx_da[1][k];
            }
        }
        let mut ddelta = [[0.0; 2]; 2];
        for (row, dd) in ddelta.iter_mut().zip([&t.ddi, &t.ddo]) {
            for (k, v) in row.iter_mut().enumerate() {
                *v = dd[2 + k] + dd[0] * dx_da[0][k] + dd[1] * dx_da[1][k];
            }
        }
        BallSolution {
            x,
            g: [t.g[0].v, t.g[1].v, t.g[2].v],
            dg,
            q: [t.qi, t.qo],
            delta: [t.di, t.dout],
            ddelta,
            orbital_speed: t.om_m,
        }
    }
}

/// Reactions, stiffness, damping and contact states of the bearing at a ring displacement and
/// rate: what [`BearingModel::evaluate_dynamic`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicForce {
    /// Load on the inner ring (N, N·m): the quasi-static reaction plus the contact damping term.
    pub reaction: [f64; 5],
    /// ∂reaction/∂q at the given rates, without the term ∂C/∂q·q̇ (N/m, N, N·m/rad).
    pub stiffness: [[f64; 5]; 5],
    /// ∂reaction/∂q̇ (N·s/m, N·s, N·m·s/rad): Σ c_k·g_k·g_kᵀ over the contacts, g_k = dδ_k/dq.
    pub damping: [[f64; 5]; 5],
    /// Per ball: [inner, outer] contact loads without the damping term, N.
    pub loads: Vec<[f64; 2]>,
    /// Per ball: [inner, outer] contact approaches, m.
    pub approaches: Vec<[f64; 2]>,
    /// Per ball: orbital speed ω_m at its equilibrium (the textbook kinematics at its operating
    /// contact angles, or the groove-line model's), rad/s.
    pub orbital_speeds: Vec<f64>,
}

/// The speed of a cage that carries balls with orbital speeds `orbital_speeds` (rad/s) and
/// contact loads `loads` ([inner, outer] per ball, N): the load-weighted mean
/// Σ_j (Q_i,j + Q_o,j)·ω_m,j / Σ_j (Q_i,j + Q_o,j), rad/s. The loaded balls drive the cage, each
/// in proportion to the traction it can carry, and a ball entering or leaving the load zone
/// enters the mean continuously. With no load at all, the plain mean of the balls' orbital
/// speeds; NaN for no balls. Under pure thrust (all balls alike) it is the balls' common ω_m.
pub fn cage_speed_of(orbital_speeds: &[f64], loads: &[[f64; 2]]) -> f64 {
    let mut weighted = 0.0;
    let mut total = 0.0;
    for (w, q) in orbital_speeds.iter().zip(loads) {
        let l = q[0].max(0.0) + q[1].max(0.0);
        weighted += l * w;
        total += l;
    }
    if total > 0.0 {
        weighted / total
    } else {
        orbital_speeds.iter().sum::<f64>() / orbital_speeds.len() as f64
    }
}

/// Consecutive creeping Newton steps of a ball (textbook kinematics) that end an attempt so that
/// `solve_ball` can restart elsewhere.
const CREEP_STOP: usize = 5;

impl BearingModel {
    /// A model of `bearing` with `laws` at the speeds of `op` (the DOF controls of `op` are not
    /// used here).
    pub fn new(
        bearing: &Bearing,
        laws: &ContactLaws,
        inner_speed: f64,
        outer_speed: f64,
        race_control: RaceControl,
    ) -> Result<Self, BearingError> {
        bearing.validate()?;
        let g = &bearing.geometry;
        let z = g.ball_count;
        if laws.inner.len() != z || laws.outer.len() != z {
            return Err(BearingError::LawCount {
                inner: laws.inner.len(),
                outer: laws.outer.len(),
                balls: z,
            });
        }
        for (name, v) in [("inner_speed", inner_speed), ("outer_speed", outer_speed)] {
            if !v.is_finite() {
                return Err(BearingError::invalid(name, v, "a finite speed in rad/s"));
            }
        }
        let d = g.ball_diameter;
        Ok(BearingModel {
            bearing: *bearing,
            laws: laws.clone(),
            inner_speed,
            outer_speed,
            race_control,
            kinematics: Kinematics::default(),
            ri: (g.inner_conformity - 0.5) * d,
            ro: (g.outer_conformity - 0.5) * d,
            a0: g.center_distance(),
            frak_ri: g.inner_groove_center_radius(),
            psi: (0..z).map(|j| 2.0 * PI * j as f64 / z as f64).collect(),
            cage_angle: 0.0,
            mass: bearing.ball_mass(),
            inertia: bearing.ball_inertia(),
        })
    }

    /// Set the ring speeds about +x, rad/s (errors if not finite).
    pub fn set_speeds(&mut self, inner_speed: f64, outer_speed: f64) -> Result<(), BearingError> {
        for (name, v) in [("inner_speed", inner_speed), ("outer_speed", outer_speed)] {
            if !v.is_finite() {
                return Err(BearingError::invalid(name, v, "a finite speed in rad/s"));
            }
        }
        self.inner_speed = inner_speed;
        self.outer_speed = outer_speed;
        Ok(())
    }

    /// Set the cage angle, rad: ball j sits at azimuth ψ_j = 2πj/Z + angle (from +y toward +z).
    /// The balls move with the cage, so a rotor simulation advances it at the operating cage
    /// speed ([`cage_speed_of`] the balls' orbital speeds); the stiffness of a radially loaded bearing then varies at
    /// Z times the cage frequency. Errors if not finite.
    pub fn set_cage_angle(&mut self, angle: f64) -> Result<(), BearingError> {
        if !angle.is_finite() {
            return Err(BearingError::invalid(
                "cage_angle",
                angle,
                "a finite angle in rad",
            ));
        }
        if angle != self.cage_angle {
            let z = self.psi.len();
            for (j, p) in self.psi.iter_mut().enumerate() {
                *p = 2.0 * PI * j as f64 / z as f64 + angle;
            }
            self.cage_angle = angle;
        }
        Ok(())
    }

    /// The bearing.
    pub fn bearing(&self) -> &Bearing {
        &self.bearing
    }

    /// The race-control hypothesis.
    pub fn race_control(&self) -> RaceControl {
        self.race_control
    }

    /// The kinematics model.
    pub fn kinematics(&self) -> Kinematics {
        self.kinematics
    }

    /// Number of balls Z.
    pub fn ball_count(&self) -> usize {
        self.psi.len()
    }

    /// Cage (orbital) speed of an unloaded ball at the free contact angle under pure rolling,
    /// rad/s: ω_c = ½·[ω_i·(1 − γ) + ω_o·(1 + γ)], γ = D·cos α0/d_m. A no-load estimate only:
    /// at an operating point the balls orbit at the speeds of their operating contact angles
    /// (11 % faster for the 218 at 15000 rpm); the cage speed there is
    /// [`Equilibrium::cage_speed`] or the `orbital_speeds` of
    /// [`BearingModel::evaluate_dynamic`] ([`cage_speed_of`]).
    pub fn cage_speed(&self) -> f64 {
        self.orbital_guess()
    }

    /// The same model with kinematics model `kinematics` ([`BearingModel::new`] uses the
    /// default, the textbook model at the operating contact angles).
    pub fn with_kinematics(mut self, kinematics: Kinematics) -> Self {
        self.kinematics = kinematics;
        self
    }

    fn groove_offsets(&self, j: usize, q: &[f64; 5]) -> [f64; 2] {
        let (s, c) = self.psi[j].sin_cos();
        let alpha0 = self.bearing.geometry.free_contact_angle;
        [
            self.a0 * alpha0.sin() + q[0] + self.frak_ri * (q[3] * s - q[4] * c),
            self.a0 * alpha0.cos() + q[1] * c + q[2] * s,
        ]
    }

    /// Ball `j`'s problem at groove-centre offsets `a` with both contacts and the model's
    /// kinematics.
    fn ball_problem(&self, j: usize, a: [f64; 2]) -> BallProblem {
        BallProblem {
            j,
            a,
            ignore_inner: false,
            kin: self.kinematics,
        }
    }

    /// The inner and outer contacts of a ball centred at `x` with the inner groove centre at
    /// `a` (both relative to the outer groove centre, axial and radial, m, as dual numbers).
    fn contact_lines(&self, x: [D4; 2], a: [D4; 2]) -> [ContactLine; 2] {
        // Inner contact.
        let dxi = a[0] - x[0];
        let dri = a[1] - x[1];
        let li = (dxi * dxi + dri * dri).sqrt();
        let inner = ContactLine {
            sin: dxi / li,
            cos: dri / li,
            delta: li - self.ri,
        };
        // Outer contact.
        let lo = (x[0] * x[0] + x[1] * x[1]).sqrt();
        let outer = ContactLine {
            sin: x[0] / lo,
            cos: x[1] / lo,
            delta: lo - self.ro,
        };
        [inner, outer]
    }

    /// The angles at which ball `p.j`'s speeds are evaluated (by the kinematics model `p.kin`),
    /// and the contact loads `q` (inner, outer; N) with the Hertz constants of laws that follow
    /// the angle taken at the operating contact angles (textbook model).
    fn kinematic_angles(
        &self,
        p: &BallProblem,
        [inner, outer]: &[ContactLine; 2],
        a: [D4; 2],
        [mut qi, mut qo]: [D4; 2],
    ) -> (KinematicAngles, [D4; 2]) {
        // Angle of the line of groove-curvature centres, atan(A1/A2): equal to both contact
        // angles at rest; it depends on the ring displacement only.
        let la = (a[0] * a[0] + a[1] * a[1]).sqrt();
        let (gsin, gcos) = (a[0] / la, a[1] / la);
        let k = match p.kin {
            // Groove-line model: the ball's speeds (ω_m, ω_R, β) are evaluated with both contact
            // angles taken as the groove-line angle (README, "Modelling choices").
            Kinematics::GrooveLine => KinematicAngles {
                sin_i: gsin,
                cos_i: gcos,
                sin_o: gsin,
                cos_o: gcos,
            },
            Kinematics::OperatingAngles => {
                let alpha_i = angle_of(inner.sin, inner.cos);
                let alpha_o = angle_of(outer.sin, outer.cos);
                // Hertz constants at the operating contact angles (laws that follow the angle).
                if let Some((c, dc)) = self.laws.inner[p.j].angle_factor(alpha_i.v) {
                    qi = qi * alpha_i.chain(c, dc);
                }
                if let Some((c, dc)) = self.laws.outer[p.j].angle_factor(alpha_o.v) {
                    qo = qo * alpha_o.chain(c, dc);
                }
                // Kinematics at each contact's operating angle. A separated contact has no
                // physical contact angle (its direction from a groove centre only tens of µm
                // away is arbitrary once the gap grows): its kinematic angle blends smoothly (C¹)
                // from the operating angle at contact to the groove-line angle at a gap of
                // SEPARATION_BAND of the groove offset (f − 1/2)·D.
                let theta = angle_of(gsin, gcos);
                // With the inner contact ignored (the separated-ball start of `solve_ball`) the
                // inner contact is taken as separated.
                let ki = if p.ignore_inner {
                    theta
                } else {
                    blend(alpha_i, theta, inner.delta, SEPARATION_BAND * self.ri)
                };
                let ko = blend(alpha_o, theta, outer.delta, SEPARATION_BAND * self.ro);
                KinematicAngles {
                    sin_i: ki.chain(ki.v.sin(), ki.v.cos()),
                    cos_i: ki.chain(ki.v.cos(), -ki.v.sin()),
                    sin_o: ko.chain(ko.v.sin(), ko.v.cos()),
                    cos_o: ko.chain(ko.v.cos(), -ko.v.sin()),
                }
            }
        };
        (k, [qi, qo])
    }

    /// The ball's rolling axis ê = (cos β, −sin β) by the race-control hypothesis, as
    /// (cos β, sin β): outer control tan β = sin α_o/(cos α_o + γ), inner control
    /// tan β = sin α_i/(cos α_i − γ) (γ = D/d_m), neither the bisector of the two.
    fn rolling_axis(&self, k: &KinematicAngles, gamma: f64) -> (D4, D4) {
        let axis_outer = || {
            let cx = k.cos_o + gamma;
            let n = (cx * cx + k.sin_o * k.sin_o).sqrt();
            (cx / n, k.sin_o / n)
        };
        let axis_inner = || {
            let cx = k.cos_i - gamma;
            let n = (cx * cx + k.sin_i * k.sin_i).sqrt();
            (cx / n, k.sin_i / n)
        };
        match self.race_control {
            RaceControl::Outer | RaceControl::NoGyroscopic => axis_outer(),
            RaceControl::Inner => axis_inner(),
            RaceControl::None => {
                let (c1, s1) = axis_outer();
                let (c2, s2) = axis_inner();
                let (c, s) = (c1 + c2, s1 + s2);
                let n = (c * c + s * s).sqrt();
                (c / n, s / n)
            }
        }
    }

    /// The ball's motion at kinematic angles `k`: its rolling axis, orbital speed ω_m and roll
    /// speed ω_R (rad/s) from pure rolling at both contact centres, centrifugal force (N) and
    /// gyroscopic moment (N·m).
    fn ball_motion(&self, k: &KinematicAngles) -> BallMotion {
        let geo = &self.bearing.geometry;
        let d = geo.ball_diameter;
        let dm = geo.pitch_diameter;
        let (cos_b, sin_b) = self.rolling_axis(k, d / dm);
        // Pure rolling at both contact centres (cage frame):
        //  −(D/2)·ω_R·cos(α_i − β) = (ω_i − ω_m)·r_i,   (D/2)·ω_R·cos(α_o − β) = (ω_o − ω_m)·r_o
        let ci = (k.cos_i * cos_b + k.sin_i * sin_b) * (0.5 * d);
        let co = (k.cos_o * cos_b + k.sin_o * sin_b) * (0.5 * d);
        let rpi = D4::cst(0.5 * dm) - k.cos_i * (0.5 * d);
        let rpo = D4::cst(0.5 * dm) + k.cos_o * (0.5 * d);
        let om_m =
            (rpi * co * self.inner_speed + rpo * ci * self.outer_speed) / (rpi * co + rpo * ci);
        let om_r = (D4::cst(self.outer_speed) - om_m) * rpo / co;
        let fc = om_m * om_m * (0.5 * self.mass * dm);
        let gyro = if self.race_control == RaceControl::NoGyroscopic {
            D4::cst(0.0)
        } else {
            -(om_m * om_r * sin_b) * self.inertia
        };
        BallMotion {
            cos_b,
            sin_b,
            om_m,
            om_r,
            fc,
            gyro,
        }
    }

    /// Ball `p.j`'s equations at centre `x` (relative to the outer groove centre, axial and
    /// radial, m): residual, ring loads and contact figures as dual numbers seeded in
    /// (X1, X2, A1, A2).
    fn terms(&self, p: &BallProblem, x: [f64; 2]) -> Terms {
        let x = [D4::var(x[0], 0), D4::var(x[1], 1)];
        let a = [D4::var(p.a[0], 2), D4::var(p.a[1], 3)];
        let geo = &self.bearing.geometry;
        let d = geo.ball_diameter;
        let lines = self.contact_lines(x, a);
        let [inner, outer] = lines;
        let (fi, dfi) = if p.ignore_inner {
            (0.0, 0.0)
        } else {
            self.laws.inner[p.j].force(inner.delta.v)
        };
        let (fo, dfo) = self.laws.outer[p.j].force(outer.delta.v);
        let loads = [inner.delta.chain(fi, dfi), outer.delta.chain(fo, dfo)];
        let (k, [qi, qo]) = self.kinematic_angles(p, &lines, a, loads);
        let m = self.ball_motion(&k);
        // Friction forces that carry the gyroscopic moment: F_i = λ_i·G/D at the inner contact and
        // F_o = −λ_o·G/D at the outer (along τ̂ = (cos α, −sin α)), each limited smoothly to
        // μ_max·Q: where a contact cannot hold its share the ball pivots (Harris) and the moment is
        // not fully resisted. The limit is inactive (F = F^H exactly) wherever |F^H| is at most
        // FRICTION_FULL_CONTROL·μ_max·Q.
        let (lam_i, lam_o) = self.race_control.lambdas();
        let fi = saturate(m.gyro * (lam_i / d), qi * MU_MAX);
        let fo = saturate(m.gyro * (-lam_o / d), qo * MU_MAX);
        let (sin_ai, cos_ai, sin_ao, cos_ao) = (inner.sin, inner.cos, outer.sin, outer.cos);
        let r1 = qi * sin_ai - qo * sin_ao + fi * cos_ai + fo * cos_ao;
        let r2 = qi * cos_ai - qo * cos_ao - fi * sin_ai - fo * sin_ao + m.fc;
        let vx = qi * sin_ai + fi * cos_ai;
        let vr = qi * cos_ai - fi * sin_ai;
        // Moment of the inner friction about the inner groove centre: f_i·D·F_i along t̂.
        let gf = fi * (geo.inner_conformity * d);
        Terms {
            r: [r1, r2],
            g: [vx, vr, gf],
            qi: qi.v,
            qo: qo.v,
            di: inner.delta.v,
            dout: outer.delta.v,
            ddi: inner.delta.d,
            ddo: outer.delta.d,
            sin_ai: sin_ai.v,
            cos_ai: cos_ai.v,
            sin_ao: sin_ao.v,
            cos_ao: cos_ao.v,
            om_m: m.om_m.v,
            om_r: m.om_r.v,
            beta: m.sin_b.v.atan2(m.cos_b.v),
            fc: m.fc.v,
            gyro: m.gyro.v,
            fi: fi.v,
            fo: fo.v,
        }
    }

    /// [`Self::terms`] of ball `j` at centre `x` and groove-centre offsets `a`, both contacts,
    /// the model's kinematics.
    fn terms_at(&self, j: usize, x: [f64; 2], a: [f64; 2]) -> Terms {
        self.terms(&self.ball_problem(j, a), x)
    }

    /// Rough orbital speed for starting values, rad/s.
    fn orbital_guess(&self) -> f64 {
        let g = &self.bearing.geometry;
        let gc = g.ball_diameter / g.pitch_diameter * g.free_contact_angle.cos();
        0.5 * (self.inner_speed * (1.0 - gc) + self.outer_speed * (1.0 + gc))
    }

    /// Solve ball j's equilibrium for groove-centre offsets `a`, starting from `warm` if given.
    /// (`CREEP_STOP`: consecutive creeping Newton steps that end an attempt, see `ball_newton`.)
    fn solve_ball(
        &self,
        j: usize,
        a: [f64; 2],
        warm: Option<[f64; 2]>,
    ) -> Result<BallSolution, BearingError> {
        self.solve_ball_from(j, a, warm, true)
    }

    /// A cold start of ball `j` on the line of groove centres (unit vector `u`, total approach
    /// `s` along it, m): half the approach at the outer race when the contacts overlap, else
    /// pressed into the outer race by the centrifugal force of the no-load orbital speed.
    fn cold_start(&self, j: usize, u: [f64; 2], s: f64) -> [f64; 2] {
        let om = self.orbital_guess();
        let fc = 0.5 * self.mass * self.bearing.geometry.pitch_diameter * om * om;
        let d_o = if s > 0.0 {
            0.5 * s
        } else {
            self.laws.outer[j].approach_at(fc).unwrap_or(0.0).max(0.0)
        };
        [u[0] * (self.ro + d_o), u[1] * (self.ro + d_o)]
    }

    /// `solve_ball`; `continuation`: when every start fails, solve the ball cold at slightly
    /// scaled offsets a·(1 ± ε) and restart from there (not nested).
    fn solve_ball_from(
        &self,
        j: usize,
        a: [f64; 2],
        warm: Option<[f64; 2]>,
        continuation: bool,
    ) -> Result<BallSolution, BearingError> {
        let p = self.ball_problem(j, a);
        let la = (a[0] * a[0] + a[1] * a[1]).sqrt();
        let u = [a[0] / la, a[1] / la];
        let s = la - self.ri - self.ro; // total approach along the line of centres
        let mut x = match warm {
            Some(w) => w,
            None => self.cold_start(j, u, s),
        };
        let mut t = self.terms(&p, x);
        // A ball that touches nothing and feels no body force carries nothing: its position is
        // undetermined; take the midpoint of the gap.
        let unloaded = |t: &Terms| t.qi == 0.0 && t.qo == 0.0 && t.fc == 0.0 && t.gyro == 0.0;
        if unloaded(&t) {
            let mid = self.ro + 0.5 * s;
            let xm = [u[0] * mid, u[1] * mid];
            let tm = self.terms(&p, xm);
            if unloaded(&tm) {
                return Ok(BallSolution {
                    x: xm,
                    g: [0.0; 3],
                    dg: [[0.0; 2]; 3],
                    q: [0.0; 2],
                    delta: [tm.di, tm.dout],
                    ddelta: [[0.0; 2]; 2],
                    orbital_speed: tm.om_m,
                });
            }
            x = xm;
            t = tm;
        }
        let (x, t) = self.converge_ball(&p, x, t, warm.is_none(), continuation);
        let res = t.residual();
        if res.is_nan() || res > 1e-9 * t.scale() {
            return Err(BearingError::BallNotConverged {
                ball: j,
                residual: res,
            });
        }
        Ok(BallSolution::at(x, &t))
    }

    /// Newton for ball `p` from centre `x` (terms `t`); a `cold` start at speed in the textbook
    /// model first converges the groove-line kinematics (robust from the groove-line start: the
    /// ball's speeds then do not depend on its position). Stalled attempts go on with
    /// [`Self::restart_ball`]. Returns the last iterate, converged or not.
    fn converge_ball(
        &self,
        p: &BallProblem,
        x: [f64; 2],
        t: Terms,
        cold: bool,
        continuation: bool,
    ) -> ([f64; 2], Terms) {
        let (mut x, mut t) = (x, t);
        if cold && p.kin == Kinematics::OperatingAngles && t.fc > 0.0 {
            // Cold start at speed: the groove-line kinematics first, then the textbook model
            // from there.
            let groove = BallProblem {
                kin: Kinematics::GrooveLine,
                ..*p
            };
            let tg = self.terms(&groove, x);
            let (xg, _) = self.ball_newton(&groove, x, tg, CREEP_STOP);
            x = xg;
            t = self.terms(p, x);
        }
        let first = self.ball_newton(p, x, t, CREEP_STOP);
        if first.1.converged() {
            return first;
        }
        self.restart_ball(p, x, continuation)
    }

    /// The restarts of a ball whose Newton iteration from `x` stalled: from the ball solved in
    /// the outer groove alone, then (textbook kinematics) without the creeping stop, then
    /// (`continuation`) from the solutions of neighbouring problems. Returns the first converged
    /// iterate, or the last one of the restart from the outer groove.
    fn restart_ball(&self, p: &BallProblem, x: [f64; 2], continuation: bool) -> ([f64; 2], Terms) {
        // Stalled at the onset of the inner contact, where a nearly unloaded but stiff inner
        // contact makes the Jacobian singular: solve the ball in the outer groove alone. If the
        // inner contact is open there, that is the solution; otherwise restart from it.
        let separated = BallProblem {
            ignore_inner: true,
            ..*p
        };
        let t0 = self.terms(&separated, x);
        let (xo, _) = self.ball_newton(&separated, x, t0, CREEP_STOP);
        let tf = self.terms(p, xo);
        let (mut xs, mut ts) = if tf.converged() {
            (xo, tf)
        } else {
            self.ball_newton(p, xo, tf, CREEP_STOP)
        };
        if !ts.converged() && p.kin == Kinematics::OperatingAngles {
            // Last resort (textbook kinematics near the inner contact's onset, where both
            // starts can stop creeping on a knife edge — found by the high-speed Jacobian
            // property test): the same Newton without the creeping stop, from the
            // separated-ball solution and from where the Newton restarted there stopped.
            for start in [xo, xs] {
                let t1 = self.terms(p, start);
                let (x1, t1) = self.ball_newton(p, start, t1, usize::MAX);
                if t1.converged() {
                    (xs, ts) = (x1, t1);
                    break;
                }
            }
        }
        if !ts.converged() && continuation {
            // Continuation: every start can end on a knife edge of the Newton path (found by
            // the Jacobian property test: 7006 at 7760 rpm, outer race control, a cold start
            // 10 µm from the solution stalled with a residual of 3.2 N while the offsets
            // scaled by 1 ± 1e-4 solved at once). Solve a neighbouring problem cold and
            // restart from its solution, which lies next to this one.
            let a = p.a;
            for eps in [1e-6, -1e-6, 1e-5, -1e-5, 1e-4, -1e-4] {
                let an = [a[0] * (1.0 + eps), a[1] * (1.0 + eps)];
                let Ok(nb) = self.solve_ball_from(p.j, an, None, false) else {
                    continue;
                };
                let t1 = self.terms(p, nb.x);
                let (x1, t1) = self.ball_newton(p, nb.x, t1, usize::MAX);
                if t1.converged() {
                    (xs, ts) = (x1, t1);
                    break;
                }
            }
        }
        (xs, ts)
    }

    /// Damped Newton (with a Levenberg–Marquardt fallback, [`Self::ball_lm_step`]) for ball `p`
    /// in polar coordinates about the outer groove centre, from centre `x` with terms `t`;
    /// `creep_stop` consecutive creeping steps end it (textbook kinematics). Returns the last
    /// iterate.
    fn ball_newton(
        &self,
        p: &BallProblem,
        x: [f64; 2],
        t: Terms,
        creep_stop: usize,
    ) -> ([f64; 2], Terms) {
        let mut t = t;
        // Newton in polar coordinates about the outer groove centre, X = ρ·(sin φ, cos φ): a ball
        // that slides along the outer groove keeps its outer approach, which a Cartesian step
        // would not (the radial Hertz stiffness is orders of magnitude above the tangential one).
        let (mut rho, mut phi) = (x[0].hypot(x[1]), x[0].atan2(x[1]));
        // Consecutive creeping steps (textbook model): accepted, but not a capped full step and
        // reducing the residual by less than 10 %. Five in a row (near a fold of the per-ball
        // equations, far from the solution) stop the iteration so that `solve_ball` can restart
        // from the separated-ball solution instead of creeping for 100 iterations.
        let mut creeping = 0;
        for _ in 0..100 {
            let res = t.residual();
            if res <= 1e-13 * t.scale() {
                break;
            }
            if p.kin == Kinematics::OperatingAngles && creeping >= creep_stop {
                break;
            }
            let (sp, cp) = phi.sin_cos();
            // dX/dρ = (sin φ, cos φ), dX/dφ = ρ·(cos φ, −sin φ)
            let jp = |row: usize| {
                let (a, b) = (t.r[row].d[0], t.r[row].d[1]);
                [a * sp + b * cp, rho * (a * cp - b * sp)]
            };
            let (j0, j1) = (jp(0), jp(1));
            let mut jac = [j0[0], j0[1], j1[0], j1[1]];
            let mut step = [-t.r[0].v, -t.r[1].v];
            if linalg::solve(&mut jac, &mut step, 2).is_none() {
                // Singular (a contact exactly at zero load): press the ball onto the outer race.
                step = [1e-9, 0.0];
            }
            // Limit the step: a tenth of the groove offset radially, 0.2 rad in angle.
            let lim = (0.1 * self.ro / step[0].abs().max(1e-300))
                .min(0.2 / step[1].abs().max(1e-300))
                .min(1.0);
            let mut accepted = false;
            let mut lam = lim;
            for k in 0..8 {
                let (rn, pn) = (rho + lam * step[0], phi + lam * step[1]);
                let tn = self.terms(p, cart(rn, pn));
                if tn.residual() < res {
                    let capped = k == 0 && lim < 1.0;
                    creeping = if !capped && tn.residual() > 0.9 * res {
                        creeping + 1
                    } else {
                        0
                    };
                    (rho, phi, t) = (rn, pn, tn);
                    accepted = true;
                    break;
                }
                lam *= 0.5;
            }
            if !accepted {
                let r = [t.r[0].v, t.r[1].v];
                if let Some((rn, pn, tn)) = self.ball_lm_step(p, (rho, phi), [j0, j1], r, res) {
                    creeping = if tn.residual() > 0.9 * res {
                        creeping + 1
                    } else {
                        0
                    };
                    (rho, phi, t) = (rn, pn, tn);
                    accepted = true;
                }
            }
            if !accepted {
                break;
            }
        }
        (cart(rho, phi), t)
    }

    /// Levenberg–Marquardt on ½|R|² with diagonal scaling from (ρ, φ) (m, rad), with the rows
    /// `j0`, `j1` of the polar Jacobian and the residual `r` (N) of norm `res`: always a descent
    /// direction, robust where the Jacobian is nearly singular (balls close to losing contact).
    /// Returns the first step (μ from 1e-6, ×10 up to 40 times) that lowers the residual below
    /// `res`: the new (ρ, φ) and terms.
    fn ball_lm_step(
        &self,
        p: &BallProblem,
        (rho, phi): (f64, f64),
        [j0, j1]: [[f64; 2]; 2],
        r: [f64; 2],
        res: f64,
    ) -> Option<(f64, f64, Terms)> {
        let jt = [[j0[0], j1[0]], [j0[1], j1[1]]]; // Jᵀ
        let g = [
            -(jt[0][0] * r[0] + jt[0][1] * r[1]),
            -(jt[1][0] * r[0] + jt[1][1] * r[1]),
        ];
        let a11 = j0[0] * j0[0] + j1[0] * j1[0];
        let a22 = j0[1] * j0[1] + j1[1] * j1[1];
        let a12 = j0[0] * j0[1] + j1[0] * j1[1];
        let mut mu = 1e-6;
        for _ in 0..40 {
            let (b11, b22) = (a11 * (1.0 + mu), a22 * (1.0 + mu));
            let det = b11 * b22 - a12 * a12;
            if det > 0.0 {
                let s0 = (b22 * g[0] - a12 * g[1]) / det;
                let s1 = (b11 * g[1] - a12 * g[0]) / det;
                let (rn, pn) = (rho + s0, phi + s1);
                if rn > 0.0 {
                    let tn = self.terms(p, cart(rn, pn));
                    if tn.residual() < res {
                        return Some((rn, pn, tn));
                    }
                }
            }
            mu *= 10.0;
        }
        None
    }

    /// Reactions and Jacobian at displacement `q`, using and updating warm starts `warm`.
    fn evaluate_with(
        &self,
        q: &[f64; 5],
        warm: &mut [Option<[f64; 2]>],
    ) -> Result<ForceResult, BearingError> {
        let mut f = [0.0; 5];
        let mut jac = [[0.0; 5]; 5];
        for j in 0..self.psi.len() {
            let a = self.groove_offsets(j, q);
            let sol = self.solve_ball(j, a, warm[j])?;
            warm[j] = Some(sol.x);
            // reaction = T·g, A = A(q) with dA/dq = P.
            let (t, p) = self.ring_maps(j);
            let mut dg_dq = [[0.0; 5]; 3];
            for m in 0..3 {
                for n in 0..5 {
                    dg_dq[m][n] = sol.dg[m][0] * p[0][n] + sol.dg[m][1] * p[1][n];
                }
            }
            for r in 0..5 {
                for m in 0..3 {
                    if t[r][m] != 0.0 {
                        f[r] += t[r][m] * sol.g[m];
                        for n in 0..5 {
                            jac[r][n] += t[r][m] * dg_dq[m][n];
                        }
                    }
                }
            }
        }
        Ok(ForceResult {
            reaction: f,
            jacobian: jac,
        })
    }

    /// Whether the model's laws are `laws` (the same shared laws, compared by pointer).
    pub fn has_laws(&self, laws: &ContactLaws) -> bool {
        let same = |a: &[Arc<dyn ContactLaw>], b: &[Arc<dyn ContactLaw>]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| Arc::ptr_eq(x, y))
        };
        same(&self.laws.inner, &laws.inner) && same(&self.laws.outer, &laws.outer)
    }

    /// Replace the contact laws (one per ball and raceway); errors if the counts differ from the
    /// bearing's ball count.
    pub fn set_laws(&mut self, laws: ContactLaws) -> Result<(), BearingError> {
        let z = self.psi.len();
        if laws.inner.len() != z || laws.outer.len() != z {
            return Err(BearingError::LawCount {
                inner: laws.inner.len(),
                outer: laws.outer.len(),
                balls: z,
            });
        }
        self.laws = laws;
        Ok(())
    }

    /// Reactions, stiffness and damping at ring displacements `q` (x, y, z in m; θy, θz in rad)
    /// and rates `q_dot` (m/s, rad/s), using and updating the per-ball warm starts `warm` (one
    /// entry per ball; `None` starts a ball from scratch).
    ///
    /// The balls are massless and follow their quasi-static equilibrium. A law with a damping
    /// term c·δ̇ ([`ContactLaw::damping`]) then acts through the rate of its approach along that
    /// equilibrium, δ̇_k = g_k·q̇ with g_k = dδ_k/dq (ball position included): the damping matrix
    /// is C = Σ_k c_k·g_k·g_kᵀ (symmetric, from the dissipated power Σ c_k·δ̇_k²) and the reaction
    /// is the quasi-static one plus C·q̇. For one ball this is the low-frequency limit of the
    /// inner and outer contacts (spring and damper each) in series. The stiffness omits the term
    /// ∂C/∂q·q̇ (exact at q̇ = 0).
    pub fn evaluate_dynamic(
        &self,
        q: &[f64; 5],
        q_dot: &[f64; 5],
        warm: &mut [Option<[f64; 2]>],
    ) -> Result<DynamicForce, BearingError> {
        check_finite_displacement(q)?;
        for (k, v) in q_dot.iter().enumerate() {
            if !v.is_finite() {
                return Err(BearingError::invalid(
                    DOF_NAMES[k],
                    *v,
                    "a finite rate (m/s or rad/s)",
                ));
            }
        }
        if warm.len() != self.psi.len() {
            return Err(BearingError::WarmStartSize {
                given: warm.len(),
                balls: self.psi.len(),
            });
        }
        let z = self.psi.len();
        let mut out = DynamicForce {
            reaction: [0.0; 5],
            stiffness: [[0.0; 5]; 5],
            damping: [[0.0; 5]; 5],
            loads: Vec::with_capacity(z),
            approaches: Vec::with_capacity(z),
            orbital_speeds: Vec::with_capacity(z),
        };
        for j in 0..z {
            let a = self.groove_offsets(j, q);
            let sol = self.solve_ball(j, a, warm[j])?;
            warm[j] = Some(sol.x);
            let (t, p) = self.ring_maps(j);
            for r in 0..5 {
                for m in 0..3 {
                    if t[r][m] != 0.0 {
                        out.reaction[r] += t[r][m] * sol.g[m];
                        for n in 0..5 {
                            out.stiffness[r][n] +=
                                t[r][m] * (sol.dg[m][0] * p[0][n] + sol.dg[m][1] * p[1][n]);
                        }
                    }
                }
            }
            for (k, law) in [&self.laws.inner[j], &self.laws.outer[j]]
                .iter()
                .enumerate()
            {
                let c = law.damping(sol.delta[k]);
                if c == 0.0 {
                    continue;
                }
                let g: [f64; 5] = std::array::from_fn(|n| {
                    sol.ddelta[k][0] * p[0][n] + sol.ddelta[k][1] * p[1][n]
                });
                let rate: f64 = g.iter().zip(q_dot).map(|(a, b)| a * b).sum();
                for r in 0..5 {
                    out.reaction[r] += c * rate * g[r];
                    for n in 0..5 {
                        out.damping[r][n] += c * g[r] * g[n];
                    }
                }
            }
            out.loads.push(sol.q);
            out.approaches.push(sol.delta);
            out.orbital_speeds.push(sol.orbital_speed);
        }
        Ok(out)
    }

    /// The maps of ball j between its local terms and the ring: reaction = T·g (T: 5×3) and the
    /// groove-centre offsets' derivative dA/dq = P (2×5).
    fn ring_maps(&self, j: usize) -> ([[f64; 3]; 5], [[f64; 5]; 2]) {
        let (s, c) = self.psi[j].sin_cos();
        let rr = self.frak_ri;
        (
            [
                [1.0, 0.0, 0.0],
                [0.0, c, 0.0],
                [0.0, s, 0.0],
                [rr * s, 0.0, -s],
                [-rr * c, 0.0, c],
            ],
            [[1.0, 0.0, 0.0, rr * s, -rr * c], [0.0, c, s, 0.0, 0.0]],
        )
    }

    /// Reactions and their Jacobian at ring displacements `q` (x, y, z in m; θy, θz in rad):
    /// the bearing as a force element. Each call solves every ball's equilibrium from scratch.
    pub fn evaluate(&self, q: &[f64; 5]) -> Result<ForceResult, BearingError> {
        check_finite_displacement(q)?;
        let mut warm = vec![None; self.psi.len()];
        self.evaluate_with(q, &mut warm)
    }

    /// Full per-ball state at displacement `q`.
    fn ball_states(
        &self,
        q: &[f64; 5],
        warm: &mut [Option<[f64; 2]>],
    ) -> Result<Vec<BallState>, BearingError> {
        let geo = &self.bearing.geometry;
        let mut out = Vec::with_capacity(self.psi.len());
        for j in 0..self.psi.len() {
            let a = self.groove_offsets(j, q);
            let sol = self.solve_ball(j, a, warm[j])?;
            let t = self.terms_at(j, sol.x, a);
            let alpha_i = t.sin_ai.atan2(t.cos_ai);
            let alpha_o = t.sin_ao.atan2(t.cos_ao);
            let d = geo.ball_diameter;
            let dm = geo.pitch_diameter;
            let rpi = 0.5 * dm - 0.5 * d * t.cos_ai;
            let rpo = 0.5 * dm + 0.5 * d * t.cos_ao;
            let (lam_i, lam_o) = self.race_control.lambdas();
            let contact = |race: Race, load: f64, alpha: f64, defl: f64, us: f64| {
                let (rx, ry) = geo.curvature_radii(race, alpha);
                let h = self.bearing.hertz(race, alpha)?.contact(load);
                let (race_speed, lam) = match race {
                    Race::Inner => (self.inner_speed, lam_i),
                    Race::Outer => (self.outer_speed, lam_o),
                };
                // Ball angular velocity relative to the race (cage frame, axial and radial
                // components): ω_R·(cos β, −sin β) − (ω_race − ω_m)·(1, 0).
                let (sb, cb) = t.beta.sin_cos();
                let w = [t.om_r * cb - (race_speed - t.om_m), -t.om_r * sb];
                let (sa, ca) = alpha.sin_cos();
                let spin = w[0] * sa + w[1] * ca;
                let roll = w[0] * ca - w[1] * sa;
                Ok::<_, BearingError>(ContactState {
                    spin_to_roll: if roll != 0.0 { spin / roll } else { 0.0 },
                    friction_needed: lam * t.gyro.abs() / d,
                    friction_limit: MU_MAX * load,
                    load,
                    contact_angle: alpha,
                    deflection: defl,
                    semi_major: h.semi_major,
                    semi_minor: h.semi_minor,
                    max_pressure: h.max_pressure,
                    rx,
                    ry,
                    sum_velocity: us,
                })
            };
            out.push(BallState {
                azimuth: self.psi[j],
                orbital_speed: t.om_m,
                spin_speed: t.om_r,
                pitch_angle: t.beta,
                kinematic_angle: a[0].atan2(a[1]),
                centrifugal_force: t.fc,
                gyroscopic_moment: t.gyro,
                inner_friction: t.fi,
                outer_friction: t.fo,
                inner: contact(
                    Race::Inner,
                    t.qi,
                    alpha_i,
                    t.di,
                    2.0 * ((self.inner_speed - t.om_m) * rpi).abs(),
                )?,
                outer: contact(
                    Race::Outer,
                    t.qo,
                    alpha_o,
                    t.dout,
                    2.0 * ((self.outer_speed - t.om_m) * rpo).abs(),
                )?,
            });
        }
        Ok(out)
    }
}

fn check_finite_displacement(q: &[f64; 5]) -> Result<(), BearingError> {
    for (k, v) in q.iter().enumerate() {
        if !v.is_finite() {
            return Err(BearingError::invalid(
                DOF_NAMES[k],
                *v,
                "a finite displacement (m) or tilt (rad)",
            ));
        }
    }
    Ok(())
}

/// Solve the bearing's quasi-static equilibrium at operating point `op` with contact laws `laws`.
///
/// Newton–Raphson on the load-controlled DOFs with an exact Jacobian and a backtracking line
/// search; Levenberg–Marquardt steps when the Jacobian is singular (all balls unloaded).
/// Non-convergence, or a load that needs deflections beyond `settings.max_deflection_ratio`·D or
/// reverses the contact angles of an angular-contact bearing, is an error that carries the
/// residual.
pub fn solve_equilibrium(
    bearing: &Bearing,
    laws: &ContactLaws,
    op: &OperatingPoint,
    settings: &EquilibriumSettings,
) -> Result<Equilibrium, BearingError> {
    let model = BearingModel::new(
        bearing,
        laws,
        op.inner_speed,
        op.outer_speed,
        op.race_control,
    )?
    .with_kinematics(settings.kinematics);
    let geo = &bearing.geometry;
    let DofControls {
        displacement: mut q,
        load: target,
        free,
    } = dof_controls(op)?;
    let problem = LoadProblem {
        model: &model,
        free,
        target,
        lever: 0.5 * geo.pitch_diameter,
    };
    let tol = settings.tolerance * problem.load_scale();
    initial_guess(bearing, laws, &problem.free, &problem.target, &mut q)?;
    let start = problem.iterate_at(q, vec![None; geo.ball_count])?;
    let (end, iterations, history) = problem.solve(start, settings.max_iterations, tol);
    if end.rn > tol {
        return Err(BearingError::NotConverged {
            iterations,
            residual: end.rn,
            tolerance: tol,
        });
    }
    let LoadIterate {
        q, mut warm, rn, ..
    } = end;
    let balls = model.ball_states(&q, &mut warm)?;
    check_carried(bearing, &balls, settings)?;
    check_ring_held(&problem.free, &balls)?;
    let warnings = warnings(&balls, settings.kinematics);
    let full = model.evaluate_with(&q, &mut warm)?;
    Ok(Equilibrium {
        converged: true,
        iterations,
        residual: rn,
        residual_history: history,
        displacement: q,
        reaction: full.reaction,
        stiffness: full.jacobian,
        balls,
        warnings,
    })
}

/// The DOF controls of an operating point, split by kind.
struct DofControls {
    /// Imposed displacements (m, rad); zero for the load-controlled DOFs.
    displacement: [f64; 5],
    /// Applied loads (N, N·m); zero for the displacement-controlled DOFs.
    load: [f64; 5],
    /// The load-controlled DOFs, in order.
    free: Vec<usize>,
}

/// The DOF controls of `op`; a value that is not finite is an error naming its DOF.
fn dof_controls(op: &OperatingPoint) -> Result<DofControls, BearingError> {
    let mut q = [0.0; 5];
    let mut target = [0.0; 5];
    let mut free = Vec::new();
    for (k, c) in op.dofs.iter().enumerate() {
        match *c {
            Control::Load(f) => {
                if !f.is_finite() {
                    return Err(BearingError::invalid(
                        DOF_NAMES[k],
                        f,
                        "a finite load (N or N·m)",
                    ));
                }
                target[k] = f;
                free.push(k);
            }
            Control::Displacement(v) => {
                if !v.is_finite() {
                    return Err(BearingError::invalid(
                        DOF_NAMES[k],
                        v,
                        "a finite displacement (m) or tilt (rad)",
                    ));
                }
                q[k] = v;
            }
        }
    }
    Ok(DofControls {
        displacement: q,
        load: target,
        free,
    })
}

/// The load-controlled part of an equilibrium solve: the model, the load-controlled DOFs
/// `free` and the applied loads `target` (N, N·m), and the pitch radius `lever` (m) that
/// scales moments to forces in the residual.
struct LoadProblem<'a> {
    model: &'a BearingModel,
    free: Vec<usize>,
    target: [f64; 5],
    lever: f64,
}

/// An iterate of the equilibrium's Newton iteration: the ring displacements (m, rad), the
/// balls' warm starts, the reactions there, and the scaled residual of the load-controlled DOFs
/// (N) with its largest magnitude.
struct LoadIterate {
    q: [f64; 5],
    warm: Vec<Option<[f64; 2]>>,
    fr: ForceResult,
    r: Vec<f64>,
    rn: f64,
}

impl LoadProblem<'_> {
    /// The residual scale of DOF `k`: 1 for forces, 1/lever for moments (1/m).
    fn unit(&self, k: usize) -> f64 {
        if k >= 3 {
            1.0 / self.lever
        } else {
            1.0
        }
    }

    /// Largest applied load (moments divided by the lever), at least 1 N: the residual
    /// tolerance is relative to it.
    fn load_scale(&self) -> f64 {
        self.free
            .iter()
            .map(|&k| (self.target[k] * self.unit(k)).abs())
            .fold(1.0_f64, f64::max)
    }

    /// The scaled residual of the load-controlled DOFs at reactions `fr` (N) and its largest
    /// magnitude.
    fn residual(&self, fr: &ForceResult) -> (Vec<f64>, f64) {
        let r: Vec<f64> = self
            .free
            .iter()
            .map(|&k| (fr.reaction[k] - self.target[k]) * self.unit(k))
            .collect();
        let n = r.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        (r, n)
    }

    /// The iterate at displacements `q`, the balls solved from warm starts `warm`.
    fn iterate_at(
        &self,
        q: [f64; 5],
        mut warm: Vec<Option<[f64; 2]>>,
    ) -> Result<LoadIterate, BearingError> {
        let fr = self.model.evaluate_with(&q, &mut warm)?;
        let (r, rn) = self.residual(&fr);
        Ok(LoadIterate { q, warm, fr, r, rn })
    }

    /// Newton–Raphson on the load-controlled DOFs from `it` with the exact Jacobian and a
    /// backtracking line search, Levenberg–Marquardt steps when the Jacobian is singular, until
    /// the residual is at most `tol` (N) or after `max_iterations`. Returns the last iterate,
    /// the iterations and the residual history (N).
    fn solve(
        &self,
        mut it: LoadIterate,
        max_iterations: usize,
        tol: f64,
    ) -> (LoadIterate, usize, Vec<f64>) {
        let mut history = vec![it.rn];
        let mut iterations = 0;
        let mut mu = 0.0_f64;
        while it.rn > tol && iterations < max_iterations {
            iterations += 1;
            let n = self.free.len();
            let jac = self.scaled_jacobian(&it.fr);
            let mut step: Vec<f64> = it.r.iter().map(|x| -x).collect();
            let newton_ok = mu == 0.0 && linalg::solve(&mut jac.clone(), &mut step, n).is_some();
            if !newton_ok {
                mu = if mu == 0.0 { 1e-3 } else { mu };
                step = self.lm_step(&jac, &it, mu);
            }
            match self.line_search(&it, &step, tol) {
                Some(next) => {
                    it = next;
                    mu = if newton_ok {
                        0.0
                    } else {
                        (mu * 0.3).max(1e-12)
                    };
                    if mu < 1e-9 {
                        mu = 0.0;
                    }
                }
                None if mu > 1e12 => break,
                None => mu = if mu == 0.0 { 1e-3 } else { mu * 10.0 },
            }
            history.push(it.rn);
        }
        (it, iterations, history)
    }

    /// The Jacobian of the scaled residual, row-major n × n: rows scaled like the residual,
    /// columns in m or rad.
    fn scaled_jacobian(&self, fr: &ForceResult) -> Vec<f64> {
        let n = self.free.len();
        let mut jac = vec![0.0; n * n];
        for (a, &ka) in self.free.iter().enumerate() {
            for (b, &kb) in self.free.iter().enumerate() {
                jac[a * n + b] = fr.jacobian[ka][kb] * self.unit(ka);
            }
        }
        jac
    }

    /// The Levenberg–Marquardt step (JᵀJ + μ·diag(JᵀJ) + ε)·s = −Jᵀr at iterate `it` with the
    /// scaled Jacobian `jac`; where J is identically zero, a small push (1e-7 m or rad) of every
    /// free DOF toward its load.
    fn lm_step(&self, jac: &[f64], it: &LoadIterate, mu: f64) -> Vec<f64> {
        let n = self.free.len();
        let r = &it.r;
        let mut jtj = vec![0.0; n * n];
        let mut g = vec![0.0; n];
        for a in 0..n {
            for b in 0..n {
                jtj[a * n + b] = (0..n).map(|m| jac[m * n + a] * jac[m * n + b]).sum();
            }
            g[a] = -(0..n).map(|m| jac[m * n + a] * r[m]).sum::<f64>();
        }
        let dmax = (0..n).map(|a| jtj[a * n + a]).fold(0.0_f64, f64::max);
        for a in 0..n {
            jtj[a * n + a] += mu * jtj[a * n + a] + 1e-12 * dmax.max(1e-30);
        }
        if linalg::solve(&mut jtj, &mut g, n).is_none() {
            // Jacobian identically zero: push every free DOF toward its load.
            g = self
                .free
                .iter()
                .map(|&k| 1e-7 * (self.target[k] - it.fr.reaction[k]).signum())
                .collect();
        }
        g
    }

    /// Backtracking line search along `step` from `it`: the first of up to 50 halvings, from a
    /// step limited to 10 % of the ball diameter, that lowers the residual or meets `tol` (N);
    /// None if none does.
    fn line_search(&self, it: &LoadIterate, step: &[f64], tol: f64) -> Option<LoadIterate> {
        let ball_diameter = self.model.bearing.geometry.ball_diameter;
        let smax = step.iter().fold(0.0_f64, |m, x| m.max(x.abs())) * self.lever.max(1.0);
        let mut lam: f64 = (0.1 * ball_diameter / smax.max(1e-300)).min(1.0);
        for _ in 0..50 {
            let mut qn = it.q;
            for (a, &k) in self.free.iter().enumerate() {
                qn[k] += lam * step[a];
            }
            if let Ok(next) = self.iterate_at(qn, it.warm.clone()) {
                if next.rn < it.rn || next.rn <= tol {
                    return Some(next);
                }
            }
            lam *= 0.5;
        }
        None
    }
}

/// A free DOF with no ball touching the inner race (zero load at speed: the balls ride on the
/// outer race) leaves the ring position undetermined: an error.
fn check_ring_held(free: &[usize], balls: &[BallState]) -> Result<(), BearingError> {
    let outer_total: f64 = balls.iter().map(|b| b.outer.load).sum();
    if !free.is_empty()
        && balls.iter().all(|b| b.inner.load <= 1e-9 * outer_total)
        && outer_total > 0.0
    {
        return Err(BearingError::Overloaded {
            reason: "no ball touches the inner race (the loads are zero and centrifugal force holds the balls on the outer race): the ring position is undetermined; apply a load or impose the displacements".into(),
        });
    }
    Ok(())
}

/// Largest deviation of the kinematic angle from a loaded ball's contact angles before a warning,
/// rad.
const KINEMATIC_ANGLE_WARNING: f64 = 1.0 * std::f64::consts::PI / 180.0;

fn warnings(balls: &[BallState], kinematics: Kinematics) -> Vec<String> {
    let mut out = Vec::new();
    if kinematics == Kinematics::GrooveLine {
        kinematic_angle_warning(balls, &mut out);
    }
    friction_warnings(balls, &mut out);
    out
}

/// Groove-line model: the kinematic angle far from a loaded ball's contact angles.
fn kinematic_angle_warning(balls: &[BallState], out: &mut Vec<String>) {
    let qmax = balls.iter().map(|b| b.inner.load).fold(0.0, f64::max);
    let (mut worst, mut at) = (0.0_f64, 0);
    for (j, b) in balls.iter().enumerate() {
        if b.inner.load > 0.01 * qmax {
            let dev = (b.inner.contact_angle - b.kinematic_angle)
                .abs()
                .max((b.outer.contact_angle - b.kinematic_angle).abs());
            if dev > worst {
                (worst, at) = (dev, j);
            }
        }
    }
    if worst > KINEMATIC_ANGLE_WARNING {
        out.push(format!(
            "the ball speeds are evaluated at the groove-centre angle, which differs from ball {at}'s contact angles by {:.2}°: orbital speed, centrifugal force and gyroscopic moment are approximate there (README, modelling choices)",
            worst.to_degrees()
        ));
    }
}

/// Gyroscopic friction near its limit μ_max·Q: a warning from 80 % of the limit needed, saying
/// whether the contact still transmits it in full (up to [`FRICTION_FULL_CONTROL`]) or the
/// moment is partly unresisted (the ball pivots).
fn friction_warnings(balls: &[BallState], out: &mut Vec<String>) {
    for (j, b) in balls.iter().enumerate() {
        for (race, f, c) in [
            ("inner", b.inner_friction, &b.inner),
            ("outer", b.outer_friction, &b.outer),
        ] {
            let limit = MU_MAX * c.load;
            if c.load > 0.0 && c.friction_needed > 0.8 * limit {
                let consequence = if c.friction_needed > FRICTION_FULL_CONTROL * limit {
                    "the moment is partly unresisted (the ball pivots)"
                } else {
                    "still transmitted in full (race control holds)"
                };
                out.push(format!(
                    "ball {j}: the gyroscopic friction needed at the {race} contact, {:.3} N, is {:.0} % of its limit μ_max·Q = {:.3} N (transmitted {:.3} N): {consequence}",
                    c.friction_needed,
                    100.0 * c.friction_needed / limit,
                    limit,
                    f.abs(),
                ));
            }
        }
    }
}

/// A solution outside what the bearing can physically carry is an error.
fn check_carried(
    bearing: &Bearing,
    balls: &[BallState],
    settings: &EquilibriumSettings,
) -> Result<(), BearingError> {
    let d = bearing.geometry.ball_diameter;
    // Loads below this are zero to round-off: a ball that merely touches a race at zero speed
    // (its position in the gap is arbitrary) has no meaningful contact angle.
    let zero_load = 1e-12
        * balls
            .iter()
            .map(|b| b.inner.load.max(b.outer.load))
            .fold(0.0, f64::max);
    for (j, b) in balls.iter().enumerate() {
        for (race, c) in [("inner", &b.inner), ("outer", &b.outer)] {
            if c.deflection > settings.max_deflection_ratio * d {
                return Err(BearingError::Overloaded {
                    reason: format!(
                        "ball {j} {race} deflection {:.3e} m exceeds {} × D (load {:.4e} N, Hertz pressure {:.2} GPa)",
                        c.deflection,
                        settings.max_deflection_ratio,
                        c.load,
                        c.max_pressure * 1e-9
                    ),
                });
            }
            // The inner contact angle shows the direction of the ring's axial load; the outer one
            // may dip below zero for a lightly loaded ball held by centrifugal force and friction.
            if race == "inner" && c.load > zero_load && c.contact_angle < settings.min_contact_angle
            {
                return Err(BearingError::Overloaded {
                    reason: format!(
                        "ball {j} {race} contact angle {:.2}° is below the shoulder limit {:.1}°: a single-row angular-contact bearing cannot carry this load (reversed or too little thrust)",
                        c.contact_angle.to_degrees(),
                        settings.min_contact_angle.to_degrees()
                    ),
                });
            }
        }
    }
    Ok(())
}

/// Starting displacements from the dry thrust and radial load relations (Jones; Stribeck's 4.37
/// factor for zero clearance), so that the first Newton step sees loaded balls.
fn initial_guess(
    bearing: &Bearing,
    laws: &ContactLaws,
    free: &[usize],
    target: &[f64; 5],
    q: &mut [f64; 5],
) -> Result<(), BearingError> {
    let geo = &bearing.geometry;
    let z = geo.ball_count as f64;
    let a0 = geo.free_contact_angle;
    // Series constant from the laws of ball 0 at a reference load.
    let qref = {
        let f = target[..3].iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        (f / z).max(1.0)
    };
    let di = laws.inner[0].approach_at(qref).unwrap_or(0.0).max(0.0);
    let dn = di + laws.outer[0].approach_at(qref).unwrap_or(0.0).max(0.0);
    // δ_n ∝ Q^(2/3) near the reference load.
    let approach = |per_ball: f64| dn * (per_ball.abs() / qref).powf(2.0 / 3.0);
    let lever = geo.inner_groove_center_radius();
    for &k in free {
        let f = target[k];
        let g = match k {
            0 => approach(f / (z * a0.sin().max(0.1))) / a0.sin().max(0.1),
            1 | 2 => approach(4.37 * f / (z * a0.cos())) / a0.cos(),
            _ => approach(4.37 * f / (z * lever * a0.sin().max(0.1))) / (lever * a0.sin().max(0.1)),
        };
        q[k] = g.copysign(f);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::geometry::BearingGeometry;
    use crate::material::Solid;

    pub(crate) fn b7006() -> Bearing {
        Bearing {
            geometry: BearingGeometry::new(11, 7e-3, 42.5e-3, 0.51, 0.54, 15f64.to_radians())
                .unwrap(),
            ball_material: Solid::AISI_52100,
            ring_material: Solid::AISI_52100,
        }
    }

    #[test]
    fn seed_case_converges() {
        let b = b7006();
        let laws = ContactLaws::hertz(&b).unwrap();
        let op = OperatingPoint {
            inner_speed: 5000.0 * PI / 30.0,
            outer_speed: 0.0,
            dofs: [
                Control::Load(1000.0),
                Control::Load(1000.0),
                Control::Load(1000.0),
                Control::Displacement(0.001f64.to_radians()),
                Control::Displacement(0.001f64.to_radians()),
            ],
            race_control: RaceControl::Outer,
        };
        let e = solve_equilibrium(&b, &laws, &op, &EquilibriumSettings::default()).unwrap();
        assert!(e.converged);
        for k in 0..3 {
            assert!((e.reaction[k] - 1000.0).abs() < 1e-7, "{:?}", e.reaction);
        }
    }
}
