//! The bearing as a force element for rotor simulations: ring displacements q, their rates q̇,
//! the ring speeds and the cage angle in; the five reactions on the inner ring, their stiffness
//! ∂F/∂q and damping ∂F/∂q̇, the contact loads and flags out.
//!
//! - [`ForceElement`]: the interface a rotor integrator calls every time step, with a
//!   caller-owned warm-start [`ElementState`] (one per bearing and caller) that makes repeated
//!   calls cheap.
//! - [`LawElement`]: contact laws fixed per contact — dry Hertz ([`LawElement::hertz`]) or the
//!   fitted laws of a characterization ([`LawElement::from_characterization`]), including each
//!   contact's damping c·δ̇ from the harmonic method.
//! - [`TrendForceElement`]: laws from a study's trend curves, load- and speed-dependent, with no
//!   EHL run.
//!
//! Every element owns its data (`Send + Sync + Clone`), so it can live in a rotor model, a Python
//! object or another thread. Conventions: x axial, y and z radial, θy and θz tilts about +y and
//! +z (right-handed); ball j at azimuth ψ_j = 2πj/Z + cage angle from +y toward +z; SI units
//! (m, rad, m/s, rad/s, N, N·m, N/m, N·s/m). The reaction is the load on the inner ring in
//! equilibrium with the balls: the bearing acts on the shaft with the opposite.

use crate::bearing::{cage_speed_of, Bearing, ForceResult};
use crate::bearing::{
    BearingError, BearingModel, ContactLaws, DynamicForce, Kinematics, Race, RaceControl,
};
use crate::case::Case;
use crate::characterize::{
    BearingCharacterization, CharacterizationReport, CharacterizeError, ContactRow,
};
use crate::contact_law::ContactLaw;
use crate::fit::FittedLaw;
use crate::trends::{RaceTrends, SpeedLaws, TrendModel};
use serde::Serialize;
use std::sync::Arc;

/// The inputs of one evaluation (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ElementInput {
    /// Inner-ring displacements x, y, z (m) and tilts θy, θz (rad) relative to the outer ring.
    pub displacement: [f64; 5],
    /// Their rates (m/s, rad/s).
    pub velocity: [f64; 5],
    /// Inner-ring speed about +x, rad/s.
    pub inner_speed: f64,
    /// Outer-ring speed about +x, rad/s.
    pub outer_speed: f64,
    /// Cage angle, rad: ball j sits at azimuth 2πj/Z + cage angle. Advance it at the operating
    /// cage speed ([`ElementOutput::cage_speed`], [`ForceElement::cage_speed_at`]) for the
    /// varying-compliance excitation at Z·f_cage; hold it fixed for a time-invariant bearing.
    pub cage_angle: f64,
}

impl ElementInput {
    /// Displacement `q` at rest (zero rates, cage angle 0) and the given speeds (rad/s).
    pub fn at(displacement: [f64; 5], inner_speed: f64, outer_speed: f64) -> Self {
        ElementInput {
            displacement,
            velocity: [0.0; 5],
            inner_speed,
            outer_speed,
            cage_angle: 0.0,
        }
    }
}

/// The result of one evaluation (SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ElementOutput {
    /// Load on the inner ring in equilibrium with the balls: F_x, F_y, F_z (N), M_y, M_z (N·m),
    /// damping term included.
    pub reaction: [f64; 5],
    /// ∂reaction/∂q (N/m, N, N·m/rad), order x, y, z, θy, θz; not symmetrized.
    pub stiffness: [[f64; 5]; 5],
    /// ∂reaction/∂q̇ (N·s/m, N·s, N·m·s/rad); zero for laws without damping.
    pub damping: [[f64; 5]; 5],
    /// Per ball: [inner, outer] contact loads without the damping term, N.
    pub loads: Vec<[f64; 2]>,
    /// Per ball: [inner, outer] contact approaches δ, m (negative: separated).
    pub approaches: Vec<[f64; 2]>,
    /// Loaded contacts whose approach lies outside the range their law was fitted on (or, for a
    /// trend element, whose load lies outside the trends' load range): (ball, race).
    pub outside_range: Vec<(usize, Race)>,
    /// For a trend element: the speed lies outside the trends' speed range (laws evaluated at the
    /// nearest end). Always false for fixed laws.
    pub speed_outside: bool,
    /// Contacts whose approach exceeds [`OVERLOAD_DEFLECTION_RATIO`]·D (ball, race): a ring
    /// displacement no bearing survives (e.g. a 1 rad tilt gave a 26 MN contact load); the
    /// numbers are returned as computed, flagged here.
    pub overloaded: Vec<(usize, Race)>,
    /// Per ball: orbital speed ω_m of the bearing model at this state (the textbook kinematics
    /// at its operating contact angles by default), rad/s.
    pub orbital_speeds: Vec<f64>,
    /// The cage speed at this state, rad/s: the load-weighted mean of `orbital_speeds`
    /// ([`crate::bearing::cage_speed_of`]); the plain mean when no ball is loaded.
    pub cage_speed: f64,
}

/// Contact approach, as a fraction of the ball diameter, beyond which an element flags the
/// contact as overloaded: the equilibrium's own limit (`max_deflection_ratio`, 2 % of D), far
/// beyond the permanent deformation of ISO 76's static rating (1e-4·D).
pub const OVERLOAD_DEFLECTION_RATIO: f64 = 0.02;

