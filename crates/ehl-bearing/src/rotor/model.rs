//! The rotor model: matrices, bearing sites, unbalances; static equilibrium and linearization.

use super::RotorError;
use crate::force_element::{ElementInput, ElementOutput, ElementState, ForceElement};
use nalgebra::{DMatrix, DVector};
use std::fmt;
use std::sync::Arc;

/// The linear rotor without its bearings: n×n matrices, row-major, SI (kg, N·s/m, N/m and
/// their rotational counterparts). The gyroscopic matrix is per unit shaft speed: the damping
/// at speed Ω is C + Ω·G (ROSS's `rotor.C(Ω) + Ω·rotor.G()`).
#[derive(Debug, Clone, PartialEq)]
pub struct RotorMatrices {
    /// Number of DOFs n.
    pub dofs: usize,
    /// Mass M (n×n, row-major).
    pub mass: Vec<f64>,
    /// Damping C (n×n).
    pub damping: Vec<f64>,
    /// Gyroscopic G per unit speed (n×n), s·(N·s/m)/rad → multiplied by Ω in rad/s.
    pub gyroscopic: Vec<f64>,
    /// Stiffness K (n×n).
    pub stiffness: Vec<f64>,
}

impl RotorMatrices {
    /// Checks sizes (n² entries each) and finiteness, naming the matrix and the entry.
    pub fn new(
        dofs: usize,
        mass: Vec<f64>,
        damping: Vec<f64>,
        gyroscopic: Vec<f64>,
        stiffness: Vec<f64>,
    ) -> Result<Self, RotorError> {
        let m = RotorMatrices {
            dofs,
            mass,
            damping,
            gyroscopic,
            stiffness,
        };
        m.validate()?;
        Ok(m)
    }

    fn validate(&self) -> Result<(), RotorError> {
        let n = self.dofs;
        if n == 0 {
            return Err(RotorError::NoDofs);
        }
        for (name, m) in [
            ("mass", &self.mass),
            ("damping", &self.damping),
            ("gyroscopic", &self.gyroscopic),
            ("stiffness", &self.stiffness),
        ] {
            if m.len() != n * n {
                return Err(RotorError::MatrixSize {
                    name,
                    entries: m.len(),
                    n,
                });
            }
            if let Some(i) = m.iter().position(|v| !v.is_finite()) {
                return Err(RotorError::MatrixEntry {
                    name,
                    row: i / n,
                    col: i % n,
                    value: m[i],
                });
            }
        }
        Ok(())
    }

    pub(crate) fn matrix(&self, entries: &[f64]) -> DMatrix<f64> {
        DMatrix::from_row_slice(self.dofs, self.dofs, entries)
    }
}

/// A bearing between a rotor node and the ground.
#[derive(Clone)]
pub struct BearingSite {
    /// The bearing's force element (dry Hertz, fitted laws, or trends).
    pub element: Arc<dyn ForceElement>,
    /// Rotor DOF index carrying the bearing's x (axial), y, z (radial), θy, θz (tilts); `None`:
    /// that bearing DOF is held at its offset (e.g. a rotor model without axial DOFs).
    pub dofs: [Option<usize>; 5],
    /// Sign of each mapping (±1): bearing DOF = offset + sign · rotor DOF. A bearing mounted the
    /// other way round along the shaft is the mirror image x → −x, which maps θy → −θy and
    /// θz → −θz and keeps its speed: [`BearingSite::mirrored`].
    pub signs: [f64; 5],
    /// Bearing displacement when the mapped rotor DOFs are zero (m, m, m, rad, rad), e.g. the
    /// approach of a mounted preload.
    pub offset: [f64; 5],
}

impl fmt::Debug for BearingSite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BearingSite")
            .field("balls", &self.element.ball_count())
            .field("dofs", &self.dofs)
            .field("signs", &self.signs)
            .field("offset", &self.offset)
            .finish()
    }
}

impl BearingSite {
    /// A bearing on rotor DOFs `dofs` (x axial, y, z, θy, θz), signs +1, no offset.
    pub fn new(element: Arc<dyn ForceElement>, dofs: [Option<usize>; 5]) -> Self {
        BearingSite {
            element,
            dofs,
            signs: [1.0; 5],
            offset: [0.0; 5],
        }
    }

