//! Steady solver driver: input validation, problem set-up, full-multigrid start, cycles to
//! convergence, load continuation, and the dimensional results.

use super::formulas::nijenbanning_central;
use super::multigrid::{Hierarchy, MgParams, Problem};
use super::{
    AttemptOutcome, CycleType, EhlAttempt, EhlContact, EhlError, EhlFields, EhlSettings,
    EhlSolution, MoesCase, StartStrategy, DISCRETIZATION_CAP, DISCRETIZATION_FLOOR,
    DISCRETIZATION_RESIDUAL_GUARD,
};
use crate::budget::Deadline;
use crate::hertz::HertzGeometry;
use crate::material::{Lubricant, ROELANDS_LN_ETA_INF, ROELANDS_P0};
use std::f64::consts::PI;
use std::time::Instant;

fn invalid(field: &'static str, value: f64, range: &'static str) -> EhlError {
    EhlError::Invalid {
        field,
        value,
        range,
    }
}

fn check_pos(field: &'static str, v: f64) -> Result<(), EhlError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(field, v, "finite and > 0"))
    }
}

fn validate_contact(c: &EhlContact) -> Result<(), EhlError> {
    check_pos("load [N]", c.load)?;
    check_pos("rx [m]", c.rx)?;
    check_pos("ry [m]", c.ry)?;
    check_pos("sum_velocity [m/s]", c.sum_velocity)?;
    check_pos("e_reduced [Pa]", c.e_reduced)?;
    check_pos("lubricant.viscosity [Pa s]", c.lubricant.viscosity)?;
    check_pos("lubricant.density [kg/m3]", c.lubricant.density)?;
    let a = c.lubricant.pressure_viscosity;
    if !(a.is_finite() && (0.0..1e-6).contains(&a)) {
        return Err(invalid(
            "lubricant.pressure_viscosity [1/Pa]",
            a,
            "finite, 0 <= alpha < 1e-6",
        ));
    }
    if c.lubricant.viscosity_model == super::ViscosityModel::Roelands
        && c.lubricant.viscosity.ln() + ROELANDS_LN_ETA_INF <= 0.0
    {
        return Err(invalid(
            "lubricant.viscosity [Pa s]",
            c.lubricant.viscosity,
            "> 6.31e-5 Pa s for the Roelands model",
        ));
    }
    let r = c.ry / c.rx;
    if !(1.0..=1000.0).contains(&r) {
        return Err(invalid("ry/rx", r, "1 <= Ry/Rx <= 1000"));
    }
    Ok(())
}

pub(crate) fn validate_settings(s: &EhlSettings) -> Result<(), EhlError> {
    let pow2 = |n: usize| n >= 2 && (n - 1).is_power_of_two();
    if !(pow2(s.grid) && (17..=1025).contains(&s.grid)) {
        return Err(invalid(
            "settings.grid",
            s.grid as f64,
            "2^k + 1, 17 to 1025",
        ));
    }
    if !(pow2(s.coarsest) && s.coarsest >= 9) {
        return Err(invalid(
            "settings.coarsest",
            s.coarsest as f64,
            "2^k + 1, >= 9 (a value above grid means a single level)",
        ));
    }
    for (f, v) in [
        ("settings.inlet", s.inlet.unwrap_or(4.5)),
        ("settings.outlet", s.outlet),
        ("settings.half_width", s.half_width.unwrap_or(2.0)),
    ] {
        if !(v.is_finite() && (1.05..=100.0).contains(&v)) {
            return Err(invalid(f, v, "1.05 to 100 semi-axes"));
        }
    }
    for (f, v) in [
        ("settings.omega_gs", s.omega_gs),
        ("settings.omega_jd", s.omega_jd),
        ("settings.h0_gain", s.h0_gain),
        ("settings.jd_threshold", s.jd_threshold),
    ] {
        if !(v.is_finite() && v > 0.0 && v <= 2.0) {
            return Err(invalid(f, v, "0 < value <= 2"));
        }
    }
    for (f, v) in [
        ("settings.tol_residual", s.tol_residual),
        ("settings.tol_force", s.tol_force),
        ("settings.tol_film", s.tol_film),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(f, v, "finite and > 0"));
        }
    }
    let f = s.discretization_fraction;
    if !(f.is_finite() && (0.0..=1.0).contains(&f)) {
        return Err(invalid(
            "settings.discretization_fraction",
            f,
            "0 (off) to 1",
        ));
    }
    if s.max_cycles == 0 || s.max_cycles > 10_000 {
        return Err(invalid(
            "settings.max_cycles",
            s.max_cycles as f64,
            "1 to 10000",
        ));
    }
    if s.coarse_sweeps == 0 || s.pre_sweeps + s.post_sweeps == 0 {
        return Err(invalid(
            "settings.coarse_sweeps / pre_sweeps + post_sweeps",
            0.0,
            ">= 1",
        ));
    }
    Ok(())
}

/// Dimensional scales of one contact.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scales {
    pub(crate) ax: f64,
    pub(crate) ay: f64,
    pub(crate) ph: f64,
    pub(crate) rx: f64,
    /// Hertz deflection, m.
    pub(crate) delta_hertz: f64,
    pub(crate) m: f64,
    pub(crate) l: f64,
    pub(crate) ratio: f64,
    /// U = η0 u_s/(E′Rx).
    pub(crate) u: f64,
}

impl Scales {
    /// h (m) from H.
    pub(crate) fn h(&self, hh: f64) -> f64 {
        hh * self.ax * self.ax / self.rx
    }
    /// Moes H from dimensionless H.
    pub(crate) fn moes(&self, hh: f64) -> f64 {
        self.h(hh) / self.rx / self.u.sqrt()
    }
}

/// Above this X extent sqrt(2H) of the rigid-isoviscous pressure (in a_x) the automatic domain
/// follows the rigid scales (only elongated contacts at M ≈ 5 in the documented range).
const RIGID_SX: f64 = 15.0;

pub(crate) fn setup(c: &EhlContact, s: &EhlSettings) -> Result<(Problem, Scales), EhlError> {
    validate_contact(c)?;
    validate_settings(s)?;
    let g = HertzGeometry::new(c.rx, c.ry, c.e_reduced)
        .map_err(|_| invalid("ry/rx", c.ry / c.rx, "1 <= Ry/Rx <= 1000"))?;
    let hz = g.contact(c.load);
    let (ax, ay, ph) = (hz.semi_minor, hz.semi_major, hz.max_pressure);
    let e = c.e_reduced;
    let eta0 = c.lubricant.viscosity;
    let u = eta0 * c.sum_velocity / (e * c.rx);
    let w = c.load / (e * c.rx * c.rx);
    let gg = c.lubricant.pressure_viscosity * e;
    let m = w * u.powf(-0.75);
    let l = gg * u.powf(0.25);
    let pr = Problem {
        lambda: 6.0 * eta0 * c.sum_velocity * c.rx * c.rx / (ax * ax * ax * ph),
        kappa2: (ax / ay).powi(2),
        gy: 0.5 * (c.rx / c.ry) * (ay / ax).powi(2),
        def_scale: 2.0 * c.rx * ph / (PI * e * ax),
        aspect: ay / ax,
        lub: c.lubricant,
        ph,
        x_min: 0.0,
        x_max: s.outlet,
        y_half: s
            .half_width
            .unwrap_or((3.5 - 0.5 * ay / ax).clamp(2.0, 3.0)),
        h0_gain_scale: 1.0,
        squeeze: 0.0,
        load_slope: 0.0,
    };
    if !(pr.lambda.is_finite() && pr.lambda > 0.0 && m.is_finite() && l.is_finite()) {
        return Err(invalid(
            "load/speed combination (M)",
            m,
            "finite Moes parameters",
        ));
    }
    let mut pr = pr;
    let sc = Scales {
        ax,
        ay,
        ph,
        rx: c.rx,
        delta_hertz: hz.deflection,
        m,
        l,
        ratio: c.ry / c.rx,
        u,
    };
    let h_est = h_estimate(&sc);
    // Elongated contacts need a long inlet at moderate load (10.5 a_x); at high load the inlet
    // zone shortens and 6 a_x suffices (log-linear in M from M = 100 to 1000); light loads get
    // a longer inlet from the film estimate.
    let elong = (3.0 + 1.5 * ay / ax).min(10.5);
    let f = (m / 100.0).log10().clamp(0.0, 1.0);
    let auto =
        (elong - (elong - 6.0).max(0.0) * f).max((1.0 + 3.5 * (2.0 * h_est).sqrt()).min(30.0));
    pr.x_min = -s.inlet.unwrap_or(auto);
    // Nearly rigid, very thick films (elongated contacts at light load, H ≫ 1): the
    // hydrodynamic pressure of the rigid-isoviscous regime spreads over X ~ sqrt(2H) and
    // Y ~ sqrt(H/gy), and its inlet tail decays slowly, so a domain on the Hertz scale (or the
    // 30 a_x inlet cap) truncates it and cannot carry the load at the right film. The domain then
    // scales with these lengths (30 and 16 of them upstream and sideways: H_c within a few
    // per cent of a domain twice as large, docs/ehl.md §5.8). The load responds only weakly to
    // H0 there (W ~ H^(-1/2)), so the H0 gain grows with H.
    let sx = (2.0 * h_est).sqrt();
    if s.inlet.is_none() && sx > RIGID_SX {
        let sy = (h_est / pr.gy).sqrt();
        pr.x_min = -(1.0 + 30.0 * sx);
        pr.x_max = pr.x_max.max(0.6 * sx);
        if s.half_width.is_none() {
            pr.y_half = pr.y_half.max(16.0 * sy);
        }
        pr.h0_gain_scale = h_est / 10.0;
    }
    Ok((pr, sc))
}