/// The contacts of `approaches` beyond [`OVERLOAD_DEFLECTION_RATIO`]·D.
fn overloaded(bearing: &Bearing, approaches: &[[f64; 2]]) -> Vec<(usize, Race)> {
    let limit = OVERLOAD_DEFLECTION_RATIO * bearing.geometry.ball_diameter;
    let mut out = Vec::new();
    for (j, a) in approaches.iter().enumerate() {
        for (k, race) in [Race::Inner, Race::Outer].into_iter().enumerate() {
            if a[k].is_nan() || a[k] > limit {
                out.push((j, race));
            }
        }
    }
    out
}

/// Caller-owned state of an element between calls: warm starts of every ball's equilibrium and
/// the model at the last speeds. One per bearing and caller; [`ElementState::default`] starts
/// cold. Results do not depend on it beyond the solvers' tolerances.
#[derive(Debug, Clone, Default)]
pub struct ElementState {
    model: Option<BearingModel>,
    warm: Vec<Option<[f64; 2]>>,
    loads: Vec<[f64; 2]>,
}

/// A bearing as a force element.
pub trait ForceElement: Send + Sync {
    /// Reactions, stiffness and damping at `input`, warm-started from and updating `state`.
    /// Errors (a ball whose equilibrium does not converge, with its residual; non-finite
    /// inputs, naming them) leave `state` usable.
    fn evaluate(
        &self,
        input: &ElementInput,
        state: &mut ElementState,
    ) -> Result<ElementOutput, crate::Error>;

    /// Number of balls Z.
    fn ball_count(&self) -> usize;

    /// The bearing (geometry and materials).
    fn bearing(&self) -> &Bearing;

    /// The no-load cage speed at ring speeds `inner_speed` and `outer_speed` (rad/s): pure
    /// rolling at the free contact angle, ω_c = ½·[ω_i·(1 − γ) + ω_o·(1 + γ)], γ = D·cos α0/d_m,
    /// rad/s. A fallback for an unloaded bearing or a speed ratio before any evaluation: at an
    /// operating point the balls orbit at the speeds of their operating contact angles
    /// ([`ForceElement::cage_speed_at`]; 0.2–0.3 % faster for the seed 7006 at 5000 rpm, 11–12 %
    /// for the 218 at 15000 rpm).
    fn cage_speed(&self, inner_speed: f64, outer_speed: f64) -> f64 {
        let g = &self.bearing().geometry;
        let gamma = g.ball_diameter * g.free_contact_angle.cos() / g.pitch_diameter;
        0.5 * (inner_speed * (1.0 - gamma) + outer_speed * (1.0 + gamma))
    }

    /// The cage speed at the operating state `input` (displacement, speeds, cage angle), rad/s:
    /// the load-weighted mean of the bearing model's ball orbital speeds there
    /// ([`ElementOutput::cage_speed`]), warm-started from and updating `state`. A rotor
    /// integrator reads it from each evaluation's output instead.
    fn cage_speed_at(
        &self,
        input: &ElementInput,
        state: &mut ElementState,
    ) -> Result<f64, crate::Error> {
        Ok(self.evaluate(input, state)?.cage_speed)
    }

    /// The reactions at `input` alone (a convenience over [`ForceElement::evaluate`] with a cold
    /// state).
    fn reaction(&self, input: &ElementInput) -> Result<[f64; 5], crate::Error> {
        Ok(self.evaluate(input, &mut ElementState::default())?.reaction)
    }
}

/// Make the model in `state` that of `bearing` with `laws` and `race_control` at the input's
/// speeds and cage angle: rebuilt (cold warm starts) when the state is new or was used with
/// another bearing, otherwise updated in place.
fn prepare(
    state: &mut ElementState,
    bearing: &Bearing,
    laws: &ContactLaws,
    (race_control, kinematics): (RaceControl, Kinematics),
    input: &ElementInput,
) -> Result<(), BearingError> {
    let z = bearing.geometry.ball_count;
    let model = match state.model.as_mut() {
        Some(m)
            if m.bearing() == bearing
                && m.race_control() == race_control
                && m.kinematics() == kinematics =>
        {
            if !m.has_laws(laws) {
                m.set_laws(laws.clone())?;
            }
            m
        }
        _ => {
            state.warm = vec![None; z];
            state.loads.clear();
            state.model.insert(
                BearingModel::new(
                    bearing,
                    laws,
                    input.inner_speed,
                    input.outer_speed,
                    race_control,
                )?
                .with_kinematics(kinematics),
            )
        }
    };
    model.set_speeds(input.inner_speed, input.outer_speed)?;
    model.set_cage_angle(input.cage_angle)
}

fn solve(state: &mut ElementState, input: &ElementInput) -> Result<DynamicForce, BearingError> {
    let ElementState { model, warm, .. } = state;
    let model = model.as_ref().ok_or(BearingError::StateWithoutModel)?;
    // A failed solve must not poison the warm starts.
    let mut trial = warm.clone();
    let out = model.evaluate_dynamic(&input.displacement, &input.velocity, &mut trial)?;
    *warm = trial;
    Ok(out)
}

/// The fitted law (with its damping, if fitted) of one row of a characterization report.
fn row_law(row: &ContactRow) -> Result<FittedLaw, crate::Error> {
    let law = FittedLaw::new(
        row.k,
        row.d,
        row.delta_f_n,
        row.fit_approach_min_m,
        row.fit_approach_max_m,
    )?;
    Ok(match row.damping_n_s_m {
        Some(c) => law.with_damping(c)?,
        None => law,
    })
}