    /// The same bearing mounted the other way round along the shaft (signs −1 on x, θy, θz).
    pub fn mirrored(mut self) -> Self {
        for k in [0, 3, 4] {
            self.signs[k] = -self.signs[k];
        }
        self
    }

    /// The same bearing with displacement `offset` at zero rotor DOFs (m, m, m, rad, rad).
    pub fn with_offset(mut self, offset: [f64; 5]) -> Self {
        self.offset = offset;
        self
    }

    /// Bearing displacement at rotor displacement `q`.
    pub(crate) fn displacement(&self, q: &DVector<f64>) -> [f64; 5] {
        let mut y = self.offset;
        for ((y, dof), sign) in y.iter_mut().zip(&self.dofs).zip(&self.signs) {
            if let Some(i) = *dof {
                *y += sign * q[i];
            }
        }
        y
    }

    /// Bearing rates at rotor rates `v` (unmapped DOFs at rest).
    pub(crate) fn rate(&self, v: &DVector<f64>) -> [f64; 5] {
        let mut y = [0.0; 5];
        for ((y, dof), sign) in y.iter_mut().zip(&self.dofs).zip(&self.signs) {
            if let Some(i) = *dof {
                *y = sign * v[i];
            }
        }
        y
    }
}

/// A rotating unbalance at a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unbalance {
    /// The node's two lateral DOFs (ROSS x, y — the bearing's y, z); the shaft turns from the
    /// first toward the second.
    pub dofs: [usize; 2],
    /// Unbalance m·e, kg·m.
    pub mass_eccentricity_kg_m: f64,
    /// Phase at rotation angle 0, rad.
    pub phase_rad: f64,
}

impl Unbalance {
    /// Force (N) on the two DOFs at rotation angle `angle` (rad), speed Ω (rad/s) and angular
    /// acceleration Ω̇ (rad/s²): m·e·[Ω²·(cos φ, sin φ) + Ω̇·(−sin φ, cos φ)], φ = angle + phase.
    pub fn force(&self, angle: f64, speed: f64, acceleration: f64) -> [f64; 2] {
        let (s, c) = (angle + self.phase_rad).sin_cos();
        let me = self.mass_eccentricity_kg_m;
        [
            me * (speed * speed * c - acceleration * s),
            me * (speed * speed * s + acceleration * c),
        ]
    }
}

/// The static equilibrium of the rotor on its bearings (its record:
/// `report::RotorStaticReport`).
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct StaticSolution {
    /// Rotor displacements q (n), SI.
    pub displacement: Vec<f64>,
    /// Per bearing: its displacement (x, y, z, θy, θz), m and rad.
    pub bearing_displacement: Vec<[f64; 5]>,
    /// Per bearing: its reaction (load on the inner ring), N and N·m.
    pub reactions: Vec<[f64; 5]>,
    /// Per bearing: its stiffness ∂R/∂q, bearing axes.
    pub bearing_stiffness: Vec<[[f64; 5]; 5]>,
    /// Per bearing: its damping ∂R/∂q̇, bearing axes.
    pub bearing_damping: Vec<[[f64; 5]; 5]>,
    /// Newton iterations.
    pub iterations: usize,
    /// Largest force residual at the end, N (or N·m).
    pub residual_n: f64,
}

/// Why a static equilibrium failed: the direction the constant load pushes the rotor along at
/// the last Newton iterate ([`RotorError::StaticNotConverged`]).
#[derive(Debug, Clone, PartialEq)]
pub struct StaticDiagnosis {
    /// Number of bearings.
    pub bearings: usize,
    /// Directions nothing holds at the last iterate: eigenvalues of the tangent stiffness
    /// (against the mass) at round-off, below 1e-12 of the largest (torsion included).
    pub free_directions: usize,
    /// Whether the load pushes the rotor mostly along such a free direction.
    pub pushed_along_free_direction: bool,
    /// Natural frequency of that direction on the bearings at the last iterate, Hz (0 if free).
    pub frequency_hz: f64,
    /// Its share of the load's static compliance, 0–1.
    pub load_share: f64,
    /// The rotor DOFs that move most in it (largest first, those above a tenth of the largest).
    pub dofs: Vec<usize>,
}