/// Smallest [`film_resolution`] at which the steady solver is known to resolve the film of a
/// contact on its grid: 10. Measured on law-map nodes (docs/ehl.md §5.9): at or above it the
/// nodal films were positive, and on 65² and 129² the thin-film nodes converged in their first
/// start in 2–10 cycles per solution (on 257², M 10000–20000 at ratio 12–27, still starts 3–6);
/// at 1.5–5 the nodal film went through zero at the outlet and every start ended in a limit
/// cycle (250–450 cycles per solution), below ≈ 1.5 the solutions converged with deeply
/// negative films; at 6.7 (129², M 10000, L 12.5) up to five starts and a fitted ΔF 5 % off the
/// 257² value. Only the mesh along x is judged.
pub const FILM_RESOLUTION_MIN: f64 = 10.0;

/// How well the grid of `s` resolves the film of contact `c`: the Nijenbanning–Venner–Moes
/// central film in the solver's units a_x²/Rx divided by ΔX², ΔX = (inlet + outlet)/(grid − 1)
/// the mesh along x in a_x, on the domain `solve_steady` would use (dimensionless). The film is
/// the difference of the gap's O(1) terms, whose discretization error is O(ΔX²): where the
/// ratio is small the discrete film goes negative (docs/ehl.md §5.9; [`FILM_RESOLUTION_MIN`]).
/// Cheap (no solve). Errors: those of the contact and settings checks.
pub fn film_resolution(c: &EhlContact, s: &EhlSettings) -> Result<f64, EhlError> {
    let (pr, sc) = setup(c, s)?;
    let dx = (pr.x_max - pr.x_min) / (s.grid - 1) as f64;
    Ok(h_estimate(&sc) / (dx * dx))
}

/// Result of the dimensionless iteration.
struct Core {
    hier: Hierarchy,
    converged: bool,
    cycles: usize,
    history: Vec<f64>,
    residual: f64,
    fb: f64,
    /// Stopped by the stagnation test (not by the cycle limit).
    stagnated: bool,
    /// See [`EhlSolution::discretization_estimate`].
    disc: Option<[f64; 2]>,
    /// See [`EhlSolution::stopped_by_discretization`].
    by_disc: bool,
}

impl Core {
    fn outcome(&self) -> AttemptOutcome {
        if self.converged {
            AttemptOutcome::Converged
        } else if self.stagnated {
            AttemptOutcome::Stagnated
        } else {
            AttemptOutcome::CycleLimit
        }
    }
}

/// Bilinear value of a nodal field at (x0, y0) on a uniform grid.
pub(crate) fn bilinear(f: &[f64], x: &[f64], y: &[f64], x0: f64, y0: f64) -> f64 {
    let nx = x.len();
    let ny = y.len();
    let hx = x[1] - x[0];
    let hy = y[1] - y[0];
    let fi = ((x0 - x[0]) / hx).clamp(0.0, (nx - 1) as f64);
    let fj = ((y0 - y[0]) / hy).clamp(0.0, (ny - 1) as f64);
    let i = (fi.floor() as usize).min(nx - 2);
    let j = (fj.floor() as usize).min(ny - 2);
    let tx = fi - i as f64;
    let ty = fj - j as f64;
    let v = |a: usize, b: usize| f[b * nx + a];
    (1.0 - tx) * (1.0 - ty) * v(i, j)
        + tx * (1.0 - ty) * v(i + 1, j)
        + (1.0 - tx) * ty * v(i, j + 1)
        + tx * ty * v(i + 1, j + 1)
}

pub(crate) fn params(s: &EhlSettings) -> MgParams {
    MgParams {
        pre: s.pre_sweeps,
        post: s.post_sweeps,
        coarse_sweeps: s.coarse_sweeps,
        gamma: match s.cycle {
            CycleType::V => 1,
            CycleType::W => 2,
        },
        omega_gs: s.omega_gs,
        omega_jd: s.omega_jd,
        h0_relax: s.h0_gain,
        jd_threshold: s.jd_threshold,
    }
}

/// Starting pressure on the finest grid: given, or Hertz.
enum Start {
    Hertz,
    /// `disc`: a discretization-error estimate carried over from a neighbouring solution (warm
    /// starts), for the stopping rule of [`EhlSettings::discretization_fraction`].
    Given {
        p: Vec<f64>,
        h0: Option<f64>,
        disc: Option<[f64; 2]>,
    },
}

/// Sets H0 so that the central film equals `h_est` for the current pressure of level `k`.
fn set_h0_from_estimate(hier: &mut Hierarchy, pr: &Problem, k: usize, h_est: f64) {
    let lv = &mut hier.levels[k];
    lv.update_film(pr, 0.0);
    let hc = bilinear(&lv.h, &lv.x, &lv.y, 0.0, 0.0);
    hier.h0 = h_est - hc;
    lv.update_film(pr, hier.h0);
}

fn hertz_fill(lv: &mut super::multigrid::Level) {
    let nx = lv.nx;
    for j in 0..lv.ny {
        for i in 0..nx {
            let r2 = lv.x[i] * lv.x[i] + lv.y[j] * lv.y[j];
            lv.p[j * nx + i] = if r2 < 1.0 { (1.0 - r2).sqrt() } else { 0.0 };
        }
    }
}

/// Central film H_c (dimensionless) of level `k`, bilinear at X = Y = 0.
fn centre_film(hier: &Hierarchy, k: usize) -> f64 {
    let lv = &hier.levels[k];
    bilinear(&lv.h, &lv.x, &lv.y, 0.0, 0.0)
}

/// What the discretization-error estimate of an iteration is measured against: (H_c, H0) on
/// the next coarser grid at the end of the full-multigrid start, or an estimate carried over
/// from a neighbouring solution (warm starts).
struct DiscretizationReference {
    coarse: Option<(f64, f64)>,
    prior: Option<[f64; 2]>,
}

impl DiscretizationReference {
    /// Relative discretization errors of (H_c, H0) for the finest grid's `hc` and `h0`: from the
    /// coarser grid's values, |X − X_2h|/3 over the scales `scale` (H_c) and `s0` (H0), else the
    /// carried-over estimate, else None.
    fn estimate(&self, hc: f64, h0: f64, scale: f64, s0: f64) -> Option<[f64; 2]> {
        match (self.coarse, self.prior) {
            (Some((hc2, h02)), _) => {
                Some([(hc - hc2).abs() / scale / 3.0, (h0 - h02).abs() / s0 / 3.0])
            }
            (None, p) => p,
        }
    }
}

