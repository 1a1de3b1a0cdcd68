// ---------------------------------------------------------------------------------------------
// Force element
// ---------------------------------------------------------------------------------------------

/// Settings of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrendEvalOptions {
    /// Fixed point on the contact loads converged when their largest relative change is below
    /// this (dimensionless).
    pub tolerance: f64,
    /// Iteration limit of the fixed point.
    pub max_iterations: usize,
    /// How the Jacobian is computed.
    pub jacobian: JacobianMode,
}

/// Jacobian of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum JacobianMode {
    /// Exact derivative of the final laws with their parameters frozen (free; omits
    /// ∂(K, d, ΔF)/∂Q: measured 5 % off the total derivative on a strongly load-dependent
    /// synthetic d(Q), see `docs/study.md`). Enough for the Newton iterations of an implicit
    /// integrator.
    Frozen,
    /// Central differences of the full evaluation (10 more evaluations) with steps `step_m` (m)
    /// for x, y, z and `step_rad` (rad) for θy, θz: the total derivative.
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
            tolerance: 1e-8,
            max_iterations: 50,
            jacobian: JacobianMode::Frozen,
        }
    }
}

/// Result of [`TrendForceElement::evaluate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrendForce {
    /// Reactions on the inner ring (N, N·m) and their Jacobian with respect to the displacements,
    /// at frozen law parameters (N/m, N, N·m/rad).
    pub force: ForceResult,
    /// Contact loads [inner, outer] per ball, N.
    pub contact_loads: Vec<[f64; 2]>,
    /// Fixed-point iterations used.
    pub iterations: usize,
    /// Whether the fixed point on the contact loads converged.
    pub converged: bool,
    /// Last largest relative load change of the fixed point.
    pub load_change: f64,
    /// Whether any contact load or the speed lies outside the trend curves' validity range
    /// (parameters are then evaluated at the nearest end of the range).
    pub outside_validity: bool,
    /// The contacts outside the load range: (ball, race).
    pub contacts_outside: Vec<(usize, Race)>,
    /// Whether the speed lies outside the speed range of either raceway.
    pub speed_outside: bool,
}

/// The bearing as a force element with contact laws from trend curves: no EHL run.
///
/// The law of each contact depends on the contact's own load (K(Q), d(Q), ΔF(Q, n)), which
/// depends on the laws. [`TrendForceElement::evaluate`] resolves this implicit dependence by a
/// fixed point on the contact loads: start from the dry Hertz loads at the given displacement,
/// build each contact's law from the trends at its current load (clamped into the validity
/// range), solve every ball's equilibrium at the imposed ring displacement, and repeat until the
/// loads change by less than `options.tolerance`. The Jacobian is that of the final laws with
/// their parameters frozen by default, or the total derivative by central differences
/// ([`JacobianMode`]).
#[derive(Debug, Clone)]
pub struct TrendForceElement {
    model: TrendModel,
    bearing: Bearing,
    /// Fixed-point settings.
    pub options: TrendEvalOptions,
}

impl TrendForceElement {
    /// A force element from a trend model.
    pub fn new(model: TrendModel) -> Result<Self, CharacterizeError> {
        let bearing = model.bearing_model()?;
        Ok(TrendForceElement {
            model,
            bearing,
            options: TrendEvalOptions::default(),
        })
    }

    /// A force element from trend JSON ([`TrendModel::to_json`]).
    pub fn from_json(text: &str) -> Result<Self, CharacterizeError> {
        Self::new(TrendModel::from_json(text)?)
    }