impl fmt::Display for StaticDiagnosis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.pushed_along_free_direction {
            write!(
                f,
                "the rotor on its {} bearing(s) has {} free direction(s) (rigid-body motions no \
                 bearing holds, torsion included) and the constant load pushes it along one \
                 (mostly rotor DOFs {:?}): no static equilibrium exists. The bearings must hold \
                 the rotor in every direction a load pushes it: a shaft needs bearings at two \
                 nodes (or one that carries the moment), and angular-contact bearings an opposed \
                 partner and a preload axially",
                self.bearings, self.free_directions, self.dofs
            )
        } else {
            write!(
                f,
                "at the last iterate {:.0} % of the constant load's static compliance goes into \
                 a mode of {:.3} Hz (mostly rotor DOFs {:?}) that the {} bearing(s) barely hold: \
                 they do not hold the rotor firmly in that direction. Check the bearings' nodes \
                 and mounting, and their preload offsets (an unloaded ball bearing has no \
                 stiffness; a shaft on one bearing pivots about it)",
                100.0 * self.load_share,
                self.frequency_hz,
                self.dofs,
                self.bearings
            )
        }
    }
}

/// A rotor with bearings, unbalances and constant loads.
#[derive(Debug, Clone)]
pub struct RotorModel {
    pub(crate) matrices: RotorMatrices,
    pub(crate) mass: DMatrix<f64>,
    pub(crate) damping: DMatrix<f64>,
    pub(crate) gyroscopic: DMatrix<f64>,
    pub(crate) stiffness: DMatrix<f64>,
    pub(crate) bearings: Vec<BearingSite>,
    pub(crate) unbalances: Vec<Unbalance>,
    pub(crate) constant_force: DVector<f64>,
}

/// Newton budget and tolerance of the static equilibrium.
const STATIC_MAX_ITERATIONS: usize = 100;
const STATIC_RELATIVE_TOLERANCE: f64 = 1e-10;

impl RotorModel {
    /// A rotor model. `constant_force` (n, N and N·m) holds gravity and other constant loads.
    /// Every DOF index is checked against n, every sign must be ±1, offsets and unbalances
    /// finite; errors name the bearing or unbalance, the field and the value.
    pub fn new(
        matrices: RotorMatrices,
        bearings: Vec<BearingSite>,
        unbalances: Vec<Unbalance>,
        constant_force: Vec<f64>,
    ) -> Result<Self, RotorError> {
        matrices.validate()?;
        let n = matrices.dofs;
        for (b, site) in bearings.iter().enumerate() {
            for k in 0..5 {
                if let Some(i) = site.dofs[k] {
                    if i >= n {
                        return Err(RotorError::SiteDof {
                            bearing: b,
                            k,
                            dof: i,
                            n,
                        });
                    }
                }
                if site.signs[k].abs() != 1.0 {
                    return Err(RotorError::SiteSign {
                        bearing: b,
                        k,
                        value: site.signs[k],
                    });
                }
                if !site.offset[k].is_finite() {
                    return Err(RotorError::SiteOffset {
                        bearing: b,
                        k,
                        value: site.offset[k],
                    });
                }
            }
            let mut used: Vec<usize> = site.dofs.iter().flatten().copied().collect();
            used.sort_unstable();
            if used.windows(2).any(|w| w[0] == w[1]) {
                return Err(RotorError::SiteDofsRepeated {
                    bearing: b,
                    dofs: site.dofs,
                });
            }
        }
        for (u, ub) in unbalances.iter().enumerate() {
            for &i in &ub.dofs {
                if i >= n {
                    return Err(RotorError::UnbalanceDof {
                        unbalance: u,
                        dof: i,
                        n,
                    });
                }
            }
            if ub.dofs[0] == ub.dofs[1] {
                return Err(RotorError::UnbalanceSameDofs {
                    unbalance: u,
                    dofs: ub.dofs,
                });
            }
            if !ub.mass_eccentricity_kg_m.is_finite() || !ub.phase_rad.is_finite() {
                return Err(RotorError::UnbalanceNotFinite {
                    unbalance: u,
                    mass_eccentricity_kg_m: ub.mass_eccentricity_kg_m,
                    phase_rad: ub.phase_rad,
                });
            }
        }
        check_vector("constant_force", &constant_force, n, " (N or N·m)")?;
        Ok(RotorModel {
            mass: matrices.matrix(&matrices.mass),
            damping: matrices.matrix(&matrices.damping),
            gyroscopic: matrices.matrix(&matrices.gyroscopic),
            stiffness: matrices.matrix(&matrices.stiffness),
            matrices,
            bearings,
            unbalances,
            constant_force: DVector::from_vec(constant_force),
        })
    }