/// Puts the start into `hier`: for [`Start::Hertz`] a Hertzian pressure on the coarsest grid
/// with H0 from `h_est`, 4 cycles there and `s.fmg_cycles` on each finer grid below the finest
/// (full multigrid); for [`Start::Given`] the pressure and H0 (or H0 from `h_est`) on the finest
/// grid. Returns the reference of the discretization-error estimate.
fn start_hierarchy(
    hier: &mut Hierarchy,
    pr: &Problem,
    prm: &MgParams,
    s: &EhlSettings,
    start: Start,
    h_est: f64,
) -> DiscretizationReference {
    let nl = hier.levels.len();
    let top = nl - 1;
    let mut coarse = None;
    let mut prior = None;
    match start {
        Start::Hertz => {
            hertz_fill(&mut hier.levels[0]);
            set_h0_from_estimate(hier, pr, 0, h_est);
            for _ in 0..4 {
                hier.cycle(pr, prm, 0);
            }
            if top == 1 {
                coarse = Some((centre_film(hier, 0), hier.h0));
            }
            for k in 1..nl {
                hier.prolong_solution(pr, k);
                if k < top {
                    for _ in 0..s.fmg_cycles {
                        hier.cycle(pr, prm, k);
                    }
                    if k + 1 == top {
                        coarse = Some((centre_film(hier, k), hier.h0));
                    }
                }
            }
        }
        Start::Given { p, h0, disc } => {
            prior = disc;
            hier.levels[top].p.copy_from_slice(&p);
            match h0 {
                Some(h0) => {
                    hier.h0 = h0;
                    hier.levels[top].update_film(pr, h0);
                }
                None => set_h0_from_estimate(hier, pr, top, h_est),
            }
        }
    }
    DiscretizationReference { coarse, prior }
}

/// The stopping rule of [`EhlSettings::discretization_fraction`] `theta`: whether the iteration
/// error left in (H_c, H0) — the last relative changes `change` continued geometrically with the
/// observed convergence factor — and the force-balance error `fb` are below `theta` times the
/// discretization estimate `d` (clamped to [DISCRETIZATION_FLOOR, DISCRETIZATION_CAP]), with
/// the relative residual (the last of `history`) below DISCRETIZATION_RESIDUAL_GUARD. `prev` are
/// the changes of the cycle before.
fn within_discretization(
    theta: f64,
    d: [f64; 2],
    change: [f64; 2],
    prev: [f64; 2],
    history: &[f64],
    fb: f64,
) -> bool {
    // Convergence factor: the more pessimistic of the last change ratio and the
    // residual ratio (the film can oscillate from cycle to cycle while the
    // residual falls steadily).
    let n = history.len();
    let rel = history[n - 1];
    let rho_res = history[n - 1] / history[n - 2];
    let small = (0..2).all(|q| {
        let rho = if change[q] == 0.0 {
            rho_res.max(DISC_RHO_MIN)
        } else {
            (change[q] / prev[q]).max(rho_res).max(DISC_RHO_MIN)
        };
        let allowed = theta * d[q].clamp(DISCRETIZATION_FLOOR, DISCRETIZATION_CAP);
        rho < DISC_RHO_MAX && change[q] * rho / (1.0 - rho) <= allowed
    });
    let allowed_fb = theta
        * d[0]
            .max(d[1])
            .clamp(DISCRETIZATION_FLOOR, DISCRETIZATION_CAP);
    small && fb <= allowed_fb && rel < DISCRETIZATION_RESIDUAL_GUARD
}

/// Runs the multigrid iteration. `Err((cycles, lowest residual reached))` on divergence.
fn iterate(
    pr: &Problem,
    s: &EhlSettings,
    start: Start,
    h_est: f64,
    max_cycles: usize,
    deadline: Option<Deadline>,
) -> Result<Core, (usize, f64)> {
    let mut prm = params(s);
    prm.h0_relax *= pr.h0_gain_scale;
    let mut hier = Hierarchy::new(pr, s.grid, s.coarsest);
    let top = hier.levels.len() - 1;
    let reference = start_hierarchy(&mut hier, pr, &prm, s, start, h_est);
    let mut history = Vec::new();
    let mut converged = false;
    let mut residual = f64::NAN;
    let mut fb = f64::NAN;
    let mut cycles = 0;
    let mut stagnated = false;
    let mut disc = None;
    let mut by_disc = false;
    // Changes of (H_c, H0) over the previous cycle, relative.
    let mut prev_change: Option<[f64; 2]> = None;
    for _ in 0..max_cycles {
        // The wall-time budget ends the iteration like the cycle limit; the caller reports it.
        if crate::budget::expired(&deadline) {
            break;
        }
        let hc_old = centre_film(&hier, top);
        let h0_old = hier.h0;
        hier.cycle(pr, &prm, top);
        cycles += 1;
        let lv = &mut hier.levels[top];
        let (sr, sw) = lv.residual(pr);
        let rel = if sw > 0.0 { sr / sw } else { f64::INFINITY };
        fb = (lv.integral() - lv.g).abs() / lv.g;
        let hc = centre_film(&hier, top);
        let best_so_far = history.iter().cloned().fold(f64::NAN, f64::min);
        // A film a million times the estimate is a blown-up iterate (seen with Barus at
        // αp ~ 50–100), even when its relative residual is still finite.
        let absurd = hc.abs().max(hier.h0.abs()) > 1e6 * h_est.max(1.0);
        if !(rel.is_finite() && hier.h0.is_finite() && hc.is_finite()) || absurd {
            return Err((cycles, best_so_far));
        }
        residual = rel;
        history.push(rel);
        let scale = hc.abs().max(1e-12);
        let dh =
            ((hc - hc_old).abs() / scale).max((hier.h0 - h0_old).abs() / hier.h0.abs().max(scale));
        let s0 = hier.h0.abs().max(scale);
        if let Some(d) = reference.estimate(hc, hier.h0, scale, s0) {
            disc = Some(d);
            let change = [(hc - hc_old).abs() / scale, (hier.h0 - h0_old).abs() / s0];
            let theta = s.discretization_fraction;
            if let (Some(prev), true) = (prev_change, theta > 0.0) {
                if within_discretization(theta, d, change, prev, &history, fb) {
                    converged = true;
                    by_disc = true;
                }
            }
            prev_change = Some(change);
        }
        if rel < s.tol_residual && fb < s.tol_force && dh < s.tol_film {
            converged = true;
            by_disc = false;
        }
        if converged {
            break;
        }
        let best = history.iter().cloned().fold(f64::INFINITY, f64::min);
        if history.len() > 3 && rel > 100.0 * best.max(1e-6) {
            return Err((cycles, best));
        }
        // Stagnation: less than a factor 2 gained over the last 6 cycles, far from tolerance.
        let n = history.len();
        if n >= 12 && rel > 10.0 * s.tol_residual && history[n - 7] < 2.0 * rel {
            stagnated = true;
            break;
        }
    }
    Ok(Core {
        hier,
        converged,
        cycles,
        history,
        residual,
        fb,
        stagnated,
        disc,
        by_disc,
    })
}

/// Smallest convergence factor the discretization-following stopping rule assumes (the first
/// cycles after the full-multigrid start can fall much faster than the asymptotic rate).
const DISC_RHO_MIN: f64 = 0.3;
/// Observed convergence factor at and above which that rule does not stop.
const DISC_RHO_MAX: f64 = 0.9;

fn h_estimate(sc: &Scales) -> f64 {
    let hm = nijenbanning_central(sc.m, sc.l.max(1e-6), 1.0 / sc.ratio);
    let h_m = hm * sc.u.sqrt() * sc.rx; // m
    h_m * sc.rx / (sc.ax * sc.ax)
}

fn contact_with_load(c: &EhlContact, load: f64) -> EhlContact {
    EhlContact { load, ..*c }
}