/// A bearing whose every contact has a fixed law: dry Hertz, or the fitted laws of one
/// characterization (with their damping terms, if the method fitted them).
#[derive(Debug, Clone)]
pub struct LawElement {
    bearing: Bearing,
    laws: ContactLaws,
    race_control: RaceControl,
    kinematics: Kinematics,
    /// The fitted laws per ball [inner, outer], for the range flags (None for dry laws and laws
    /// by load).
    fitted: Option<Vec<[FittedLaw; 2]>>,
    /// Laws by load [inner, outer], shared by every ball (None for laws per contact).
    by_load: Option<[Arc<LoadInterpolatedLaw>; 2]>,
}

impl LawElement {
    /// Dry Hertz laws (K at the free contact angle) for `bearing` with `race_control`.
    pub fn hertz(bearing: &Bearing, race_control: RaceControl) -> Result<Self, crate::Error> {
        bearing.validate()?;
        Ok(LawElement {
            bearing: *bearing,
            laws: ContactLaws::hertz(bearing)?,
            race_control,
            kinematics: Kinematics::default(),
            fitted: None,
            by_load: None,
        })
    }

    /// Dry Hertz laws for the bearing, race control and kinematics model of `case`.
    pub fn hertz_case(case: &Case) -> Result<Self, crate::Error> {
        Ok(Self::hertz(&case.bearing, case.operating.race_control)?
            .with_kinematics(case.settings.kinematics))
    }

    /// The same element with the ball kinematics evaluated by `kinematics` (default: the
    /// textbook model at the operating contact angles, as the equilibrium's default).
    pub fn with_kinematics(mut self, kinematics: Kinematics) -> Self {
        self.kinematics = kinematics;
        self
    }

    /// The fitted laws of a characterization of `case` (the laws of its final equilibrium,
    /// including each contact's c·δ̇ term where the method fitted one).
    pub fn from_characterization(
        case: &Case,
        c: &BearingCharacterization,
    ) -> Result<Self, crate::Error> {
        let laws: Vec<FittedLaw> = c.contacts.iter().map(|r| r.characterized.law).collect();
        Ok(
            Self::from_fitted(&case.bearing, case.operating.race_control, &laws)?
                .with_kinematics(case.settings.kinematics),
        )
    }

    /// The fitted laws of a characterization report (e.g. a study point file or
    /// `characterization.json`) for `bearing` with `race_control`.
    pub fn from_report(
        bearing: &Bearing,
        race_control: RaceControl,
        report: &CharacterizationReport,
    ) -> Result<Self, crate::Error> {
        let laws = report
            .contacts
            .iter()
            .map(row_law)
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_fitted(bearing, race_control, &laws)
    }

    /// Fitted laws in contact order (ball 0 inner, ball 0 outer, ball 1 inner, …).
    pub fn from_fitted(
        bearing: &Bearing,
        race_control: RaceControl,
        laws: &[FittedLaw],
    ) -> Result<Self, crate::Error> {
        bearing.validate()?;
        let z = bearing.geometry.ball_count;
        if laws.len() != 2 * z {
            return Err(BearingError::ElementLawCount {
                given: laws.len(),
                balls: z,
            }
            .into());
        }
        let pairs: Vec<[FittedLaw; 2]> = laws.chunks(2).map(|p| [p[0], p[1]]).collect();
        let inner: Vec<Arc<dyn ContactLaw>> = pairs
            .iter()
            .map(|p| Arc::new(p[0]) as Arc<dyn ContactLaw>)
            .collect();
        let outer: Vec<Arc<dyn ContactLaw>> = pairs
            .iter()
            .map(|p| Arc::new(p[1]) as Arc<dyn ContactLaw>)
            .collect();
        Ok(LawElement {
            bearing: *bearing,
            laws: ContactLaws { inner, outer },
            race_control,
            kinematics: Kinematics::default(),
            fitted: Some(pairs),
            by_load: None,
        })
    }

    /// Laws by load from a characterization of `case`: every ball, at any cage angle, takes the
    /// law of the load it carries, interpolated over the characterization's per-contact laws of
    /// its raceway ([`LoadInterpolatedLaw`], knots at each contact's characterization load). The
    /// balls are then alike, so a rolling cage excites Z·f_cage and its harmonics only, where the
    /// per-contact laws of [`LawElement::from_characterization`] (each fixed to its position in the
    /// case) turn with the cage and excite f_cage. Valid at the characterization's speed.
    pub fn by_load_from_characterization(
        case: &Case,
        c: &BearingCharacterization,
    ) -> Result<Self, crate::Error> {
        let mut pts: [Vec<(f64, FittedLaw)>; 2] = [Vec::new(), Vec::new()];
        for r in &c.contacts {
            pts[r.race as usize].push((r.characterized.load, r.characterized.law));
        }
        Ok(
            Self::by_load(&case.bearing, case.operating.race_control, &pts[0], &pts[1])?
                .with_kinematics(case.settings.kinematics),
        )
    }