    /// Number of rotor DOFs n.
    pub fn dofs(&self) -> usize {
        self.matrices.dofs
    }

    /// The rotor's matrices (without bearings).
    pub fn matrices(&self) -> &RotorMatrices {
        &self.matrices
    }

    /// The bearing sites.
    pub fn bearings(&self) -> &[BearingSite] {
        &self.bearings
    }

    /// Evaluate bearing `b` at rotor state (q, v) (rotor DOFs), shaft speed Ω (rad/s) and cage
    /// angle (rad); `time_s` is for the error.
    pub(crate) fn evaluate_bearing(
        &self,
        b: usize,
        (q, v): (&DVector<f64>, &DVector<f64>),
        (speed, cage_angle): (f64, f64),
        state: &mut ElementState,
        time_s: f64,
    ) -> Result<ElementOutput, RotorError> {
        let site = &self.bearings[b];
        let input = ElementInput {
            displacement: site.displacement(q),
            velocity: site.rate(v),
            inner_speed: speed,
            outer_speed: 0.0,
            cage_angle,
        };
        site.element
            .evaluate(&input, state)
            .map_err(|e| RotorError::Element {
                bearing: b,
                time_s,
                source: Box::new(e),
            })
    }

    /// Add Lᵀ·R of bearing `b` to `rhs`.
    pub(crate) fn scatter_force(&self, b: usize, reaction: &[f64; 5], rhs: &mut DVector<f64>) {
        let site = &self.bearings[b];
        for ((r, dof), sign) in reaction.iter().zip(&site.dofs).zip(&site.signs) {
            if let Some(i) = *dof {
                rhs[i] += sign * r;
            }
        }
    }

    /// Add Lᵀ·B·L of a bearing matrix B (bearing axes) to `m`.
    pub(crate) fn scatter_matrix(&self, b: usize, block: &[[f64; 5]; 5], m: &mut DMatrix<f64>) {
        let site = &self.bearings[b];
        for ((row, dr), sr) in block.iter().zip(&site.dofs).zip(&site.signs) {
            let Some(i) = *dr else { continue };
            for ((entry, dc), sc) in row.iter().zip(&site.dofs).zip(&site.signs) {
                let Some(j) = *dc else { continue };
                m[(i, j)] += sr * sc * entry;
            }
        }
    }