fn finish(
    c: &EhlContact,
    sc: &Scales,
    core: Core,
    cycles_total: usize,
    steps: usize,
    t0: Instant,
) -> EhlSolution {
    let lv = core.hier.levels.last().expect("at least one level");
    let hc = bilinear(&lv.h, &lv.x, &lv.y, 0.0, 0.0);
    let hmin = lv.h.iter().cloned().fold(f64::INFINITY, f64::min);
    let pmax = lv.p.iter().cloned().fold(0.0, f64::max);
    let fields = EhlFields {
        x: lv.x.iter().map(|v| v * sc.ax).collect(),
        y: lv.y.iter().map(|v| v * sc.ay).collect(),
        p: lv.p.iter().map(|v| v * sc.ph).collect(),
        h: lv.h.iter().map(|v| sc.h(*v)).collect(),
        p_dimensionless: lv.p.clone(),
        h_dimensionless: lv.h.clone(),
        a_x: sc.ax,
        a_y: sc.ay,
    };
    let _ = c;
    EhlSolution {
        converged: core.converged,
        moes_m: sc.m,
        moes_l: sc.l,
        ry_over_rx: sc.ratio,
        h_central: sc.h(hc),
        h_min: sc.h(hmin),
        p_max: pmax * sc.ph,
        p_hertz: sc.ph,
        approach: -sc.h(core.hier.h0),
        approach_hertz: sc.delta_hertz,
        h_central_moes: sc.moes(hc),
        h_min_moes: sc.moes(hmin),
        force_balance_residual: core.fb,
        residual: core.residual,
        grid: [lv.nx, lv.ny],
        cycles: cycles_total,
        seconds: t0.elapsed().as_secs_f64(),
        residual_history: core.history,
        discretization_estimate: core.disc,
        stopped_by_discretization: core.by_disc,
        continuation_steps: steps,
        attempts: 1,
        attempt_log: Vec::new(),
        fields,
    }
}

/// Solves one steady contact from a Hertzian start (more conservative restarts, then load and α
/// continuation and a single-grid relaxation if the direct start diverges; docs/ehl.md §2), the
/// starts tried in the order of [`start_order`], every one recorded in
/// [`EhlSolution::attempt_log`]. A run that stops at `max_cycles` is returned with
/// `converged: false`.
pub fn solve_steady(c: &EhlContact, s: &EhlSettings) -> Result<EhlSolution, EhlError> {
    solve_steady_within(c, s, None)
}

/// [`solve_steady`] within a wall-time budget: `deadline` is checked before every multigrid
/// cycle and between the starts; when it has passed the solve ends with
/// [`EhlError::TimeLimit`] (None: no budget).
pub fn solve_steady_within(
    c: &EhlContact,
    s: &EhlSettings,
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    let t0 = Instant::now();
    let (pr, sc) = setup(c, s)?;
    let order = order_for(&pr, &sc);
    let ctx = SolveContext {
        c,
        s,
        pr: &pr,
        sc: &sc,
        t0,
        deadline,
    };
    solve_ordered(&ctx, &order, Vec::new(), 0)
}

/// [`solve_steady`] with the starts tried in the given order (for studies of the start choice;
/// `StartStrategy::Warm` entries are ignored, an empty order gives an error), within the
/// wall-time budget `deadline` (as [`solve_steady_within`]). An order without the later
/// fallbacks can fail where [`solve_steady`] succeeds.
pub fn solve_steady_starts(
    c: &EhlContact,
    s: &EhlSettings,
    order: &[StartStrategy],
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    let t0 = Instant::now();
    let (pr, sc) = setup(c, s)?;
    if order.iter().all(|x| *x == StartStrategy::Warm) {
        return Err(invalid(
            "start order (length)",
            0.0,
            "at least one cold start",
        ));
    }
    let ctx = SolveContext {
        c,
        s,
        pr: &pr,
        sc: &sc,
        t0,
        deadline,
    };
    solve_ordered(&ctx, order, Vec::new(), 0)
}

/// The order in which [`solve_steady`] tries its starts for this contact (docs/ehl.md §2):
/// the fallback ladder 1–9, or, for the contacts where start 1 is known to fail, the start
/// that converges for them first and the others after it in ladder order.
pub fn start_order(c: &EhlContact, s: &EhlSettings) -> Result<Vec<StartStrategy>, EhlError> {
    let (pr, sc) = setup(c, s)?;
    Ok(order_for(&pr, &sc))
}

/// Region where start 1 fails and start 5 (`Conservative`) converges first time: Roelands
/// viscosity, L ≥ 23 and either Ry/Rx ≥ 30 with M ≤ 1100 or 10 ≤ Ry/Rx < 30 with M ≤ 100.
/// Measured on the seed bearing's 66 contacts at 257² (`tests/ehl_seed_contacts.rs`,
/// docs/ehl.md §2): the inner contacts (Ry/Rx 60) with L = 23.9–25.3 and M = 132–1030 and the
/// outer one with L = 23.4, M = 79 stagnated in start 1 after 12–17 cycles and needed start 2,
/// 3, 4 or 5 (27–86 cycles in all, up to 39 s); start 5 alone converges for each of them in
/// 10–19 cycles. Outside the region start 1 converges in 5–11 cycles (L ≤ 22.3 at any M up to
/// 3200; the outer contacts with L = 23.4 and M ≥ 125; the inner ones with M ≥ 1190), and the
/// region's contacts where start 1 also converges (two of the inner ones, M 570 and 707) take
/// 12–13 cycles instead of 6–7. Barus cases keep the ladder order (their large-αp_h fallbacks
/// are documented in §5.8).
fn conservative_first(pr: &Problem, sc: &Scales) -> bool {
    let roelands = pr.lub.viscosity_model == super::ViscosityModel::Roelands;
    let m_max = if sc.ratio >= 30.0 {
        1100.0
    } else if sc.ratio >= 10.0 {
        100.0
    } else {
        return false;
    };
    roelands && sc.l >= 23.0 && sc.m <= m_max
}

fn order_for(pr: &Problem, sc: &Scales) -> Vec<StartStrategy> {
    if conservative_first(pr, sc) {
        let mut o = vec![StartStrategy::Conservative];
        o.extend(
            StartStrategy::LADDER
                .iter()
                .filter(|x| **x != StartStrategy::Conservative),
        );
        o
    } else {
        StartStrategy::LADDER.to_vec()
    }
}

fn record(
    log: &mut Vec<EhlAttempt>,
    strategy: StartStrategy,
    outcome: AttemptOutcome,
    cycles: usize,
    residual: f64,
    t: Instant,
) {
    log.push(EhlAttempt {
        strategy,
        outcome,
        cycles,
        residual,
        seconds: t.elapsed().as_secs_f64(),
    });
}

/// What every start of one steady solve shares: the contact and its settings, the
/// dimensionless problem and scales, the solve's start time and its wall-time budget.
#[derive(Clone, Copy)]
struct SolveContext<'a> {
    c: &'a EhlContact,
    s: &'a EhlSettings,
    pr: &'a Problem,
    sc: &'a Scales,
    /// Start of the solve (for the reported wall time).
    t0: Instant,
    deadline: Option<Deadline>,
}

impl SolveContext<'_> {
    /// [`EhlError::TimeLimit`] after `cycles` cycles in all, with the residual history of the
    /// last start that ran cycles; None without a budget.
    fn time_limit(&self, cycles: usize, history: &[f64]) -> Option<EhlError> {
        self.deadline.map(|d| EhlError::TimeLimit {
            limit_s: d.limit_seconds(),
            seconds: self.t0.elapsed().as_secs_f64(),
            cycles,
            m: self.sc.m,
            l: self.sc.l,
            ratio: self.sc.ratio,
            residual_history: history.to_vec(),
        })
    }

    /// The time-limit error if the budget has passed (see [`SolveContext::time_limit`]).
    fn expired(&self, cycles: usize, history: &[f64]) -> Option<EhlError> {
        if crate::budget::expired(&self.deadline) {
            self.time_limit(cycles, history)
        } else {
            None
        }
    }
}

/// The unconverged (finite) iterate of the α-continuation's last step with the lowest residual:
/// dimensionless pressure on the finest grid, H0, and the continuation steps so far.
struct AlphaIterate {
    p: Vec<f64>,
    h0: f64,
    steps: usize,
}

/// The starts of one solve so far: their log, the cycles spent, and what the later starts and
/// the final answer need of the ones that failed.
struct Attempts {
    log: Vec<EhlAttempt>,
    /// Cycles spent in all.
    cycles: usize,
    /// The unconverged multigrid start with the lowest residual.
    best: Option<(Core, StartStrategy)>,
    /// The load continuation's outcome, if it ran and did not converge.
    load_cont: Option<Result<EhlSolution, EhlError>>,
    /// Lowest residual at the case's α of the α-continuation and the single-grid relaxation.
    alpha_lowest: f64,
    /// The α-continuation's best iterate, for the single-grid relaxation.
    alpha_best: Option<AlphaIterate>,
    /// Residual history of the last start that ran cycles (for the time-limit error).
    last_history: Vec<f64>,
}