    /// Laws by load from a characterization report (each row's law at its
    /// `characterized_load_n`), as [`LawElement::by_load_from_characterization`].
    pub fn by_load_from_report(
        bearing: &Bearing,
        race_control: RaceControl,
        report: &CharacterizationReport,
    ) -> Result<Self, crate::Error> {
        let mut pts: [Vec<(f64, FittedLaw)>; 2] = [Vec::new(), Vec::new()];
        for row in &report.contacts {
            let k = match row.race.as_str() {
                "inner" => 0,
                "outer" => 1,
                other => {
                    return Err(BearingError::ContactRace {
                        ball: row.ball,
                        race: other.to_string(),
                    }
                    .into())
                }
            };
            pts[k].push((row.characterized_load_n, row_law(row)?));
        }
        Self::by_load(bearing, race_control, &pts[0], &pts[1])
    }

    /// Laws by load from `(characterization load w in N, fitted law)` pairs of the inner and the
    /// outer raceway ([`LoadInterpolatedLaw::new`]); every ball on a raceway shares its law.
    pub fn by_load(
        bearing: &Bearing,
        race_control: RaceControl,
        inner: &[(f64, FittedLaw)],
        outer: &[(f64, FittedLaw)],
    ) -> Result<Self, crate::Error> {
        bearing.validate()?;
        let z = bearing.geometry.ball_count;
        let li = Arc::new(LoadInterpolatedLaw::new(inner)?);
        let lo = Arc::new(LoadInterpolatedLaw::new(outer)?);
        let (ai, ao): (Arc<dyn ContactLaw>, Arc<dyn ContactLaw>) = (li.clone(), lo.clone());
        Ok(LawElement {
            bearing: *bearing,
            laws: ContactLaws {
                inner: vec![ai; z],
                outer: vec![ao; z],
            },
            race_control,
            kinematics: Kinematics::default(),
            fitted: None,
            by_load: Some([li, lo]),
        })
    }

    /// The laws by load [inner, outer], if the element was built by load.
    pub fn laws_by_load(&self) -> Option<[&LoadInterpolatedLaw; 2]> {
        self.by_load.as_ref().map(|[i, o]| [i.as_ref(), o.as_ref()])
    }

    /// Whether the laws carry damping terms.
    pub fn has_damping(&self) -> bool {
        self.fitted
            .as_ref()
            .is_some_and(|f| f.iter().flatten().any(|l| l.c().is_some()))
            || self.by_load.as_ref().is_some_and(|b| {
                b.iter()
                    .any(|l| l.damping.iter().any(|c| *c != 0.0) || l.low.c().is_some())
            })
    }
}

impl ForceElement for LawElement {
    fn evaluate(
        &self,
        input: &ElementInput,
        state: &mut ElementState,
    ) -> Result<ElementOutput, crate::Error> {
        prepare(
            state,
            &self.bearing,
            &self.laws,
            (self.race_control, self.kinematics),
            input,
        )?;
        let f = solve(state, input)?;
        let mut outside_range = Vec::new();
        if let Some(fitted) = &self.fitted {
            for (j, (laws, delta)) in fitted.iter().zip(&f.approaches).enumerate() {
                for (k, race) in [Race::Inner, Race::Outer].into_iter().enumerate() {
                    if f.loads[j][k] > 0.0 && laws[k].outside_fit_range(delta[k]) {
                        outside_range.push((j, race));
                    }
                }
            }
        }
        if let Some(by_load) = &self.by_load {
            for (j, delta) in f.approaches.iter().enumerate() {
                for (k, race) in [Race::Inner, Race::Outer].into_iter().enumerate() {
                    if f.loads[j][k] > 0.0 && by_load[k].outside_range(delta[k]) {
                        outside_range.push((j, race));
                    }
                }
            }
        }
        state.loads.clone_from(&f.loads);
        let cage_speed = cage_speed_of(&f.orbital_speeds, &f.loads);
        Ok(ElementOutput {
            reaction: f.reaction,
            stiffness: f.stiffness,
            damping: f.damping,
            loads: f.loads,
            overloaded: overloaded(&self.bearing, &f.approaches),
            approaches: f.approaches,
            outside_range,
            speed_outside: false,
            cage_speed,
            orbital_speeds: f.orbital_speeds,
        })
    }

    fn ball_count(&self) -> usize {
        self.bearing.geometry.ball_count
    }

    fn bearing(&self) -> &Bearing {
        &self.bearing
    }
}

// ---------------------------------------------------------------------------------------------
// Trend curves as a force element
// ---------------------------------------------------------------------------------------------

/// Settings of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrendEvalOptions {
    /// Relative tolerance of a contact's load inverted from the approach trend (dimensionless).
    pub tolerance: f64,
    /// Iteration limit of that inversion (safeguarded Newton).
    pub max_iterations: usize,
    /// How the Jacobian is computed.
    pub jacobian: JacobianMode,
}

/// Jacobian of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum JacobianMode {
    /// The exact derivative of the trend laws (each contact's dQ/dδ = 1/(∂δ_trend/∂Q) inside
    /// the validity range), through the balls' equilibria: free.
    Exact,
    /// Central differences of the reactions (10 more evaluations) with steps `step_m` (m) for
    /// x, y, z and `step_rad` (rad) for θy, θz: a check of [`JacobianMode::Exact`].
    CentralDifference {
        /// Step of the translations, m.
        step_m: f64,
        /// Step of the tilts, rad.
        step_rad: f64,
    },
}

impl Default for TrendEvalOptions {
    fn default() -> Self {
        TrendEvalOptions {
            tolerance: 1e-12,
            max_iterations: 100,
            jacobian: JacobianMode::Exact,
        }
    }
}