    /// Static equilibrium K·q + Σ Lᵀ·R(L·q + o) = f_const at shaft speed `speed_rad_s` (cage
    /// angle 0, no unbalance), by Newton's method with a backtracking line search from q = 0.
    /// Rigid-body DOFs that no bearing holds and no load drives (e.g. torsion) stay at zero:
    /// the Newton matrix carries a tiny mass-proportional shift that keeps it invertible, and
    /// convergence is judged on the unshifted residual.
    pub fn static_equilibrium(&self, speed_rad_s: f64) -> Result<StaticSolution, RotorError> {
        check_speed(speed_rad_s)?;
        let n = self.dofs();
        let mut states = vec![ElementState::default(); self.bearings.len()];
        let mut q = DVector::zeros(n);
        let (mut residual, mut outs) = self.static_residual(&q, speed_rad_s, &mut states)?;
        let scale = self.static_force_scale(&outs);
        let mut history = Vec::new();
        let kdiag = (0..n)
            .map(|i| self.stiffness[(i, i)].abs())
            .fold(0.0, f64::max);
        let mdiag = (0..n).map(|i| self.mass[(i, i)].abs()).fold(0.0, f64::max);
        for iteration in 0..=STATIC_MAX_ITERATIONS {
            let r_max = residual.amax();
            history.push(r_max);
            if r_max <= STATIC_RELATIVE_TOLERANCE * scale {
                return Ok(StaticSolution {
                    displacement: q.iter().copied().collect(),
                    bearing_displacement: self
                        .bearings
                        .iter()
                        .map(|s| s.displacement(&q))
                        .collect(),
                    reactions: outs.iter().map(|o| o.reaction).collect(),
                    bearing_stiffness: outs.iter().map(|o| o.stiffness).collect(),
                    bearing_damping: outs.iter().map(|o| o.damping).collect(),
                    iterations: iteration,
                    residual_n: r_max,
                });
            }
            if iteration == STATIC_MAX_ITERATIONS {
                break;
            }
            let mut jac = self.stiffness.clone();
            for (b, o) in outs.iter().enumerate() {
                self.scatter_matrix(b, &o.stiffness, &mut jac);
            }
            let kmax = kdiag.max((0..n).map(|i| jac[(i, i)].abs()).fold(0.0, f64::max));
            if mdiag > 0.0 {
                jac += &self.mass * (1e-12 * kmax / mdiag);
            }
            // A singular Newton matrix (nothing holds some direction, not even the mass shift:
            // no structural stiffness, no bearing) ends the search with the diagnosis.
            let Some(step) = jac.lu().solve(&(-&residual)) else {
                return Err(RotorError::StaticNotConverged {
                    iterations: iteration,
                    residual_history: history,
                    diagnosis: self.diagnose(&outs),
                });
            };
            // Backtracking: halve the step until the residual falls (bearings stiffen with load,
            // so a full step from q = 0 may overshoot into separation).
            let mut alpha = 1.0;
            loop {
                let trial = &q + &step * alpha;
                let mut trial_states = states.clone();
                match self.static_residual(&trial, speed_rad_s, &mut trial_states) {
                    Ok((r, o)) if r.amax() < r_max || alpha < 1e-3 => {
                        q = trial;
                        residual = r;
                        outs = o;
                        states = trial_states;
                        break;
                    }
                    Err(e) if alpha < 1e-3 => return Err(e),
                    _ => alpha *= 0.5,
                }
            }
        }
        Err(RotorError::StaticNotConverged {
            iterations: STATIC_MAX_ITERATIONS,
            residual_history: history,
            diagnosis: self.diagnose(&outs),
        })
    }

    fn static_residual(
        &self,
        q: &DVector<f64>,
        speed: f64,
        states: &mut [ElementState],
    ) -> Result<(DVector<f64>, Vec<ElementOutput>), RotorError> {
        let mut r = &self.stiffness * q - &self.constant_force;
        let mut outs = Vec::with_capacity(self.bearings.len());
        let rest = DVector::zeros(q.len());
        for (b, state) in states.iter_mut().enumerate() {
            let o = self.evaluate_bearing(b, (q, &rest), (speed, 0.0), state, 0.0)?;
            self.scatter_force(b, &o.reaction, &mut r);
            outs.push(o);
        }
        Ok((r, outs))
    }

    /// Force scale of the static residual: the largest of the loads, the reactions and 1 N.
    fn static_force_scale(&self, outs: &[ElementOutput]) -> f64 {
        let f = self.constant_force.amax();
        let r = outs
            .iter()
            .flat_map(|o| o.reaction.iter().take(3))
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        f.max(r).max(1.0)
    }