impl Attempts {
    /// A multigrid start `st` from a Hertzian pressure with the settings `sk` of the fallback
    /// ladder (`h_est` the film estimate): the solution if it converges, else recorded (the
    /// lowest-residual one kept).
    fn multigrid(
        &mut self,
        ctx: &SolveContext,
        st: StartStrategy,
        sk: &EhlSettings,
        h_est: f64,
    ) -> Option<EhlSolution> {
        let ta = Instant::now();
        match iterate(
            ctx.pr,
            sk,
            Start::Hertz,
            h_est,
            ctx.s.max_cycles,
            ctx.deadline,
        ) {
            Ok(core) => {
                self.cycles += core.cycles;
                if !core.history.is_empty() {
                    self.last_history.clone_from(&core.history);
                }
                record(
                    &mut self.log,
                    st,
                    core.outcome(),
                    core.cycles,
                    core.residual,
                    ta,
                );
                if core.converged {
                    let mut r = finish(ctx.c, ctx.sc, core, self.cycles, 0, ctx.t0);
                    r.attempts = st.number();
                    r.attempt_log = std::mem::take(&mut self.log);
                    return Some(r);
                }
                if self
                    .best
                    .as_ref()
                    .map_or(true, |b| core.residual < b.0.residual)
                {
                    self.best = Some((core, st));
                }
            }
            Err((n, res)) => {
                self.cycles += n;
                record(&mut self.log, st, AttemptOutcome::Diverged, n, res, ta);
            }
        }
        None
    }

    /// The load continuation `st` with the settings `sk`: the solution if it converges, else
    /// recorded and kept for the final answer.
    fn load_continuation(
        &mut self,
        ctx: &SolveContext,
        st: StartStrategy,
        sk: &EhlSettings,
    ) -> Option<EhlSolution> {
        let ta = Instant::now();
        let before = self.cycles;
        let r = continuation(ctx, sk, self.cycles);
        let (outcome, res) = match &r {
            Ok(sol) => {
                self.cycles = sol.cycles;
                if !sol.residual_history.is_empty() {
                    self.last_history.clone_from(&sol.residual_history);
                }
                let o = if sol.converged {
                    AttemptOutcome::Converged
                } else {
                    AttemptOutcome::CycleLimit
                };
                (o, sol.residual)
            }
            Err(EhlError::Diverged {
                cycles: n,
                residual,
                ..
            }) => {
                self.cycles = *n;
                (AttemptOutcome::Diverged, *residual)
            }
            Err(_) => (AttemptOutcome::Diverged, f64::NAN),
        };
        record(&mut self.log, st, outcome, self.cycles - before, res, ta);
        if let Ok(mut sol) = r {
            if sol.converged {
                sol.attempt_log = std::mem::take(&mut self.log);
                return Some(sol);
            }
            self.load_cont = Some(Ok(sol));
        } else {
            self.load_cont = Some(r);
        }
        None
    }

    /// Start `st` converged with `r` (its cycles counted from `before`, its time from `ta`): the
    /// attempt recorded, and the solution given the log of every attempt.
    fn converged(
        &mut self,
        st: StartStrategy,
        mut r: EhlSolution,
        before: usize,
        ta: Instant,
    ) -> EhlSolution {
        record(
            &mut self.log,
            st,
            AttemptOutcome::Converged,
            r.cycles - before,
            r.residual,
            ta,
        );
        r.attempt_log = std::mem::take(&mut self.log);
        r
    }

    /// The α-continuation `st` over the settings of `ladder`: the solution if it completes, else
    /// recorded, its lowest residual and best iterate kept.
    fn alpha(
        &mut self,
        ctx: &SolveContext,
        st: StartStrategy,
        ladder: &[EhlSettings; LADDER],
    ) -> Option<EhlSolution> {
        let ta = Instant::now();
        let before = self.cycles;
        match alpha_continuation(ctx, ladder, self.cycles) {
            Ok(r) => Some(self.converged(st, r, before, ta)),
            Err(AlphaFailure {
                cycles: n,
                lowest,
                best: b,
            }) => {
                self.cycles = n;
                self.alpha_lowest = self.alpha_lowest.min(lowest);
                let o = if b.is_some() {
                    AttemptOutcome::CycleLimit
                } else {
                    AttemptOutcome::Diverged
                };
                record(&mut self.log, st, o, self.cycles - before, lowest, ta);
                self.alpha_best = b;
                None
            }
        }
    }

    /// The single-grid relaxation `st` (settings `sk`) of the α-continuation's best iterate:
    /// the solution if it converges; skipped without such an iterate.
    fn single_grid(
        &mut self,
        ctx: &SolveContext,
        st: StartStrategy,
        sk: &EhlSettings,
    ) -> Option<EhlSolution> {
        let ta = Instant::now();
        let before = self.cycles;
        let Some(it) = self.alpha_best.take() else {
            record(&mut self.log, st, AttemptOutcome::Skipped, 0, f64::NAN, ta);
            return None;
        };
        match polish(ctx, sk, it, self.cycles) {
            Ok(r) => Some(self.converged(st, r, before, ta)),
            Err((n, res)) => {
                self.cycles = n;
                self.alpha_lowest = self.alpha_lowest.min(res);
                record(
                    &mut self.log,
                    st,
                    AttemptOutcome::CycleLimit,
                    self.cycles - before,
                    res,
                    ta,
                );
                None
            }
        }
    }

    /// The answer when no start converged: the lowest-residual multigrid start (unconverged),
    /// else the load continuation's unconverged solution, else its error or
    /// [`EhlError::Diverged`] with the lowest residual reached.
    fn into_result(self, ctx: &SolveContext) -> Result<EhlSolution, EhlError> {
        let Attempts {
            log,
            cycles,
            best,
            load_cont,
            alpha_lowest,
            ..
        } = self;
        let sc = ctx.sc;
        match best {
            Some((core, st)) => {
                let mut r = finish(ctx.c, sc, core, cycles, 0, ctx.t0);
                r.attempts = st.number();
                r.attempt_log = log;
                Ok(r)
            }
            None => match load_cont {
                Some(Ok(mut r)) => {
                    r.cycles = cycles;
                    r.attempt_log = log;
                    Ok(r)
                }
                Some(Err(EhlError::Diverged {
                    m,
                    l,
                    ratio,
                    residual,
                    ..
                })) => Err(EhlError::Diverged {
                    cycles,
                    m,
                    l,
                    ratio,
                    residual: residual.min(alpha_lowest),
                }),
                Some(Err(e)) => Err(e),
                None => Err(EhlError::Diverged {
                    cycles,
                    m: sc.m,
                    l: sc.l,
                    ratio: sc.ratio,
                    residual: alpha_lowest,
                }),
            },
        }
    }
}

/// Runs the starts of `order` until one converges. Every start is recorded in `log`; `cycles`
/// counts the cycles spent before (a failed warm start).
fn solve_ordered(
    ctx: &SolveContext,
    order: &[StartStrategy],
    log: Vec<EhlAttempt>,
    cycles: usize,
) -> Result<EhlSolution, EhlError> {
    let h_est = h_estimate(ctx.sc);
    let ladder = fallback_ladder(ctx.s);
    let mut at = Attempts {
        log,
        cycles,
        best: None,
        load_cont: None,
        alpha_lowest: f64::NAN,
        alpha_best: None,
        last_history: Vec::new(),
    };
    for &st in order {
        if let Some(e) = ctx.expired(at.cycles, &at.last_history) {
            return Err(e);
        }
        let solved = match st {
            StartStrategy::Warm => None,
            StartStrategy::Given
            | StartStrategy::SmallH0Gain
            | StartStrategy::WideJacobi
            | StartStrategy::WideJacobiSmallSteps
            | StartStrategy::Conservative
            | StartStrategy::DampedLines => at.multigrid(ctx, st, &ladder[st.number() - 1], h_est),
            StartStrategy::LoadContinuation => at.load_continuation(ctx, st, &ladder[CONSERVATIVE]),
            StartStrategy::AlphaContinuation => at.alpha(ctx, st, &ladder),
            StartStrategy::SingleGrid => at.single_grid(ctx, st, &ladder[0]),
        };
        if let Some(r) = solved {
            return Ok(r);
        }
    }
    if let Some(e) = ctx.expired(at.cycles, &at.last_history) {
        return Err(e);
    }
    at.into_result(ctx)
}