    /// Largest relative difference between the reactions F_x, F_y, F_z this element gives at a
    /// characterized point's displacement and speed and the point's own equilibrium reactions
    /// (each relative to max(|F|, 1 N)): how well the trends reproduce the characterization.
    /// `point` is a point JSON as written by [`run_point`].
    pub fn reaction_error(&self, point: &Value) -> Result<f64, crate::Error> {
        let num = |v: &Value, what: &str| {
            v.as_f64()
                .ok_or_else(|| CharacterizeError::Trend(format!("point JSON: {what} missing")))
        };
        let mut q = [0.0; 5];
        for (k, key) in ["x", "y", "z", "theta_y", "theta_z"].iter().enumerate() {
            q[k] = num(&point["displacement"][key], key)?;
        }
        let rpm = num(&point["spec"]["inner_speed_rpm"], "spec.inner_speed_rpm")?;
        let outer = num(
            &point["spec"]["operating"]["outer_speed"],
            "spec.operating.outer_speed",
        )?;
        let r = self.evaluate(&q, rpm * PI / 30.0, outer)?;
        let mut worst = 0.0_f64;
        for (k, key) in ["force_x", "force_y", "force_z"].iter().enumerate() {
            let want = num(&point["reaction"][key], key)?;
            worst = worst.max((r.force.reaction[k] - want).abs() / want.abs().max(1.0));
        }
        Ok(worst)
    }

    /// The trend model.
    pub fn model(&self) -> &TrendModel {
        &self.model
    }

    /// The law of a contact on `race` at load `load` (N) and speed `n` (rad/s): d and ΔF from
    /// their trends at the load and speed clamped into the validity range, K = (Q − ΔF)/δ(Q, n)^d
    /// so that the law passes through the approach trend (K(Q) from its own trend only if that
    /// anchor is not positive), fitted range δ at 0.8·Q and 1.2·Q (or just above ΔF). Returns the
    /// law and whether the load was clamped.
    pub fn law_at(
        &self,
        race: Race,
        load: f64,
        n: f64,
    ) -> Result<(FittedLaw, bool), CharacterizeError> {
        let t = self.model.race(race);
        let [lo, hi] = t.load_range_n;
        let qc = if load.is_nan() {
            lo
        } else {
            load.clamp(lo, hi)
        };
        let clamped = !(load >= lo && load <= hi);
        let [nlo, nhi] = t.speed_range_rad_s;
        let nc = n.clamp(nlo, nhi);
        let d = t.d.eval(qc, nc);
        let df = t.delta_f.eval(qc, nc);
        let k = t.k_at(qc, nc);
        let q_lo = (0.8 * qc).max(df + 0.05 * qc);
        let q_hi = (1.2 * qc).max(1.5 * q_lo);
        let delta = |q: f64| ((q - df) / k).powf(1.0 / d);
        let law = FittedLaw::new(k, d, df, delta(q_lo), delta(q_hi)).map_err(|e| {
            CharacterizeError::Trend(format!(
                "law from the trends at Q = {qc} N, n = {nc} rad/s ({race:?}): {e}"
            ))
        })?;
        Ok((law, clamped))
    }

    /// Reactions and Jacobian at ring displacement `displacement` (x, y, z in m; θy, θz in rad)
    /// and ring speeds (rad/s), with the flags of the validity range. See the type's
    /// documentation for how the load dependence of the laws is resolved.
    pub fn evaluate(
        &self,
        displacement: &[f64; 5],
        inner_speed: f64,
        outer_speed: f64,
    ) -> Result<TrendForce, crate::Error> {
        self.evaluate_from(displacement, inner_speed, outer_speed, None)
    }