/// Result of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrendForce {
    /// Reactions on the inner ring (N, N·m) and their Jacobian (N/m, N, N·m/rad).
    pub force: ForceResult,
    /// Contact loads [inner, outer] per ball, N.
    pub contact_loads: Vec<[f64; 2]>,
    /// Evaluations of the bearing (1, or 11 with central differences).
    pub iterations: usize,
    /// Whether every contact's load inversion met its tolerance.
    pub converged: bool,
    /// Largest relative residual of the contact-load inversions (dimensionless).
    pub load_change: f64,
    /// Whether any contact load or the speed lies outside the trend curves' validity range
    /// (laws are then those at the nearest end of the range).
    pub outside_validity: bool,
    /// The contacts outside the load range: (ball, race).
    pub contacts_outside: Vec<(usize, Race)>,
    /// Whether the speed lies outside the speed range of either raceway.
    pub speed_outside: bool,
}

/// The bearing as a force element with contact laws from trend curves: no EHL run.
///
/// Each contact's law depends on the contact's own load (K(Q), d(Q), ΔF(Q, n)). The element
/// evaluates it as the load whose approach trend δ(Q, n) equals the contact's approach
/// ([`crate::trends::RaceLaw`]): one bearing evaluation per call, no fixed point over the loads, and the
/// exact Jacobian. Contacts whose load falls outside the trends' load range, and speeds outside
/// their speed range, are flagged and use the laws at the nearest end.
#[derive(Debug, Clone)]
pub struct TrendForceElement {
    model: TrendModel,
    bearing: Bearing,
    races: [Arc<RaceTrends>; 2],
    /// Evaluation settings.
    pub options: TrendEvalOptions,
    last_speed_laws: SpeedLawMemo,
}

/// The raceway laws at the last speed a [`TrendForceElement`] was asked for. A clone starts
/// empty (a memo, not a result).
#[derive(Debug, Default)]
struct SpeedLawMemo(std::sync::Mutex<Option<(SpeedLawKey, Arc<SpeedLaws>)>>);

/// What the laws at a speed are made from: speed (rad/s), inversion tolerance, iteration limit.
type SpeedLawKey = (f64, f64, usize);

impl Clone for SpeedLawMemo {
    fn clone(&self) -> Self {
        SpeedLawMemo::default()
    }
}

impl TrendForceElement {
    /// A force element from a trend model. Errors if the model's bearing is invalid or its
    /// approach trend does not increase with the load over the validity range (it could not be
    /// inverted).
    pub fn new(model: TrendModel) -> Result<Self, CharacterizeError> {
        let bearing = model.bearing_model()?;
        model.check_invertible()?;
        let races = [Arc::new(model.inner.clone()), Arc::new(model.outer.clone())];
        Ok(TrendForceElement {
            model,
            bearing,
            races,
            options: TrendEvalOptions::default(),
            last_speed_laws: SpeedLawMemo::default(),
        })
    }

    /// A force element from trend JSON ([`TrendModel::to_json`]).
    pub fn from_json(text: &str) -> Result<Self, CharacterizeError> {
        Self::new(TrendModel::from_json(text)?)
    }

    /// The trend model.
    pub fn model(&self) -> &TrendModel {
        &self.model
    }

    /// The fitted law of a contact on `race` at load `load` (N) and speed `n` (rad/s), and
    /// whether the load was clamped into the validity range: [`TrendModel::law_at`].
    pub fn law_at(
        &self,
        race: Race,
        load: f64,
        n: f64,
    ) -> Result<(FittedLaw, bool), CharacterizeError> {
        Ok(self.model.law_at(race, load, n)?)
    }

    /// The raceway laws at relative speed `n` (rad/s): those of the last speed asked for when
    /// `n` is that speed, else made anew and remembered. They are a function of the element
    /// and `n` alone (about 40 µs to make, as much as the rest of a warm call), so the element
    /// remembers them rather than each caller's [`ElementState`]; a call that finds the memo
    /// busy (another thread) makes its own.
    fn speed_laws_memo(&self, n: f64) -> Result<Arc<SpeedLaws>, CharacterizeError> {
        // The options are public: a memo made with other inversion settings is not reused.
        let key = (n, self.options.tolerance, self.options.max_iterations);
        if let Ok(memo) = self.last_speed_laws.0.try_lock() {
            if let Some((_, laws)) = memo.as_ref().filter(|(k, _)| *k == key) {
                return Ok(laws.clone());
            }
        }
        let laws = Arc::new(self.speed_laws(n)?);
        if let Ok(mut memo) = self.last_speed_laws.0.try_lock() {
            *memo = Some((key, laws.clone()));
        }
        Ok(laws)
    }

    /// The raceway laws at relative speed `n` (rad/s, clamped into the speed range).
    fn speed_laws(&self, n: f64) -> Result<SpeedLaws, CharacterizeError> {
        Ok(SpeedLaws::new(
            &self.model,
            &self.races,
            n,
            self.options.tolerance,
            self.options.max_iterations,
        )?)
    }