/// Smallest pressure–viscosity coefficient of the α-continuation, as a fraction of the case's.
const ALPHA_FROM: f64 = 0.25;
/// Largest step of the α-continuation (ratio of successive α). A step that diverges is halved
/// (in log α) down to `ALPHA_MIN_STEP`; one that succeeds lets the next grow by half again.
const ALPHA_STEP: f64 = 1.2;
/// See `ALPHA_STEP`.
const ALPHA_MIN_STEP: f64 = 1.002;
/// Cycles on an intermediate step of the α-continuation (the last one gets `max_cycles`).
const ALPHA_STEP_CYCLES: usize = 8;
/// Largest ω_GS of the α-continuation's warm-started steps.
const ALPHA_OMEGA_GS: f64 = 0.1;
/// Smallest coarsest grid of the α-continuation's warm-started steps.
const ALPHA_COARSEST: usize = 65;

/// An α-continuation that could not be completed: cycles spent, lowest residual reached at the
/// case's α, and the unconverged (finite) iterate of its last step with the lowest residual, if
/// any.
struct AlphaFailure {
    cycles: usize,
    lowest: f64,
    best: Option<AlphaIterate>,
}

/// Last resort after a failed α-continuation (`attempts` = 9): the lowest-residual iterate of its
/// last step, at the case's α, iterated on the finest grid alone (no coarse-grid correction),
/// with ω_GS ≤ `ALPHA_OMEGA_GS`, to the full tolerances (`max_cycles` cycles of `coarse_sweeps`
/// relaxations each). For Barus at αp_h ≈ 37 on an elongated
/// contact (Ry/Rx 100, M 2000, 257²) the pressure spike is one node wide and the multigrid
/// cycles end in a period-2 limit cycle at a relative residual of ≈ 1.2e-3 (the spike height
/// alternates by ~30 %), whatever the coarsest grid down to 65²; the single-grid relaxation
/// converges (docs/ehl.md §5.8). `s` are the settings it starts from, `cycles_total` the cycles
/// spent before. `Err((cycles, lowest residual))` if it does not.
fn polish(
    ctx: &SolveContext,
    s: &EhlSettings,
    it: AlphaIterate,
    cycles_total: usize,
) -> Result<EhlSolution, (usize, f64)> {
    let (pr, sc) = (ctx.pr, ctx.sc);
    let single = EhlSettings {
        omega_gs: s.omega_gs.min(ALPHA_OMEGA_GS),
        coarsest: s.grid,
        ..*s
    };
    let start = Start::Given {
        p: it.p,
        h0: Some(it.h0),
        disc: None,
    };
    match iterate(
        pr,
        &single,
        start,
        h_estimate(sc),
        s.max_cycles,
        ctx.deadline,
    ) {
        Ok(core) => {
            let n = cycles_total + core.cycles;
            if core.converged {
                let mut r = finish(ctx.c, sc, core, n, it.steps + 1, ctx.t0);
                r.attempts = LADDER + 3;
                Ok(r)
            } else {
                Err((n, core.residual))
            }
        }
        Err((n, res)) => Err((cycles_total + n, res)),
    }
}

/// The case with the pressure–viscosity coefficient scaled by `f` (same Hertz scales, grid and
/// domain; only L, i.e. αp_h, changes).
fn with_alpha(pr: &Problem, sc: &Scales, f: f64) -> (Problem, Scales) {
    let prk = Problem {
        lub: crate::material::Lubricant {
            pressure_viscosity: pr.lub.pressure_viscosity * f,
            ..pr.lub
        },
        ..pr.clone()
    };
    (prk, Scales { l: sc.l * f, ..*sc })
}

/// Settings of an intermediate stage of a continuation (a solution that only starts the next
/// stage): `s` with the fixed tolerances alone (`discretization_fraction` 0).
fn intermediate(s: &EhlSettings) -> EhlSettings {
    EhlSettings {
        discretization_fraction: 0.0,
        ..*s
    }
}

/// The α-continuation's progress: cycles spent, the lowest residual at the case's α and the
/// best unconverged iterate there, and the steps taken.
struct AlphaRun {
    cycles: usize,
    lowest: f64,
    best: Option<AlphaIterate>,
    /// Residual of `best`.
    best_res: f64,
    /// Continuation steps so far (the reduced-α start is the first).
    steps: usize,
}

/// Outcome of one step of the α-continuation.
enum AlphaStep {
    /// The last step (the case's α) converged.
    Solved(Box<EhlSolution>),
    /// An intermediate step ended finite: its pressure and H0 start the next one.
    Advanced(Vec<f64>, f64),
    /// The step diverged, or the last one did not converge.
    Failed,
}

impl AlphaRun {
    /// The failure to report, with what was reached.
    fn failure(self) -> AlphaFailure {
        AlphaFailure {
            cycles: self.cycles,
            lowest: self.lowest,
            best: self.best,
        }
    }

    /// The first stage: the case at α·`ALPHA_FROM` from a Hertzian start, the settings of
    /// `ladder` tried in turn until one converges; its pressure and H0, None if none does.
    fn reduced_alpha_start(
        &mut self,
        ctx: &SolveContext,
        ladder: &[EhlSettings; LADDER],
    ) -> Option<(Vec<f64>, f64)> {
        let (pr0, sc0) = with_alpha(ctx.pr, ctx.sc, ALPHA_FROM);
        let h_est0 = h_estimate(&sc0);
        for sk in ladder.iter() {
            // The reduced-α start only feeds the continuation: converged to the fixed tolerances
            // (the discretization-following rule is for solutions that are returned; stopping
            // this one at the grid's error left Barus, L 25, M 5 diverging later in the steps).
            let sk = &intermediate(sk);
            match iterate(&pr0, sk, Start::Hertz, h_est0, sk.max_cycles, ctx.deadline) {
                Ok(core) => {
                    self.cycles += core.cycles;
                    if core.converged {
                        let lv = core.hier.levels.last().expect("at least one level");
                        return Some((lv.p.clone(), core.hier.h0));
                    }
                }
                Err((n, _)) => self.cycles += n,
            }
        }
        None
    }

    /// One step of the continuation to the fraction `f` of the case's α (the last step when
    /// f = 1), warm-started from `state` (pressure, H0) with the settings `warm`.
    fn step(
        &mut self,
        ctx: &SolveContext,
        warm: &EhlSettings,
        state: &(Vec<f64>, f64),
        f: f64,
    ) -> AlphaStep {
        let last = f == 1.0;
        let (prk, sck) = with_alpha(ctx.pr, ctx.sc, f);
        let start = Start::Given {
            p: state.0.clone(),
            h0: Some(state.1),
            disc: None,
        };
        let maxc = if last {
            warm.max_cycles
        } else {
            ALPHA_STEP_CYCLES.min(warm.max_cycles)
        };
        self.steps += 1;
        match iterate(&prk, warm, start, h_estimate(&sck), maxc, ctx.deadline) {
            Ok(core) => {
                self.cycles += core.cycles;
                if last {
                    self.lowest = self.lowest.min(core.residual);
                    if core.converged {
                        let mut r = finish(ctx.c, ctx.sc, core, self.cycles, self.steps, ctx.t0);
                        r.attempts = LADDER + 2;
                        return AlphaStep::Solved(Box::new(r));
                    }
                    if core.residual < self.best_res {
                        self.best_res = core.residual;
                        let lv = core.hier.levels.last().expect("at least one level");
                        self.best = Some(AlphaIterate {
                            p: lv.p.clone(),
                            h0: core.hier.h0,
                            steps: self.steps,
                        });
                    }
                    AlphaStep::Failed
                } else {
                    let lv = core.hier.levels.last().expect("at least one level");
                    AlphaStep::Advanced(lv.p.clone(), core.hier.h0)
                }
            }
            Err((n, res)) => {
                self.cycles += n;
                if last {
                    self.lowest = self.lowest.min(res);
                }
                AlphaStep::Failed
            }
        }
    }
}