    /// As [`TrendForceElement::evaluate`], starting the fixed point from `start_loads` (N,
    /// [inner, outer] per ball, e.g. the `contact_loads` of the previous time step) instead of the
    /// dry Hertz loads: the result is the same to the fixed-point tolerance, in fewer iterations.
    pub fn evaluate_from(
        &self,
        displacement: &[f64; 5],
        inner_speed: f64,
        outer_speed: f64,
        start_loads: Option<&[[f64; 2]]>,
    ) -> Result<TrendForce, crate::Error> {
        let op = OperatingPoint {
            inner_speed,
            outer_speed,
            dofs: displacement.map(Control::Displacement),
            race_control: self.model.race_control,
        };
        let settings = EquilibriumSettings::default();
        let n = (inner_speed - outer_speed).abs();
        let loads_of = |e: &crate::bearing::Equilibrium| -> Vec<f64> {
            e.balls
                .iter()
                .flat_map(|b| [b.inner.load, b.outer.load])
                .collect()
        };
        let z = self.bearing.geometry.ball_count;
        let mut loads = match start_loads {
            Some(l) if l.len() == z => l.iter().flatten().copied().collect(),
            Some(l) => {
                return Err(CharacterizeError::Trend(format!(
                    "start loads given for {} balls, the bearing has {z}",
                    l.len()
                ))
                .into())
            }
            None => {
                let hertz = ContactLaws::hertz(&self.bearing)?;
                loads_of(&solve_equilibrium(&self.bearing, &hertz, &op, &settings)?)
            }
        };
        let mut iterations = 0;
        let (eq, change) = loop {
            iterations += 1;
            let mut inner: Vec<Arc<dyn ContactLaw>> = Vec::new();
            let mut outer: Vec<Arc<dyn ContactLaw>> = Vec::new();
            for (i, &q) in loads.iter().enumerate() {
                let race = if i % 2 == 0 { Race::Inner } else { Race::Outer };
                let (law, _) = self.law_at(race, q, n)?;
                if i % 2 == 0 {
                    inner.push(Arc::new(law));
                } else {
                    outer.push(Arc::new(law));
                }
            }
            let laws = ContactLaws { inner, outer };
            let eq = solve_equilibrium(&self.bearing, &laws, &op, &settings)?;
            let next = loads_of(&eq);
            let change = max_relative_load_change(&loads, &next, 0.01);
            loads = next;
            if change < self.options.tolerance || iterations >= self.options.max_iterations {
                break (eq, change);
            }
        };
        // Flags at the final loads.
        let mut contacts_outside = Vec::new();
        for (i, &q) in loads.iter().enumerate() {
            let race = if i % 2 == 0 { Race::Inner } else { Race::Outer };
            let [lo, hi] = self.model.race(race).load_range_n;
            if !(q >= lo && q <= hi) {
                contacts_outside.push((i / 2, race));
            }
        }
        let speed_outside = [&self.model.inner, &self.model.outer].iter().any(|t| {
            let [lo, hi] = t.speed_range_rad_s;
            !(n >= lo * (1.0 - 1e-12) && n <= hi * (1.0 + 1e-12))
        });
        let mut jacobian = eq.stiffness;
        if let JacobianMode::CentralDifference { step_m, step_rad } = self.options.jacobian {
            let frozen = TrendForceElement {
                options: TrendEvalOptions {
                    jacobian: JacobianMode::Frozen,
                    ..self.options
                },
                ..self.clone()
            };
            for k in 0..5 {
                let h = if k < 3 { step_m } else { step_rad };
                let mut qp = *displacement;
                let mut qm = *displacement;
                qp[k] += h;
                qm[k] -= h;
                let fp = frozen
                    .evaluate(&qp, inner_speed, outer_speed)?
                    .force
                    .reaction;
                let fm = frozen
                    .evaluate(&qm, inner_speed, outer_speed)?
                    .force
                    .reaction;
                for r in 0..5 {
                    jacobian[r][k] = (fp[r] - fm[r]) / (2.0 * h);
                }
            }
        }
        Ok(TrendForce {
            force: ForceResult {
                reaction: eq.reaction,
                jacobian,
            },
            contact_loads: loads.chunks(2).map(|c| [c[0], c[1]]).collect(),
            iterations,
            converged: change < self.options.tolerance,
            load_change: change,
            outside_validity: !contacts_outside.is_empty() || speed_outside,
            contacts_outside,
            speed_outside,
        })
    }
}