    /// Reactions and Jacobian at ring displacement `displacement` (x, y, z in m; θy, θz in rad)
    /// and ring speeds (rad/s), with the flags of the validity range. Cold start; a rotor model
    /// calls [`ForceElement::evaluate`] with a state instead.
    pub fn evaluate(
        &self,
        displacement: &[f64; 5],
        inner_speed: f64,
        outer_speed: f64,
    ) -> Result<TrendForce, crate::Error> {
        let input = ElementInput::at(*displacement, inner_speed, outer_speed);
        let mut state = ElementState::default();
        let (out, residual) = self.evaluate_state(&input, &mut state)?;
        let mut jacobian = out.stiffness;
        let mut iterations = 1;
        if let JacobianMode::CentralDifference { step_m, step_rad } = self.options.jacobian {
            for k in 0..5 {
                let h = if k < 3 { step_m } else { step_rad };
                let mut plus = input;
                let mut minus = input;
                plus.displacement[k] += h;
                minus.displacement[k] -= h;
                let fp = self.evaluate_state(&plus, &mut state.clone())?.0.reaction;
                let fm = self.evaluate_state(&minus, &mut state.clone())?.0.reaction;
                for (row, (p, m)) in jacobian.iter_mut().zip(fp.iter().zip(&fm)) {
                    row[k] = (p - m) / (2.0 * h);
                }
                iterations += 2;
            }
        }
        Ok(TrendForce {
            force: ForceResult {
                reaction: out.reaction,
                jacobian,
            },
            contact_loads: out.loads.clone(),
            iterations,
            converged: residual <= self.options.tolerance,
            load_change: residual,
            outside_validity: !out.outside_range.is_empty() || out.speed_outside,
            contacts_outside: out.outside_range,
            speed_outside: out.speed_outside,
        })
    }

    /// One evaluation and the largest relative residual of its load inversions.
    fn evaluate_state(
        &self,
        input: &ElementInput,
        state: &mut ElementState,
    ) -> Result<(ElementOutput, f64), crate::Error> {
        let n = (input.inner_speed - input.outer_speed).abs();
        if !n.is_finite() {
            return Err(BearingError::invalid(
                "inner_speed − outer_speed",
                n,
                "finite ring speeds in rad/s",
            )
            .into());
        }
        let laws_at_speed = self.speed_laws_memo(n)?;
        let races = laws_at_speed.races();
        let z = self.bearing.geometry.ball_count;
        let mut inner: Vec<Arc<dyn ContactLaw>> = Vec::with_capacity(z);
        let mut outer: Vec<Arc<dyn ContactLaw>> = Vec::with_capacity(z);
        for j in 0..z {
            let hint = |k: usize| state.loads.get(j).map_or(f64::NAN, |l| l[k]);
            inner.push(Arc::new(races[0].with_hint(hint(0))));
            outer.push(Arc::new(races[1].with_hint(hint(1))));
        }
        let laws = ContactLaws { inner, outer };
        prepare(
            state,
            &self.bearing,
            &laws,
            (self.model.race_control, Kinematics::default()),
            input,
        )?;
        let f = solve(state, input)?;
        let mut outside_range = Vec::new();
        let mut residual = 0.0_f64;
        for (j, (loads, delta)) in f.loads.iter().zip(&f.approaches).enumerate() {
            for (k, race) in [Race::Inner, Race::Outer].into_iter().enumerate() {
                let l = &races[k];
                if l.outside_load_range(loads[k]) {
                    outside_range.push((j, race));
                }
                // The inverted load's approach against the contact's: the inversion residual.
                if let Some(r) = l.inversion_residual(loads[k], delta[k]) {
                    residual = residual.max(r);
                }
            }
        }
        let speed_outside = self.races.iter().any(|t| {
            let [lo, hi] = t.speed_range_rad_s;
            !(n >= lo * (1.0 - 1e-12) && n <= hi * (1.0 + 1e-12))
        });
        state.loads.clone_from(&f.loads);
        let cage_speed = cage_speed_of(&f.orbital_speeds, &f.loads);
        Ok((
            ElementOutput {
                reaction: f.reaction,
                stiffness: f.stiffness,
                damping: f.damping,
                loads: f.loads,
                overloaded: overloaded(&self.bearing, &f.approaches),
                approaches: f.approaches,
                outside_range,
                speed_outside,
                cage_speed,
                orbital_speeds: f.orbital_speeds,
            },
            residual,
        ))
    }
}

impl ForceElement for TrendForceElement {
    fn evaluate(
        &self,
        input: &ElementInput,
        state: &mut ElementState,
    ) -> Result<ElementOutput, crate::Error> {
        Ok(self.evaluate_state(input, state)?.0)
    }

    fn ball_count(&self) -> usize {
        self.bearing.geometry.ball_count
    }

    fn bearing(&self) -> &Bearing {
        &self.bearing
    }
}

// ---------------------------------------------------------------------------------------------
// Laws by load: each ball takes the characterized law of the load it carries
// ---------------------------------------------------------------------------------------------