/// Continuation in the pressure–viscosity coefficient α, i.e. in L at fixed M (tried last, after
/// the starts of [`fallback_ladder`] and load continuation have failed; meant for Barus at large
/// αp_h, docs/ehl.md §5.8). The case is solved at α·`ALPHA_FROM` from a Hertzian start (the
/// starts of the ladder in turn), then α is raised geometrically to its value, each step
/// warm-started from the previous pressure and H0 on the same grid and domain, with ω_GS ≤
/// `ALPHA_OMEGA_GS` and a coarsest grid of at least `ALPHA_COARSEST` points (with larger ω_GS,
/// or the 33² coarsest grid, the warm starts diverge within 2–5 cycles at αp_max ≳ 60–90).
/// Intermediate steps get `ALPHA_STEP_CYCLES` cycles and need not converge; the last one must.
/// `cycles_total` counts the cycles spent before. [`AlphaFailure`] if it cannot be completed.
fn alpha_continuation(
    ctx: &SolveContext,
    ladder: &[EhlSettings; LADDER],
    cycles_total: usize,
) -> Result<EhlSolution, AlphaFailure> {
    let mut run = AlphaRun {
        cycles: cycles_total,
        lowest: f64::NAN,
        best: None,
        best_res: f64::INFINITY,
        steps: 1,
    };
    if ctx.pr.lub.pressure_viscosity <= 0.0 {
        return Err(run.failure());
    }
    let Some(mut state) = run.reduced_alpha_start(ctx, ladder) else {
        return Err(run.failure());
    };
    let warm = EhlSettings {
        omega_gs: ladder[0].omega_gs.min(ALPHA_OMEGA_GS),
        coarsest: ladder[0].coarsest.max(ALPHA_COARSEST),
        ..ladder[0]
    };
    let mut done = ALPHA_FROM;
    let mut q = ALPHA_STEP;
    loop {
        if crate::budget::expired(&ctx.deadline) {
            return Err(run.failure());
        }
        let mut f = done * q;
        if f > 1.0 - 1e-9 {
            f = 1.0;
        }
        let ok = match run.step(ctx, &warm, &state, f) {
            AlphaStep::Solved(r) => return Ok(*r),
            AlphaStep::Advanced(p, h0) => {
                state = (p, h0);
                true
            }
            AlphaStep::Failed => false,
        };
        if ok {
            done = f;
            q = q.powf(1.5).min(ALPHA_STEP);
        } else {
            q = (f / done).sqrt();
            if q < ALPHA_MIN_STEP {
                return Err(run.failure());
            }
        }
    }
}

/// Number of settings in [`fallback_ladder`].
const LADDER: usize = 6;
/// Index in [`fallback_ladder`] of the settings used for load continuation.
const CONSERVATIVE: usize = 4;

/// The settings tried in turn when a start diverges or stagnates: as given; a smaller h0 gain;
/// a wider Jacobi-distributive zone; both with smaller distributive steps; all more conservative
/// still (`CONSERVATIVE`, also used for load continuation); and the given settings with strongly
/// under-relaxed Gauss–Seidel lines (ω_GS ≤ 0.1). The last one is for nearly isoviscous, highly
/// loaded elongated contacts (L ≈ 2, M ≳ 500, Ry/Rx ≳ 60): there the Poiseuille term dominates
/// the line diagonal in the whole Hertzian zone (Gauss–Seidel everywhere), but the elastic
/// coupling that a line solve leaves out (beyond its band, and of the other lines, whose film is
/// updated only after the sweep) is not small, and the relaxation at ω_GS = 0.3–0.4 oscillates
/// without converging even on a single grid (docs/ehl.md §5.8).
fn fallback_ladder(s: &EhlSettings) -> [EhlSettings; LADDER] {
    let a = EhlSettings {
        h0_gain: s.h0_gain * 0.4,
        ..*s
    };
    let b = EhlSettings {
        jd_threshold: s.jd_threshold.max(1.0),
        ..*s
    };
    let c = EhlSettings {
        h0_gain: s.h0_gain * 0.4,
        jd_threshold: s.jd_threshold.max(1.0),
        omega_jd: s.omega_jd.min(0.15),
        ..*s
    };
    let d = EhlSettings {
        h0_gain: s.h0_gain * 0.2,
        jd_threshold: s.jd_threshold.max(1.0),
        omega_jd: s.omega_jd.min(0.15),
        omega_gs: s.omega_gs.min(0.3),
        ..*s
    };
    let e = EhlSettings {
        omega_gs: s.omega_gs.min(0.1),
        ..*s
    };
    [*s, a, b, c, d, e]
}

/// Load continuation: solve at M_k = M_start·2^k (dimensionless pressure carried over), up to M,
/// with the settings `s`; `cycles_total` counts the cycles spent before.
fn continuation(
    ctx: &SolveContext,
    s: &EhlSettings,
    mut cycles_total: usize,
) -> Result<EhlSolution, EhlError> {
    let (c, sc, t0, deadline) = (ctx.c, ctx.sc, ctx.t0, ctx.deadline);
    let m_start = (sc.m / 2.0).min(20.0);
    let mut loads = Vec::new();
    let mut mk = m_start;
    while mk < sc.m {
        loads.push(c.load * mk / sc.m);
        mk *= 2.0;
    }
    loads.push(c.load);
    let mut p_prev: Option<Vec<f64>> = None;
    let mut last_res = f64::NAN;
    let steps = loads.len();
    for (k, &load) in loads.iter().enumerate() {
        if crate::budget::expired(&deadline) && k + 1 < steps {
            // Straight to the last step, which stops at once and returns its iterate.
            continue;
        }
        let ck = contact_with_load(c, load);
        let (pr, sck) = setup(&ck, s)?;
        let h_est = h_estimate(&sck);
        let last = k + 1 == steps;
        let start = match p_prev.take() {
            None => Start::Hertz,
            Some(p) => Start::Given {
                p,
                h0: None,
                disc: None,
            },
        };
        let maxc = if last {
            s.max_cycles
        } else {
            6.min(s.max_cycles)
        };
        let sk = if last { *s } else { intermediate(s) };
        match iterate(&pr, &sk, start, h_est, maxc, deadline) {
            Ok(core) => {
                cycles_total += core.cycles;
                last_res = core.residual;
                if last {
                    let mut r = finish(c, &sck, core, cycles_total, steps, t0);
                    r.attempts = LADDER + 1;
                    return Ok(r);
                }
                p_prev = Some(core.hier.levels.last().expect("level").p.clone());
            }
            Err((cyc, res)) => {
                cycles_total += cyc;
                let res = if res.is_finite() { res } else { last_res };
                return Err(EhlError::Diverged {
                    cycles: cycles_total,
                    m: sc.m,
                    l: sc.l,
                    ratio: sc.ratio,
                    residual: res,
                });
            }
        }
    }
    Err(EhlError::Diverged {
        cycles: cycles_total,
        m: sc.m,
        l: sc.l,
        ratio: sc.ratio,
        residual: last_res,
    })
}

/// Solves a contact starting from a previous solution (warm start): the previous dimensionless
/// pressure P = p/p_h at the same point in Hertz semi-axes (X = x/a_x, Y = y/a_y) and the
/// previous H0 = −δ·Rx/a_x², so that a Hertzian solution at another load starts exactly where it
/// ends (on the seed's quasi-static family this halves the cycles per member, 7–8 → 4–5, against
/// a start at the same physical point; BENCHMARKS.md). Useful for sweeps in
/// load or speed and for the bearing loop. Falls back to the cold starts of [`solve_steady`] if
/// the warm start does not converge (its cycles are counted, and it is the first entry of
/// `attempt_log`; a converged warm start reports `attempts` = 1).
pub fn solve_steady_from(
    c: &EhlContact,
    s: &EhlSettings,
    previous: &EhlSolution,
) -> Result<EhlSolution, EhlError> {
    solve_warm(c, s, previous, None, None)
}

/// [`solve_steady_from`] within a wall-time budget (as [`solve_steady_within`]).
pub fn solve_steady_from_within(
    c: &EhlContact,
    s: &EhlSettings,
    previous: &EhlSolution,
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    solve_warm(c, s, previous, None, deadline)
}