    /// Why the static equilibrium failed: at the bearing state `outs` (the last iterate), the
    /// rotor's tangent stiffness J = K + Σ Lᵀ·K_b·L (symmetric part) against its mass M. The
    /// modes φ of J·φ = λ·M·φ split the static compliance of the constant load f into shares
    /// (φᵀf)²/λ; the mode with the largest share is the direction the load pushes the rotor
    /// along. None if M is not positive definite.
    fn diagnose(&self, outs: &[ElementOutput]) -> Option<StaticDiagnosis> {
        let n = self.dofs();
        let mut jac = self.stiffness.clone();
        for (b, o) in outs.iter().enumerate() {
            self.scatter_matrix(b, &o.stiffness, &mut jac);
        }
        let sym = (&jac + jac.transpose()) * 0.5;
        let l = self.mass.clone().cholesky()?.l();
        let l_inv = l.try_inverse()?;
        let a = &l_inv * sym * l_inv.transpose();
        let eig = a.symmetric_eigen();
        let lambda_max = eig.eigenvalues.max();
        if lambda_max.is_nan() {
            return None;
        }
        // Below this an eigenvalue is round-off: a free (rigid-body) direction (all of them
        // when nothing is held at all).
        let free_below = 1e-12 * lambda_max.max(0.0);
        let is_free = |lambda: f64| lambda <= free_below;
        let modes = l_inv.transpose() * &eig.eigenvectors;
        let p: Vec<f64> = (0..n)
            .map(|i| modes.column(i).dot(&self.constant_force))
            .collect();
        let p_max = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let free = (0..n).filter(|&i| is_free(eig.eigenvalues[i])).count();
        // A free direction the load drives (beyond round-off) dominates any held one; among the
        // held ones the static compliance (φᵀf)²/λ decides.
        let loaded_free: Vec<(usize, f64)> = (0..n)
            .filter(|&i| is_free(eig.eigenvalues[i]) && p[i].abs() > 1e-6 * p_max)
            .map(|i| (i, p[i] * p[i]))
            .collect();
        let weights = if loaded_free.is_empty() {
            (0..n)
                .filter(|&i| !is_free(eig.eigenvalues[i]))
                .map(|i| (i, p[i] * p[i] / eig.eigenvalues[i]))
                .collect()
        } else {
            loaded_free
        };
        let total: f64 = weights.iter().map(|w| w.1).sum();
        let best = weights
            .iter()
            .copied()
            .fold((0usize, -1.0_f64), |b, c| if c.1 > b.1 { c } else { b });
        let (i, share) = best;
        let phi = modes.column(i);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| phi[b].abs().total_cmp(&phi[a].abs()));
        let peak = phi[order[0]].abs();
        let dofs = order
            .into_iter()
            .take(4)
            .filter(|&k| phi[k].abs() >= 0.1 * peak)
            .collect();
        let lambda = eig.eigenvalues[i];
        Some(StaticDiagnosis {
            bearings: self.bearings.len(),
            free_directions: free,
            pushed_along_free_direction: is_free(lambda),
            frequency_hz: lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI),
            load_share: if total > 0.0 { share / total } else { 0.0 },
            dofs,
        })
    }

    /// The rotor linearized about its static equilibrium at `speed_rad_s`: K + Σ Lᵀ·K_b·L and
    /// C + Σ Lᵀ·C_b·L (bearing stiffness and damping not symmetrized), M and G unchanged; with
    /// the equilibrium it is taken at. Simulating the returned matrices (no bearings, no
    /// constant force) gives the motion about that equilibrium.
    pub fn linearized(
        &self,
        speed_rad_s: f64,
    ) -> Result<(RotorMatrices, StaticSolution), RotorError> {
        let eq = self.static_equilibrium(speed_rad_s)?;
        let mut k = self.stiffness.clone();
        let mut c = self.damping.clone();
        for b in 0..self.bearings.len() {
            self.scatter_matrix(b, &eq.bearing_stiffness[b], &mut k);
            self.scatter_matrix(b, &eq.bearing_damping[b], &mut c);
        }
        let row_major = |m: &DMatrix<f64>| m.transpose().as_slice().to_vec();
        let matrices = RotorMatrices::new(
            self.dofs(),
            self.matrices.mass.clone(),
            row_major(&c),
            self.matrices.gyroscopic.clone(),
            row_major(&k),
        )?;
        Ok((matrices, eq))
    }
}

/// A vector input of the rotor: `n` entries, all finite; the error names `name`, the entry and
/// its value (`unit`, e.g. " (N or N·m)", follows "must be finite").
pub(crate) fn check_vector(
    name: &'static str,
    v: &[f64],
    n: usize,
    unit: &'static str,
) -> Result<(), RotorError> {
    if v.len() != n {
        return Err(RotorError::VectorSize {
            name,
            entries: v.len(),
            n,
        });
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(RotorError::VectorEntry {
            name,
            index: i,
            value: v[i],
            unit,
        });
    }
    Ok(())
}

pub(crate) fn check_speed(speed_rad_s: f64) -> Result<(), RotorError> {
    if !speed_rad_s.is_finite() || speed_rad_s < 0.0 {
        return Err(RotorError::Range {
            field: "shaft speed",
            value: speed_rad_s,
            unit: " rad/s",
            expected: "finite and ≥ 0",
        });
    }
    Ok(())
}