/// The contact law of one raceway in which every contact takes, wherever it is, the law of the
/// load it carries, interpolated over a characterization's per-contact laws (one speed).
///
/// A characterization fits one law Q = K·δ^d + ΔF (+ c·δ̇) per contact at the load w_k that
/// contact carries in the case. Each law gives a knot (w_k, δ_k = law_k⁻¹(w_k)) with the law's
/// own compliance dδ/dQ = 1/law_k′(δ_k) there. Where the knots' approaches do not grow with the
/// load (contacts at other contact angles or speeds carry nearly the same load at a different
/// approach: the 218 at 15000 rpm under combined load), adjacent knots are pooled into their mean
/// load, approach, damping and compliance until they do (pool-adjacent-violators, the isotonic
/// regression of δ over Q; [`LoadInterpolatedLaw::pooled_knots`] counts the knots merged).
/// Between the knots the approach is the monotone cubic Hermite interpolant δ(Q) through the
/// knots with these slopes (Fritsch–Carlson limited if a pair of slopes would let it turn back;
/// [`LoadInterpolatedLaw::limited_knots`]), and a contact at approach δ carries the load Q(δ) that
/// solves δ(Q) = δ, with dQ/dδ = 1/δ′(Q): at each unpooled knot the force and stiffness of that
/// contact's own fitted law, in between a smooth blend. Below the lowest knot the lowest-load law
/// applies as fitted (with its extension towards separation), above the highest the highest-load
/// law, each shifted in approach to pass through its end knot if that knot was pooled: the force
/// is continuous there and so is its slope unless that end knot was limited. The damping
/// coefficient c is interpolated linearly in the load between the knots (the end laws' own c,
/// fading below their fitted range, outside).
#[derive(Debug, Clone)]
pub struct LoadInterpolatedLaw {
    loads: Vec<f64>,
    approaches: Vec<f64>,
    slopes: Vec<f64>,
    damping: Vec<f64>,
    low: FittedLaw,
    high: FittedLaw,
    /// Approach offsets of the end laws: the law below the first knot is low(δ − shift[0]).
    shift: [f64; 2],
    limited: usize,
    pooled: usize,
}

/// A knot of [`LoadInterpolatedLaw`] while pooling: sums over its members.
struct Pool {
    n: f64,
    load: f64,
    approach: f64,
    damping: f64,
    members: Vec<FittedLaw>,
}

impl LoadInterpolatedLaw {
    /// The law from `(characterization load w in N, fitted law)` pairs of one raceway. Loads
    /// that are not finite and positive are skipped (a floored or unloaded contact adds nothing);
    /// of knots closer than 1e-9 relative in load the first is kept (mirror-image contacts).
    /// Errors when no knot is left or when a law does not reach its own load or has no positive
    /// stiffness there (naming the load).
    pub fn new(points: &[(f64, FittedLaw)]) -> Result<Self, crate::Error> {
        let mut pts: Vec<(f64, FittedLaw)> = points
            .iter()
            .copied()
            .filter(|(w, _)| w.is_finite() && *w > 0.0)
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts.dedup_by(|b, a| b.0 - a.0 <= 1e-9 * b.0);
        let (Some(&(_, low)), Some(&(_, high))) = (pts.first(), pts.last()) else {
            return Err(BearingError::NoLawLoad.into());
        };
        // Compliance dδ/dQ of `law` at load `w`, and its approach there.
        let compliance = |law: &FittedLaw, w: f64| -> Result<(f64, f64), crate::Error> {
            let delta = law
                .approach_at(w)
                .ok_or(BearingError::LawLoadUnreached { load_n: w })?;
            let stiffness = law.force(delta).1;
            if !(stiffness.is_finite() && stiffness > 0.0) {
                return Err(BearingError::LawStiffness {
                    stiffness_n_m: stiffness,
                    load_n: w,
                }
                .into());
            }
            Ok((delta, 1.0 / stiffness))
        };
        // Pool adjacent violators until the approaches grow with the load.
        let mut pools: Vec<Pool> = Vec::with_capacity(pts.len());
        for (w, law) in &pts {
            let (delta, _) = compliance(law, *w)?;
            pools.push(Pool {
                n: 1.0,
                load: *w,
                approach: delta,
                damping: law.c().unwrap_or(0.0),
                members: vec![*law],
            });
            while pools.len() >= 2 {
                let m = pools.len();
                let (a, b) = (&pools[m - 2], &pools[m - 1]);
                if b.approach / b.n > a.approach / a.n {
                    break;
                }
                let b = pools.pop().expect("two pools");
                let a = pools.last_mut().expect("two pools");
                a.n += b.n;
                a.load += b.load;
                a.approach += b.approach;
                a.damping += b.damping;
                a.members.extend(b.members);
            }
        }
        let pooled = pts.len() - pools.len();
        let mut loads = Vec::with_capacity(pools.len());
        let mut approaches = Vec::with_capacity(pools.len());
        let mut slopes = Vec::with_capacity(pools.len());
        let mut damping = Vec::with_capacity(pools.len());
        for p in &pools {
            let w = p.load / p.n;
            let mut slope = 0.0;
            for law in &p.members {
                slope += compliance(law, w)?.1;
            }
            loads.push(w);
            approaches.push(p.approach / p.n);
            slopes.push(slope / p.members.len() as f64);
            damping.push(p.damping / p.n);
        }
        // The end laws pass through the end knots with their own slopes there.
        let last = loads.len() - 1;
        let (d_low, s_low) = compliance(&low, loads[0])?;
        let (d_high, s_high) = compliance(&high, loads[last])?;
        let shift = [approaches[0] - d_low, approaches[last] - d_high];
        slopes[0] = s_low;
        slopes[last] = s_high;
        // Fritsch–Carlson: a cubic Hermite piece is monotone if (m_k/Δ)² + (m_k+1/Δ)² ≤ 9.
        let mut limited = vec![false; loads.len()];
        for k in 0..last {
            let secant = (approaches[k + 1] - approaches[k]) / (loads[k + 1] - loads[k]);
            let (a, b) = (slopes[k] / secant, slopes[k + 1] / secant);
            let r2 = a * a + b * b;
            if r2 > 9.0 {
                let tau = 3.0 / r2.sqrt();
                slopes[k] = tau * a * secant;
                slopes[k + 1] = tau * b * secant;
                limited[k] = true;
                limited[k + 1] = true;
            }
        }
        Ok(LoadInterpolatedLaw {
            loads,
            approaches,
            slopes,
            damping,
            low,
            high,
            shift,
            limited: limited.iter().filter(|l| **l).count(),
            pooled,
        })
    }