/// Pressure of a solution at the dimensionless nodes of a new problem, at the same point in
/// Hertz semi-axes (X = x/a_x, Y = y/a_y) and with the same P = p/p_h: a load change moves a
/// Hertzian pressure to the same dimensionless field. Zero outside the solution's domain.
fn warm_pressure(pr: &Problem, n: usize, f: &EhlFields) -> Vec<f64> {
    let hx = (pr.x_max - pr.x_min) / (n - 1) as f64;
    let hy = 2.0 * pr.y_half / (n - 1) as f64;
    let xs: Vec<f64> = f.x.iter().map(|v| v / f.a_x).collect();
    let ys: Vec<f64> = f.y.iter().map(|v| v / f.a_y).collect();
    // Nodes of the same dimensionless grid land on the solution's nodes up to rounding.
    let tol = 1e-9;
    let (x0, x1) = (xs[0] - tol, xs[xs.len() - 1] + tol);
    let (y0, y1) = (ys[0] - tol, ys[ys.len() - 1] + tol);
    let mut p = vec![0.0; n * n];
    for j in 1..n - 1 {
        let y = -pr.y_half + j as f64 * hy;
        for i in 1..n - 1 {
            let x = pr.x_min + i as f64 * hx;
            if x > x0 && x < x1 && y > y0 && y < y1 {
                p[j * n + i] = bilinear(&f.p_dimensionless, &xs, &ys, x, y);
            }
        }
    }
    p
}

/// [`solve_steady_from`] with the start extrapolated linearly in load from two solutions of a
/// load family, each given with its load in N: `previous` (the nearer one) and `earlier`. With
/// r = (w − w_prev)/(w_prev − w_earlier), the start is P = max(0, P_prev + r·(P_prev − P_earlier))
/// in Hertz-scaled coordinates (as [`solve_steady_from`]) and H0 = H0_prev + r·(H0_prev −
/// H0_earlier), each H0 = −δ·Rx/a_x² in its own solution's scale. For |r| > 4 (or r not finite)
/// it is [`solve_steady_from`] from `previous`. Falls back to the cold starts like it.
pub fn solve_steady_extrapolated(
    c: &EhlContact,
    s: &EhlSettings,
    previous: (&EhlSolution, f64),
    earlier: (&EhlSolution, f64),
) -> Result<EhlSolution, EhlError> {
    solve_steady_extrapolated_within(c, s, previous, earlier, None)
}

/// [`solve_steady_extrapolated`] within a wall-time budget (as [`solve_steady_within`]).
pub fn solve_steady_extrapolated_within(
    c: &EhlContact,
    s: &EhlSettings,
    previous: (&EhlSolution, f64),
    earlier: (&EhlSolution, f64),
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    let (w1, w0) = (previous.1, earlier.1);
    let r = (c.load - w1) / (w1 - w0);
    if !(r.is_finite() && r.abs() <= 4.0) {
        return solve_warm(c, s, previous.0, None, deadline);
    }
    solve_warm(c, s, previous.0, Some((earlier.0, r)), deadline)
}

fn solve_warm(
    c: &EhlContact,
    s: &EhlSettings,
    previous: &EhlSolution,
    earlier: Option<(&EhlSolution, f64)>,
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    let t0 = Instant::now();
    let (pr, sc) = setup(c, s)?;
    let valid = |f: &EhlFields| {
        f.x.len() >= 2
            && f.y.len() >= 2
            && f.p.len() == f.x.len() * f.y.len()
            && f.p_dimensionless.len() == f.p.len()
    };
    if !valid(&previous.fields) {
        return solve_steady_within(c, s, deadline);
    }
    let earlier = earlier.filter(|(e, _)| valid(&e.fields));
    let n = s.grid;
    let mut p = warm_pressure(&pr, n, &previous.fields);
    // H0 = −δ·Rx/a_x²: kept from the previous solution (a Hertzian approach scales with a_x²),
    // or extrapolated from the two in their own scales.
    let h0_of = |sol: &EhlSolution| -sol.approach * sc.rx / (sol.fields.a_x * sol.fields.a_x);
    let mut h0 = h0_of(previous);
    if let Some((e, r)) = earlier {
        let pe = warm_pressure(&pr, n, &e.fields);
        for (a, b) in p.iter_mut().zip(&pe) {
            *a = (*a + r * (*a - b)).max(0.0);
        }
        h0 += r * (h0 - h0_of(e));
    }
    let h_est = h_estimate(&sc);
    let ta = Instant::now();
    let mut log = Vec::new();
    // The warm start relaxes with the given settings, also where the cold starts begin with the
    // conservative ones (`conservative_first`): those are for the first cycles from a Hertzian
    // pressure, and from a neighbouring solution they only slow the convergence (the seed's light
    // inner contacts: 15–16 cycles per family member with them, 7 without; the seed study
    // 33.6 → 28.5 s, no warm start failed — BENCHMARKS.md). A warm start that fails
    // falls back to the cold starts in their order.
    let order = order_for(&pr, &sc);
    let spent = match iterate(
        &pr,
        s,
        Start::Given {
            p,
            h0: Some(h0),
            disc: previous.discretization_estimate,
        },
        h_est,
        s.max_cycles,
        deadline,
    ) {
        Ok(core) => {
            let n = core.cycles;
            record(
                &mut log,
                StartStrategy::Warm,
                core.outcome(),
                n,
                core.residual,
                ta,
            );
            if core.converged {
                let mut r = finish(c, &sc, core, n, 0, t0);
                r.attempt_log = log;
                return Ok(r);
            }
            n
        }
        Err((n, res)) => {
            record(
                &mut log,
                StartStrategy::Warm,
                AttemptOutcome::Diverged,
                n,
                res,
                ta,
            );
            n
        }
    };
    let ctx = SolveContext {
        c,
        s,
        pr: &pr,
        sc: &sc,
        t0,
        deadline,
    };
    solve_ordered(&ctx, &order, log, spent)
}

/// Largest Moes material parameter L accepted by [`solve_moes`] (dimensionless).
pub const MOES_L_MAX: f64 = 100.0;

/// Solves a dimensionless case. The dimensional contact behind it: E′ = 2.2e11 Pa, Rx = 10 mm,
/// Ry = Rx·ratio, α = alpha_p0/p0, η0 = exp(ln_eta0_ratio − 9.67), ρ0 = 870 kg/m³; U, W and the
/// load follow from M and L. The dimensionless results depend only on (M, L, Ry/Rx, α p0,
/// ln η0 + 9.67), the dimensional ones refer to that contact.
pub fn solve_moes(c: &MoesCase, s: &EhlSettings) -> Result<EhlSolution, EhlError> {
    solve_moes_within(c, s, None)
}

/// [`solve_moes`] within a wall-time budget (as [`solve_steady_within`]).
pub fn solve_moes_within(
    c: &MoesCase,
    s: &EhlSettings,
    deadline: Option<Deadline>,
) -> Result<EhlSolution, EhlError> {
    check_pos("M", c.m)?;
    if !(c.l.is_finite() && c.l > 0.0 && c.l <= MOES_L_MAX) {
        return Err(invalid(
            "L",
            c.l,
            "0 < L ≤ 100 (L = G·U^(1/4) of oil-lubricated rolling contacts lies between about 1 \
             and 40; far above, the case describes no real contact)",
        ));
    }
    if !(c.ry_over_rx.is_finite() && (1.0..=1000.0).contains(&c.ry_over_rx)) {
        return Err(invalid("ry_over_rx", c.ry_over_rx, "1 <= Ry/Rx <= 1000"));
    }
    check_pos("alpha_p0", c.alpha_p0)?;
    check_pos("ln_eta0_ratio", c.ln_eta0_ratio)?;
    let e = 2.2e11;
    let rx = 0.01;
    let alpha = c.alpha_p0 / ROELANDS_P0;
    let eta0 = (c.ln_eta0_ratio - ROELANDS_LN_ETA_INF).exp();
    let g = alpha * e;
    let u = (c.l / g).powi(4);
    let w = c.m * u.powf(0.75);
    let contact = EhlContact {
        load: w * e * rx * rx,
        rx,
        ry: rx * c.ry_over_rx,
        sum_velocity: u * e * rx / eta0,
        e_reduced: e,
        lubricant: Lubricant {
            viscosity: eta0,
            pressure_viscosity: alpha,
            density: 870.0,
            viscosity_model: c.viscosity,
            density_model: c.density,
        },
    };
    solve_steady_within(&contact, s, deadline)
}