    /// Knots merged into their neighbours because their approaches did not grow with the load
    /// (0: every knot is its own contact's law).
    pub fn pooled_knots(&self) -> usize {
        self.pooled
    }

    /// The knots' load range [w_min, w_max], N.
    pub fn load_range(&self) -> [f64; 2] {
        [self.loads[0], self.loads[self.loads.len() - 1]]
    }

    /// Number of knots.
    pub fn knots(&self) -> usize {
        self.loads.len()
    }

    /// Knots whose slope the monotonicity limit changed (0: every knot has its own law's
    /// stiffness).
    pub fn limited_knots(&self) -> usize {
        self.limited
    }

    /// Whether a contact at approach `approach` (m) lies outside the fitted range of the law that
    /// applies there: below the lowest or above the highest knot, that end law's fitted range
    /// (between the knots, inside).
    pub fn outside_range(&self, approach: f64) -> bool {
        if approach < self.approaches[0] {
            self.low.outside_fit_range(approach - self.shift[0])
        } else if approach > self.approaches[self.approaches.len() - 1] {
            self.high.outside_fit_range(approach - self.shift[1])
        } else {
            approach.is_nan()
        }
    }

    /// The Hermite piece k at load q: (δ, dδ/dQ).
    fn piece(&self, k: usize, q: f64) -> (f64, f64) {
        let h = self.loads[k + 1] - self.loads[k];
        let t = (q - self.loads[k]) / h;
        let (t2, t3) = (t * t, t * t * t);
        let (y0, y1) = (self.approaches[k], self.approaches[k + 1]);
        let (m0, m1) = (self.slopes[k] * h, self.slopes[k + 1] * h);
        let v = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
            + (t3 - 2.0 * t2 + t) * m0
            + (-2.0 * t3 + 3.0 * t2) * y1
            + (t3 - t2) * m1;
        let dv = (6.0 * t2 - 6.0 * t) * y0
            + (3.0 * t2 - 4.0 * t + 1.0) * m0
            + (-6.0 * t2 + 6.0 * t) * y1
            + (3.0 * t2 - 2.0 * t) * m1;
        (v, dv / h)
    }

    /// Load and dQ/dδ at an approach strictly between the first and the last knot: the root of
    /// the monotone piece by Newton safeguarded with bisection (to 1e-14 of the piece's load
    /// span).
    fn load_between(&self, approach: f64) -> (f64, f64) {
        let k = self
            .approaches
            .partition_point(|d| *d <= approach)
            .clamp(1, self.approaches.len() - 1)
            - 1;
        let (mut a, mut b) = (self.loads[k], self.loads[k + 1]);
        let span = b - a;
        let (d0, d1) = (self.approaches[k], self.approaches[k + 1]);
        let mut q = a + span * (approach - d0) / (d1 - d0);
        let mut slope = 0.0;
        for _ in 0..100 {
            let (v, dv) = self.piece(k, q);
            slope = dv;
            let f = v - approach;
            if f > 0.0 {
                b = q;
            } else {
                a = q;
            }
            if f == 0.0 || b - a <= 1e-14 * span {
                break;
            }
            let newton = q - f / dv;
            let next = if dv > 0.0 && newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - q).abs() <= 1e-14 * span {
                q = next;
                slope = self.piece(k, q).1;
                break;
            }
            q = next;
        }
        let dq = if slope > 0.0 { 1.0 / slope } else { 0.0 };
        (q, dq)
    }
}

impl ContactLaw for LoadInterpolatedLaw {
    fn force(&self, approach: f64) -> (f64, f64) {
        let n = self.approaches.len();
        if n == 1 || approach <= self.approaches[0] {
            self.low.force(approach - self.shift[0])
        } else if approach >= self.approaches[n - 1] {
            self.high.force(approach - self.shift[1])
        } else {
            self.load_between(approach)
        }
    }

    fn approach_at(&self, load: f64) -> Option<f64> {
        if !(load.is_finite() && load > 0.0) {
            return None;
        }
        let n = self.loads.len();
        if n == 1 || load <= self.loads[0] {
            self.low.approach_at(load).map(|d| d + self.shift[0])
        } else if load >= self.loads[n - 1] {
            self.high.approach_at(load).map(|d| d + self.shift[1])
        } else {
            let k = self.loads.partition_point(|w| *w <= load).clamp(1, n - 1) - 1;
            Some(self.piece(k, load).0)
        }
    }

    fn damping(&self, approach: f64) -> f64 {
        let n = self.approaches.len();
        if n == 1 || approach <= self.approaches[0] {
            self.low.damping(approach - self.shift[0])
        } else if approach >= self.approaches[n - 1] {
            self.high.damping(approach - self.shift[1])
        } else {
            let q = self.load_between(approach).0;
            let k = self.loads.partition_point(|w| *w <= q).clamp(1, n - 1) - 1;
            let t = ((q - self.loads[k]) / (self.loads[k + 1] - self.loads[k])).clamp(0.0, 1.0);
            self.damping[k] + t * (self.damping[k + 1] - self.damping[k])
        }
    }
}
