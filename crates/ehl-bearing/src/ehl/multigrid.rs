//! Dimensionless steady EHL problem and its FAS multigrid solver (Venner & Lubrecht 2000).
//!
//! Coordinates: X = x/a_x (rolling direction, a_x the Hertz semi-axis along x), Y = y/a_y,
//! P = p/p_h, H = h·R_x/a_x². Reynolds:
//! ∂/∂X(ε ∂P/∂X) + κ²·∂/∂Y(ε ∂P/∂Y) − ∂(ρ̄H)/∂X = 0, ε = ρ̄H³/(η̄λ̄), κ = a_x/a_y,
//! λ̄ = 6·η0·u_s·R_x²/(a_x³·p_h); film H = H0 + X²/2 + g_y·Y² + c·∬P/r̃, with r̃ measured in units
//! of a_x; force balance ∬P dX dY = 2π/3.
//!
//! Discretization: second-order central differences for the Poiseuille terms (ε at half points
//! by averaging), second-order upwind for the wedge term (first-order upwind on the first interior
//! line), piecewise-constant pressure cells for the deformation (DC-FFT on every level).
//! Relaxation: line relaxation along X, Gauss–Seidel where the Poiseuille term dominates and
//! Jacobi-distributive (change δ at a point, −δ/4 at its four neighbours) where the wedge term
//! dominates; the line systems include the deformation coupling of the line's own points
//! (banded). Cavitation by projection P ≥ 0. H0 is updated on the coarsest grid from the force
//! balance (FAS right-hand side included).

use super::deformation::Deformation;
use crate::material::Lubricant;

/// Half bandwidth of the line systems.
const BAND: usize = 2;
/// Largest number of re-solves of a line's active set after the first projected solve.
const ACTIVE_SET_PASSES: usize = 4;
/// Largest |dx| of the local kernel table.
const KX: usize = 2 * BAND + 3;

/// The dimensionless problem.
#[derive(Debug, Clone)]
pub(crate) struct Problem {
    /// λ̄ = 6η0·u_s·Rx²/(a_x³·p_h).
    pub lambda: f64,
    /// κ² = (a_x/a_y)².
    pub kappa2: f64,
    /// Coefficient of Y² in H: (Rx/Ry)(a_y/a_x)²/2.
    pub gy: f64,
    /// Deformation factor c = 2·Rx·p_h/(π·E′·a_x).
    pub def_scale: f64,
    /// a_y/a_x.
    pub aspect: f64,
    /// Lubricant (rheology), evaluated at p = p_h·P.
    pub lub: Lubricant,
    /// Hertz pressure, Pa.
    pub ph: f64,
    /// Domain: X in [x_min, x_max], Y in [−y_half, y_half].
    pub x_min: f64,
    /// See `x_min`.
    pub x_max: f64,
    /// See `x_min`.
    pub y_half: f64,
    /// Multiplier of the H0 gain (1, or larger in the nearly rigid regime where the load
    /// responds only weakly to H0).
    pub h0_gain_scale: f64,
    /// Transient problems: coefficient β0/ΔT of the implicit squeeze term β0·ρ̄H/ΔT at the new
    /// time level (BDF2: β0 = 3/2; ΔT in units a_x/u_m); 0 for a steady problem. The known
    /// history part of ∂(ρ̄H)/∂T enters through the finest level's right-hand side.
    pub squeeze: f64,
    /// Transient problems: slope γ of the force target in H0, ∬P = g + γ·H0 (the ball's
    /// inertia under an implicit time discretization); 0 for a steady problem.
    pub load_slope: f64,
}

/// Relaxation and cycle parameters.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MgParams {
    pub pre: usize,
    pub post: usize,
    pub coarse_sweeps: usize,
    pub gamma: usize,
    pub omega_gs: f64,
    pub omega_jd: f64,
    pub h0_relax: f64,
    pub jd_threshold: f64,
}

/// One grid level.
#[derive(Debug, Clone)]
pub(crate) struct Level {
    pub nx: usize,
    pub ny: usize,
    pub hx: f64,
    pub hy: f64,
    /// 1/hx and 1/hx², 1/hy² (the relaxation and the operator multiply instead of dividing).
    ihx: f64,
    ihx2: f64,
    ihy2: f64,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub p: Vec<f64>,
    pub h: Vec<f64>,
    f: Vec<f64>,
    eps: Vec<f64>,
    rho: Vec<f64>,
    w: Vec<f64>,
    delta: Vec<f64>,
    pbar: Vec<f64>,
    /// Force-balance target ∬P (FAS-corrected on coarse levels).
    pub g: f64,
    def: Deformation,
    /// Scaled kernel K(|dx|, |dy|) for |dx| ≤ KX, |dy| ≤ 1.
    kloc: [[f64; KX + 1]; 2],
    // line buffers
    band: Vec<f64>,
    rhs: Vec<f64>,
    jd: Vec<bool>,
}

impl Level {
    pub fn new(n: usize, pr: &Problem) -> Level {
        let (nx, ny) = (n, n);
        let hx = (pr.x_max - pr.x_min) / (nx - 1) as f64;
        let hy = 2.0 * pr.y_half / (ny - 1) as f64;
        let x: Vec<f64> = (0..nx).map(|i| pr.x_min + i as f64 * hx).collect();
        let y: Vec<f64> = (0..ny).map(|j| -pr.y_half + j as f64 * hy).collect();
        let def = Deformation::new(nx, ny, hx, hy * pr.aspect, pr.def_scale);
        let mut kloc = [[0.0; KX + 1]; 2];
        for (dy, row) in kloc.iter_mut().enumerate() {
            for (dx, k) in row.iter_mut().enumerate() {
                *k = def.coefficient(dx as isize, dy as isize);
            }
        }
        let nn = nx * ny;
        Level {
            nx,
            ny,
            hx,
            hy,
            ihx: 1.0 / hx,
            ihx2: 1.0 / (hx * hx),
            ihy2: 1.0 / (hy * hy),
            x,
            y,
            p: vec![0.0; nn],
            h: vec![0.0; nn],
            f: vec![0.0; nn],
            eps: vec![0.0; nn],
            rho: vec![1.0; nn],
            w: vec![0.0; nn],
            delta: vec![0.0; nn],
            pbar: vec![0.0; nn],
            g: 2.0 * std::f64::consts::PI / 3.0,
            def,
            kloc,
            band: vec![0.0; nx * (2 * BAND + 1)],
            rhs: vec![0.0; nx],
            jd: vec![false; nx],
        }
    }

    fn k(&self, dx: isize, dy: isize) -> f64 {
        let ax = dx.unsigned_abs();
        let ay = dy.unsigned_abs();
        if ax <= KX && ay <= 1 {
            self.kloc[ay][ax]
        } else {
            0.0
        }
    }

    /// Sets the right-hand side of the discrete Reynolds equation (finest level of a transient
    /// problem: the history part of the squeeze term). Zero for a steady problem.
    pub fn set_source(&mut self, f: &[f64]) {
        self.f.copy_from_slice(f);
    }

    /// ρ̄·H at every node (for the time history of a transient problem).
    pub fn rho_h(&self) -> Vec<f64> {
        self.rho.iter().zip(&self.h).map(|(r, h)| r * h).collect()
    }

    /// ∬P dX dY (trapezoid; boundary values are zero).
    pub fn integral(&self) -> f64 {
        self.p.iter().sum::<f64>() * self.hx * self.hy
    }

    /// Recomputes H, ρ̄ and ε from P and H0.
    pub fn update_film(&mut self, pr: &Problem, h0: f64) {
        self.def.apply(&self.p, &mut self.w);
        let rheo = super::rheology::table(&pr.lub, pr.ph);
        let nx = self.nx;
        for j in 0..self.ny {
            let yy = pr.gy * self.y[j] * self.y[j];
            for i in 0..nx {
                let idx = j * nx + i;
                let hh = h0 + 0.5 * self.x[i] * self.x[i] + yy + self.w[idx];
                self.h[idx] = hh;
                let p = self.p[idx];
                // ρ̄(0) = η̄(0) = 1 exactly in every model: skip the pow/exp of the rheology
                // at the (many) unloaded and cavitated nodes.
                let (r, eta) = if p > 0.0 { rheo.at(p) } else { (1.0, 1.0) };
                self.rho[idx] = r;
                let hp = hh.max(0.0);
                self.eps[idx] = r * hp * hp * hp / (eta * pr.lambda);
            }
        }
    }

    /// Wedge weights for row i.
    fn wedge_w(i: usize) -> [f64; 3] {
        if i >= 2 {
            [1.5, -2.0, 0.5]
        } else {
            [1.0, -1.0, 0.0]
        }
    }

    /// Σ_t w_t·ρ̄H over the upwind nodes of row i at `idx` (weights [`Level::wedge_w`]): the
    /// wedge term before its 1/ΔX.
    #[inline]
    fn wedge_flux(&self, i: usize, idx: usize) -> f64 {
        let w = Self::wedge_w(i);
        let mut wedge = 0.0;
        for (t, wt) in w.iter().enumerate() {
            if *wt != 0.0 {
                let k = idx - t;
                wedge += wt * self.rho[k] * self.h[k];
            }
        }
        wedge
    }

    /// Discrete operator L(P) at interior (i, j), and the wedge-term magnitude.
    fn op(&self, pr: &Problem, i: usize, j: usize) -> (f64, f64) {
        let nx = self.nx;
        let idx = j * nx + i;
        let e = &self.eps;
        let p = &self.p;
        let ew = 0.5 * (e[idx] + e[idx - 1]);
        let ee = 0.5 * (e[idx] + e[idx + 1]);
        let es = 0.5 * (e[idx] + e[idx - nx]);
        let en = 0.5 * (e[idx] + e[idx + nx]);
        let pc = p[idx];
        let poi = (ew * (p[idx - 1] - pc) + ee * (p[idx + 1] - pc)) * self.ihx2
            + pr.kappa2 * (es * (p[idx - nx] - pc) + en * (p[idx + nx] - pc)) * self.ihy2;
        let wedge = self.wedge_flux(i, idx) * self.ihx;
        let squeeze = pr.squeeze * self.rho[idx] * self.h[idx];
        (poi - wedge - squeeze, wedge.abs())
    }

    /// Residual field f − L(P) (zero on the boundary and where P ≤ 0), written to `self.delta`;
    /// returns (Σ|r_c|, Σ|wedge|) over the non-cavitated interior, r_c the complementarity
    /// residual (|r|, limited to P·|diagonal| where the step would make P negative).
    pub fn residual(&mut self, pr: &Problem) -> (f64, f64) {
        let (nx, ny) = (self.nx, self.ny);
        let mut sr = 0.0;
        let mut sw = 0.0;
        let mut r = std::mem::take(&mut self.delta);
        r.iter_mut().for_each(|v| *v = 0.0);
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                let idx = j * nx + i;
                if self.p[idx] > 0.0 {
                    let (l, w) = self.op(pr, i, j);
                    let v = self.f[idx] - l;
                    r[idx] = v;
                    // Complementarity (projected) residual: a point that wants to fall below
                    // zero counts only the change that reaches P = 0 (P·|diagonal|).
                    let e = &self.eps;
                    let d = 0.5 * (2.0 * e[idx] + e[idx - 1] + e[idx + 1]) / (self.hx * self.hx)
                        + 0.5 * pr.kappa2 * (2.0 * e[idx] + e[idx - nx] + e[idx + nx])
                            / (self.hy * self.hy)
                        + (1.5 / self.hx + pr.squeeze) * self.rho[idx] * self.kloc[0][0];
                    let c = if v > 0.0 { v.min(self.p[idx] * d) } else { -v };
                    sr += c;
                    sw += w;
                } else {
                    // A node held at P = 0 whose equation asks for a positive pressure (r < 0:
                    // the change would be positive) violates the complementarity: it counts
                    // with |r|. Without this term, solutions with nodes wrongly held at zero
                    // near the outlet's side lobes passed as converged, and the solution
                    // depended on the relaxation's path (docs/ehl.md §2, "Projection").
                    let (l, _) = self.op(pr, i, j);
                    let v = self.f[idx] - l;
                    if v < 0.0 {
                        sr -= v;
                    }
                }
            }
        }
        self.delta = r;
        (sr, sw)
    }

    /// One relaxation sweep (line relaxation along X, lines ordered in Y), then film update.
    pub fn relax(&mut self, pr: &Problem, prm: &MgParams, h0: f64) {
        self.relax_lines(pr, prm);
        self.update_film(pr, h0);
    }

    /// The sweep of [`Level::relax`] without the film update: P changes, H, ρ̄ and ε are those of
    /// before the sweep (for the coarsest grid, which updates H0 from ∬P and then the film).
    pub fn relax_lines(&mut self, pr: &Problem, prm: &MgParams) {
        let ny = self.ny;
        let mut delta = std::mem::take(&mut self.delta);
        delta.iter_mut().for_each(|v| *v = 0.0);
        let mut ls = self.line_scratch(prm);
        let mut any_jd = false;
        for j in 1..ny - 1 {
            self.line_coefficients(pr, prm, j, &mut ls);
            self.line_band(pr, j, &mut ls);
            if !self.solve_line(j, &mut ls) {
                continue;
            }
            any_jd |= self.apply_line(j, &ls, &mut delta);
        }
        if any_jd {
            self.distribute(&delta, prm.omega_jd);
        }
        self.delta = delta;
        self.band = ls.band;
        self.rhs = ls.rhs;
        self.jd = ls.jd;
    }

    /// The work arrays of a sweep's line solves: the level's line buffers (taken, given back at
    /// the end of the sweep), the per-row arrays, and the kernel of a Jacobi-distributive change.
    #[inline]
    fn line_scratch(&mut self, prm: &MgParams) -> LineScratch {
        let nx = self.nx;
        let band = std::mem::take(&mut self.band);
        let rhs = std::mem::take(&mut self.rhs);
        let jd = std::mem::take(&mut self.jd);
        // Kernel of a Jacobi-distributive change along its own line (dy = 0).
        let mut kd = [0.0; KX + 1];
        for (d, v) in kd.iter_mut().enumerate().take(KX) {
            let di = d as isize;
            *v = self.k(di, 0)
                - 0.25 * (self.k(di - 1, 0) + self.k(di + 1, 0) + 2.0 * self.k(di, 1));
        }
        LineScratch {
            borig: band.clone(),
            rorig: rhs.clone(),
            band,
            rhs,
            jd,
            om: vec![prm.omega_gs; nx],
            held: vec![false; nx],
            cws: vec![[0.0; 5]; nx],
            kd,
        }
    }

    /// For each interior node of line j: the Poiseuille coefficients (into `ls.cws`), the
    /// classification Gauss–Seidel or Jacobi-distributive (`ls.jd`), the relaxation factor
    /// (`ls.om`) and the residual f − L(P) (`ls.rhs`).
    #[inline]
    fn line_coefficients(&self, pr: &Problem, prm: &MgParams, j: usize, ls: &mut LineScratch) {
        let nx = self.nx;
        let (ihx, ihx2) = (self.ihx, self.ihx2);
        let ky = pr.kappa2 * self.ihy2;
        let k0 = self.kloc[0][0];
        for i in 1..nx - 1 {
            let idx = j * nx + i;
            let e = &self.eps;
            let ew = 0.5 * (e[idx] + e[idx - 1]);
            let ee = 0.5 * (e[idx] + e[idx + 1]);
            let es = 0.5 * (e[idx] + e[idx - nx]);
            let en = 0.5 * (e[idx] + e[idx + nx]);
            let cw = [
                -(ew + ee) * ihx2 - ky * (es + en),
                ew * ihx2,
                ee * ihx2,
                ky * es,
                ky * en,
            ];
            ls.cws[i] = cw;
            let ap = -cw[0];
            let aw = self.rho[idx] * k0 * (ihx + pr.squeeze);
            ls.jd[i] = ap < prm.jd_threshold * aw;
            // Deep in the Poiseuille-dominated inlet the line solve is stable undamped (ω = 1);
            // damping there leaves interpolation errors of the coarse-grid correction alive.
            ls.om[i] = if ap > 1000.0 * aw { 1.0 } else { prm.omega_gs };
            // The residual f − L(P) at the node (the operator of `op`, from the same faces).
            let p = &self.p;
            let poi = cw[0] * p[idx]
                + cw[1] * p[idx - 1]
                + cw[2] * p[idx + 1]
                + cw[3] * p[idx - nx]
                + cw[4] * p[idx + nx];
            let wedge = self.wedge_flux(i, idx) * ihx;
            let squeeze = pr.squeeze * self.rho[idx] * self.h[idx];
            ls.rhs[i] = self.f[idx] - (poi - wedge - squeeze);
        }
    }

    /// The band matrix of line j's system (`ls.band`): Poiseuille terms, the wedge and squeeze
    /// terms through the deformation of the line's own points within the band, and the
    /// distribution of the Jacobi-distributive points' changes. Row r = i − 1, column offset
    /// c = k − i + BAND.
    #[inline]
    fn line_band(&self, pr: &Problem, j: usize, ls: &mut LineScratch) {
        let nx = self.nx;
        let ihx = self.ihx;
        let nb = 2 * BAND + 1;
        for i in 1..nx - 1 {
            let idx = j * nx + i;
            let cw = ls.cws[i];
            let ww = Self::wedge_w(i);
            let rr = [
                (ww[0] * ihx + pr.squeeze) * self.rho[idx],
                ww[1] * self.rho[idx - 1] * ihx,
                if i >= 2 {
                    ww[2] * self.rho[idx - 2] * ihx
                } else {
                    0.0
                },
            ];
            // Poiseuille coefficient of row i for the node at offset o = −3…3 (index o + 3).
            let pz = [0.0, 0.0, cw[1], cw[0], cw[2], 0.0, 0.0];
            let row = &mut ls.band[(i - 1) * nb..i * nb];
            for (c, out) in row.iter_mut().enumerate() {
                // Column k = i + c − BAND, inside the line's interior 1…nx − 2.
                let kb = i + c;
                if kb < BAND + 1 || kb > nx - 2 + BAND {
                    *out = 0.0;
                    continue;
                }
                let k = kb - BAND;
                let d = c as isize - BAND as isize;
                // wedge: Σ_t rr_t · K(i − t − k) = Σ_t rr_t · K(d + t)
                let tab = if ls.jd[k] { &ls.kd } else { &self.kloc[0] };
                let wsum = rr[0] * tab[d.unsigned_abs()]
                    + rr[1] * tab[(d + 1).unsigned_abs()]
                    + rr[2] * tab[(d + 2).unsigned_abs()];
                let mut a = pz[c + 1] - wsum;
                if ls.jd[k] {
                    a -= 0.25 * (pz[c] + pz[c + 2]);
                    if c == BAND {
                        a -= 0.25 * (cw[3] + cw[4]);
                    }
                }
                *out = a;
            }
        }
    }

    /// Solves line j's system for the changes δ (into `ls.rhs`), projected so that no
    /// Gauss–Seidel point goes below P = 0. False when a pivot fails: the line is left as it is.
    ///
    /// The active set starts from the Gauss–Seidel points at zero pressure (the last sweep's
    /// cavitated ones): where that is already the final set the line is solved once instead of
    /// twice (unconstrained, then constrained). A line without such points is solved
    /// unconstrained first and its set taken from that solve.
    #[inline]
    fn solve_line(&self, j: usize, ls: &mut LineScratch) -> bool {
        let nx = self.nx;
        let n = nx - 2;
        ls.borig.copy_from_slice(&ls.band);
        ls.rorig.copy_from_slice(&ls.rhs);
        let mut any = false;
        for i in 1..nx - 1 {
            ls.held[i] = !ls.jd[i] && self.p[j * nx + i] <= 0.0;
            any |= ls.held[i];
        }
        if !any {
            if !solve_band(&mut ls.band, &mut ls.rhs[1..nx - 1], n) {
                return false;
            }
            for i in 1..nx - 1 {
                ls.held[i] = !ls.jd[i] && self.p[j * nx + i] + ls.om[i] * ls.rhs[i] < 0.0;
                any |= ls.held[i];
            }
        }
        !any || self.projected_solve(j, ls)
    }

    /// The projected solve of line j (an active-set iteration on the line): Gauss–Seidel points
    /// that would become negative are held at zero and the line is solved again with those rows
    /// replaced by P + ω·δ = 0; then every Gauss–Seidel row is checked against its own equation
    /// with the neighbours' new changes ([`Level::update_active_set`]) and the line solved again,
    /// until the set is stable (at most ACTIVE_SET_PASSES). Holding points on the first solve's
    /// verdict alone kept nodes next to the outlet's cavitation boundary at zero for good: the
    /// coupling with their cavitating neighbours made their unconstrained change negative, while
    /// their own equation asked for a positive pressure (docs/ehl.md §2, "Projection"). False
    /// when a pivot fails.
    #[inline]
    fn projected_solve(&self, j: usize, ls: &mut LineScratch) -> bool {
        let nx = self.nx;
        let n = nx - 2;
        let nb = 2 * BAND + 1;
        for pass in 0..=ACTIVE_SET_PASSES {
            ls.band.copy_from_slice(&ls.borig);
            ls.rhs.copy_from_slice(&ls.rorig);
            for i in 1..nx - 1 {
                if ls.held[i] {
                    let r = i - 1;
                    ls.band[r * nb..(r + 1) * nb].fill(0.0);
                    ls.band[r * nb + BAND] = 1.0;
                    ls.rhs[i] = -self.p[j * nx + i] / ls.om[i];
                }
            }
            if !solve_band(&mut ls.band, &mut ls.rhs[1..nx - 1], n) {
                return false;
            }
            if pass == ACTIVE_SET_PASSES || !self.update_active_set(j, ls) {
                break;
            }
        }
        true
    }

    /// Checks every Gauss–Seidel row of line j against its own equation (`ls.borig`,
    /// `ls.rorig`) with the neighbours' new changes (`ls.rhs`): a held point whose free change
    /// would keep it positive is released, a free one that would go negative is held. Returns
    /// whether the active set changed.
    #[inline]
    fn update_active_set(&self, j: usize, ls: &mut LineScratch) -> bool {
        let nx = self.nx;
        let nb = 2 * BAND + 1;
        let mut changed = false;
        for i in 1..nx - 1 {
            if ls.jd[i] {
                continue;
            }
            let r = i - 1;
            let row = &ls.borig[r * nb..(r + 1) * nb];
            let mut free = ls.rorig[i];
            for (c, a) in row.iter().enumerate() {
                let k = i + c;
                if c != BAND && k > BAND && k - BAND < nx - 1 {
                    free -= a * ls.rhs[k - BAND];
                }
            }
            let hold = self.p[j * nx + i] + ls.om[i] * free / row[BAND] < 0.0;
            changed |= hold != ls.held[i];
            ls.held[i] = hold;
        }
        changed
    }

    /// Applies line j's changes (`ls.rhs`): Gauss–Seidel points at once (P + ω·δ, kept ≥ 0),
    /// Jacobi-distributive ones stored in `delta` for [`Level::distribute`]. Returns whether
    /// the line has Jacobi-distributive points.
    #[inline]
    fn apply_line(&mut self, j: usize, ls: &LineScratch, delta: &mut [f64]) -> bool {
        let nx = self.nx;
        let mut any_jd = false;
        for i in 1..nx - 1 {
            let d = ls.rhs[i];
            let idx = j * nx + i;
            if ls.jd[i] {
                delta[idx] = d;
                any_jd = true;
            } else {
                let v = self.p[idx] + ls.om[i] * d;
                self.p[idx] = v.max(0.0);
            }
        }
        any_jd
    }

    /// The Jacobi-distributive changes of a sweep: δ at a point and −δ/4 at its four
    /// neighbours, relaxed by `omega_jd`, P kept ≥ 0.
    #[inline]
    fn distribute(&mut self, delta: &[f64], omega_jd: f64) {
        let (nx, ny) = (self.nx, self.ny);
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                let idx = j * nx + i;
                let d = delta[idx]
                    - 0.25 * (delta[idx - 1] + delta[idx + 1] + delta[idx - nx] + delta[idx + nx]);
                if d != 0.0 {
                    self.p[idx] = (self.p[idx] + omega_jd * d).max(0.0);
                }
            }
        }
    }
}

/// Work arrays of a relaxation sweep's line solves, reused from line to line.
struct LineScratch {
    /// Band matrix of the line system: rows 1…nx − 2 of the line, 2·BAND + 1 entries each.
    band: Vec<f64>,
    /// Right-hand side (the residuals) and, after the solve, the changes δ, indexed by node i.
    rhs: Vec<f64>,
    /// `band` and `rhs` before the active-set rows replace theirs.
    borig: Vec<f64>,
    rorig: Vec<f64>,
    /// Per node: relaxed Jacobi-distributive (else Gauss–Seidel).
    jd: Vec<bool>,
    /// Per node: relaxation factor ω of a Gauss–Seidel change.
    om: Vec<f64>,
    /// Per node: held at P = 0 in the projected solve.
    held: Vec<bool>,
    /// Per node: the Poiseuille coefficients (centre, west, east, south, north).
    cws: Vec<[f64; 5]>,
    /// Kernel of a Jacobi-distributive change along its own line (dy = 0).
    kd: [f64; KX + 1],
}

/// Whether a pivot cannot be divided by (vanishing or not finite): the line solvers give up.
fn unusable_pivot(v: f64) -> bool {
    v.abs() <= 1e-300 || !v.is_finite()
}

/// Solves the line's pentadiagonal system in place (no pivoting): `a` holds n rows of 5
/// entries, row r's entry for column r + d (d = −2…2) at a[5r + d + 2]. The solution overwrites
/// `x`; `a` is overwritten. False if a pivot vanishes or the solution is not finite.
///
/// Eliminates from both ends at once (a "twisted" factorization): the upper half's rows
/// eliminate the subdiagonals downward, the lower half's rows the superdiagonals upward, the two
/// middle rows form a 2×2 system, and the two back substitutions run outward. Each row's
/// elimination waits for the previous row's pivot division, so a one-ended elimination is a
/// single chain of n dependent divisions; two independent chains of n/2 overlap in the
/// processor (the line solves were a fifth of a harmonic run's time). The arithmetic is that of
/// Gaussian elimination without pivoting, in a different order: results agree with
/// [`solve_band_forward`] to round-off (tested against the generic elimination). Systems of
/// fewer than 8 rows use [`solve_band_forward`].
fn solve_band(a: &mut [f64], x: &mut [f64], n: usize) -> bool {
    const _: () = assert!(BAND == 2, "solve_band is written for a half bandwidth of 2");
    if n < 8 {
        return solve_band_forward(a, x, n);
    }
    debug_assert!(a.len() >= 5 * n && x.len() >= n);
    let a = &mut a[..5 * n];
    let x = &mut x[..n];
    // Middle rows k and k + 1; the top eliminates with pivots 0…k − 1, the bottom with pivots
    // n − 1 down to k + 2. Their updates of rows k and k + 1 touch disjoint multipliers
    // (columns < k from the top, > k + 1 from the bottom) and add to the same 2×2 block.
    let k = n / 2 - 1;
    let (top, bottom) = (k, n - k - 2);
    for t in 0..top.max(bottom) {
        if t < top {
            let r = t;
            let piv = a[5 * r + 2];
            if unusable_pivot(piv) {
                return false;
            }
            let inv = 1.0 / piv;
            a[5 * r + 2] = inv;
            let (u1, u2, xr) = (a[5 * r + 3], a[5 * r + 4], x[r]);
            let f = a[5 * r + 6] * inv;
            a[5 * r + 7] -= f * u1;
            a[5 * r + 8] -= f * u2;
            x[r + 1] -= f * xr;
            let f = a[5 * r + 10] * inv;
            a[5 * r + 11] -= f * u1;
            a[5 * r + 12] -= f * u2;
            x[r + 2] -= f * xr;
        }
        if t < bottom {
            let r = n - 1 - t;
            let piv = a[5 * r + 2];
            if unusable_pivot(piv) {
                return false;
            }
            let inv = 1.0 / piv;
            a[5 * r + 2] = inv;
            let (l1, l2, xr) = (a[5 * r + 1], a[5 * r], x[r]);
            // Row r − 1: its column r at d = +1; row r − 2: its column r at d = +2.
            let f = a[5 * r - 2] * inv;
            a[5 * r - 3] -= f * l1;
            a[5 * r - 4] -= f * l2;
            x[r - 1] -= f * xr;
            let f = a[5 * r - 6] * inv;
            a[5 * r - 7] -= f * l1;
            a[5 * r - 8] -= f * l2;
            x[r - 2] -= f * xr;
        }
    }
    // The 2×2 system of rows k and k + 1 in x_k, x_{k+1}.
    let (akk, ak1) = (a[5 * k + 2], a[5 * k + 3]);
    let (a1k, a11) = (a[5 * k + 6], a[5 * k + 7]);
    if unusable_pivot(akk) {
        return false;
    }
    let l = a1k / akk;
    let d2 = a11 - l * ak1;
    if unusable_pivot(d2) {
        return false;
    }
    x[k + 1] = (x[k + 1] - l * x[k]) / d2;
    x[k] = (x[k] - ak1 * x[k + 1]) / akk;
    if !(x[k].is_finite() && x[k + 1].is_finite()) {
        return false;
    }
    for t in 0..top.max(bottom) {
        if t < top {
            let r = k - 1 - t;
            let s = x[r] - a[5 * r + 3] * x[r + 1] - a[5 * r + 4] * x[r + 2];
            x[r] = s * a[5 * r + 2];
            if !x[r].is_finite() {
                return false;
            }
        }
        if t < bottom {
            let r = k + 2 + t;
            let s = x[r] - a[5 * r + 1] * x[r - 1] - a[5 * r] * x[r - 2];
            x[r] = s * a[5 * r + 2];
            if !x[r].is_finite() {
                return false;
            }
        }
    }
    true
}

/// Solves the line's pentadiagonal system in place by forward elimination (no pivoting): `a`
/// holds n rows of 5 entries, row r's entry for column r + d (d = −2…2) at a[5r + d + 2]. The solution overwrites
/// `x`. False if a pivot vanishes or the solution is not finite. Written out for the half
/// bandwidth 2 of [`BAND`] (the generic loop spent a quarter of a steady solve in its bounds and
/// loop logic); the operations and their order are those of Gaussian elimination without
/// pivoting, as in the generic [`tests::solve_band_generic`] it is tested against.
fn solve_band_forward(a: &mut [f64], x: &mut [f64], n: usize) -> bool {
    const _: () = assert!(BAND == 2, "solve_band is written for a half bandwidth of 2");
    debug_assert!(a.len() >= 5 * n && x.len() >= n);
    let a = &mut a[..5 * n];
    let x = &mut x[..n];
    for r in 0..n {
        let (head, tail) = a.split_at_mut(5 * r + 5);
        let row: &mut [f64; 5] = (&mut head[5 * r..]).try_into().expect("5 entries");
        let piv = row[2];
        if unusable_pivot(piv) {
            return false;
        }
        // One division per row: the pivot's reciprocal is kept in its place for the back
        // substitution.
        let inv = 1.0 / piv;
        row[2] = inv;
        let (u1, u2) = (row[3], row[4]);
        let xr = x[r];
        if r + 1 < n {
            let next = &mut tail[..5];
            let f = next[1] * inv;
            if f != 0.0 {
                next[2] -= f * u1;
                if r + 2 < n {
                    next[3] -= f * u2;
                }
                x[r + 1] -= f * xr;
            }
        }
        if r + 2 < n {
            let next2 = &mut tail[5..10];
            let f = next2[0] * inv;
            if f != 0.0 {
                next2[1] -= f * u1;
                next2[2] -= f * u2;
                x[r + 2] -= f * xr;
            }
        }
    }
    for r in (0..n).rev() {
        let row = &a[5 * r..5 * r + 5];
        let mut s = x[r];
        if r + 1 < n {
            s -= row[3] * x[r + 1];
        }
        if r + 2 < n {
            s -= row[4] * x[r + 2];
        }
        x[r] = s * row[2];
        if !x[r].is_finite() {
            return false;
        }
    }
    true
}

/// The level hierarchy and the global unknown H0.
#[derive(Debug, Clone)]
pub(crate) struct Hierarchy {
    pub levels: Vec<Level>,
    pub h0: f64,
}

/// Bilinear interpolation of a coarse field to the fine grid.
fn interpolate(c: &[f64], ncx: usize, ncy: usize, f: &mut [f64], nfx: usize) {
    let _ = ncy;
    let nfy = 2 * ncy - 1;
    for jf in 0..nfy {
        let jc = jf / 2;
        let oy = jf % 2 == 1;
        for i_f in 0..nfx {
            let ic = i_f / 2;
            let ox = i_f % 2 == 1;
            let v = match (ox, oy) {
                (false, false) => c[jc * ncx + ic],
                (true, false) => 0.5 * (c[jc * ncx + ic] + c[jc * ncx + ic + 1]),
                (false, true) => 0.5 * (c[jc * ncx + ic] + c[(jc + 1) * ncx + ic]),
                (true, true) => {
                    0.25 * (c[jc * ncx + ic]
                        + c[jc * ncx + ic + 1]
                        + c[(jc + 1) * ncx + ic]
                        + c[(jc + 1) * ncx + ic + 1])
                }
            };
            f[jf * nfx + i_f] = v;
        }
    }
}

impl Hierarchy {
    /// Levels from `n_fine` down to `n_coarse` points per side (both 2^k + 1).
    pub fn new(pr: &Problem, n_fine: usize, n_coarse: usize) -> Hierarchy {
        let mut sizes = vec![n_fine];
        let mut n = n_fine;
        while n > n_coarse && (n - 1) % 2 == 0 && (n - 1) / 2 >= 4 {
            n = (n - 1) / 2 + 1;
            sizes.push(n);
        }
        sizes.reverse();
        Hierarchy {
            levels: sizes.iter().map(|&n| Level::new(n, pr)).collect(),
            h0: 0.0,
        }
    }

    /// One FAS cycle with `levels[k]` as the finest.
    pub fn cycle(&mut self, pr: &Problem, prm: &MgParams, k: usize) {
        if k == 0 {
            for _ in 0..prm.coarse_sweeps {
                // The film is updated once per sweep, after H0: H0's update needs only ∬P, and
                // the film of the old H0 (the update inside `relax`) would be overwritten unread.
                let lv = &mut self.levels[0];
                lv.relax_lines(pr, prm);
                // Force target g + γ·H0 (γ = 0 when steady); Newton-like step with the
                // contact's stiffness estimated as 1/h0_relax.
                let err = lv.g + pr.load_slope * self.h0 - lv.integral();
                self.h0 -= prm.h0_relax * err / (1.0 + prm.h0_relax * pr.load_slope);
                let h0 = self.h0;
                self.levels[0].update_film(pr, h0);
            }
            return;
        }
        for _ in 0..prm.pre {
            let h0 = self.h0;
            self.levels[k].relax(pr, prm, h0);
        }
        // restriction
        let (lo, hi) = self.levels.split_at_mut(k);
        let coarse = &mut lo[k - 1];
        let fine = &mut hi[0];
        fine.residual(pr);
        let (ncx, ncy, nfx) = (coarse.nx, coarse.ny, fine.nx);
        for jc in 0..ncy {
            for ic in 0..ncx {
                coarse.p[jc * ncx + ic] = fine.p[2 * jc * nfx + 2 * ic];
            }
        }
        coarse.pbar.copy_from_slice(&coarse.p);
        coarse.update_film(pr, self.h0);
        coarse.f.iter_mut().for_each(|v| *v = 0.0);
        for jc in 1..ncy - 1 {
            for ic in 1..ncx - 1 {
                let (l, _) = coarse.op(pr, ic, jc);
                let fi = 2 * jc * nfx + 2 * ic;
                let r = &fine.delta;
                let rw = 0.25 * r[fi]
                    + 0.125 * (r[fi - 1] + r[fi + 1] + r[fi - nfx] + r[fi + nfx])
                    + 0.0625
                        * (r[fi - 1 - nfx] + r[fi + 1 - nfx] + r[fi - 1 + nfx] + r[fi + 1 + nfx]);
                coarse.f[jc * ncx + ic] = l + rw;
            }
        }
        coarse.g = fine.g + coarse.integral() - fine.integral();
        for _ in 0..prm.gamma {
            self.cycle(pr, prm, k - 1);
        }
        // correction
        let (lo, hi) = self.levels.split_at_mut(k);
        let coarse = &mut lo[k - 1];
        let fine = &mut hi[0];
        let (ncx, ncy) = (coarse.nx, coarse.ny);
        let mut e = std::mem::take(&mut coarse.w);
        for (ev, (p, pb)) in e.iter_mut().zip(coarse.p.iter().zip(&coarse.pbar)) {
            *ev = p - pb;
        }
        let nfx = fine.nx;
        interpolate(&e, ncx, ncy, &mut fine.delta, nfx);
        for (p, d) in fine.p.iter_mut().zip(&fine.delta) {
            if *p > 0.0 {
                *p = (*p + d).max(0.0);
            }
        }
        coarse.w = e;
        // (The coarse film is recomputed at the next restriction; only the fine one is needed.)
        fine.update_film(pr, self.h0);
        for _ in 0..prm.post {
            let h0 = self.h0;
            self.levels[k].relax(pr, prm, h0);
        }
    }

    /// Interpolates the solution of level k−1 onto level k (FMG step) and updates its film.
    pub fn prolong_solution(&mut self, pr: &Problem, k: usize) {
        let (lo, hi) = self.levels.split_at_mut(k);
        let coarse = &lo[k - 1];
        let fine = &mut hi[0];
        let nfx = fine.nx;
        interpolate(&coarse.p, coarse.nx, coarse.ny, &mut fine.p, nfx);
        fine.update_film(pr, self.h0);
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The generic banded solver that [`solve_band`] replaced, kept as its reference: solves a
    /// banded system in place (no pivoting), `a` holding n rows of 2B+1 entries, row r's entry
    /// for column c at a[r·(2B+1) + c − r + B]; the solution overwrites `x`.
    pub(super) fn solve_band_generic<const B: usize>(
        a: &mut [f64],
        x: &mut [f64],
        n: usize,
    ) -> bool {
        let nb = 2 * B + 1;
        for r in 0..n {
            let piv = a[r * nb + B];
            if piv.abs() <= 1e-300 || !piv.is_finite() {
                return false;
            }
            // One division per row: the pivot's reciprocal is kept in its place for the back
            // substitution.
            let inv = 1.0 / piv;
            a[r * nb + B] = inv;
            let xr = x[r];
            let end = (r + B + 1).min(n);
            for rr in r + 1..end {
                let f = a[rr * nb + (r + B - rr)] * inv;
                if f == 0.0 {
                    continue;
                }
                // Column r of row rr becomes zero and is never read again: start at r + 1.
                for c in r + 1..end {
                    a[rr * nb + (c + B - rr)] -= f * a[r * nb + (c + B - r)];
                }
                x[rr] -= f * xr;
            }
        }
        for r in (0..n).rev() {
            let mut s = x[r];
            for c in r + 1..(r + B + 1).min(n) {
                s -= a[r * nb + (c + B - r)] * x[c];
            }
            x[r] = s * a[r * nb + B];
            if !x[r].is_finite() {
                return false;
            }
        }
        true
    }

    /// Random diagonally weighted pentadiagonal systems of 1 to 40 rows (and of 127, a 129²
    /// line), handed to `f` as (n, a, x).
    fn random_systems(mut f: impl FnMut(usize, &[f64], &[f64])) {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for n in (1..=40).chain([127]) {
            for _ in 0..20 {
                let mut a: Vec<f64> = (0..5 * n).map(|_| next()).collect();
                for r in 0..n {
                    a[5 * r + 2] += 3.0 * next().signum();
                }
                let x: Vec<f64> = (0..n).map(|_| next()).collect();
                f(n, &a, &x);
            }
        }
    }

    /// The solutions of `solver` and of the generic elimination for the system (n, a, x).
    fn both(
        solver: fn(&mut [f64], &mut [f64], usize) -> bool,
        n: usize,
        a: &[f64],
        x: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let (mut a1, mut x1) = (a.to_vec(), x.to_vec());
        let (mut a2, mut x2) = (a.to_vec(), x.to_vec());
        assert!(solver(&mut a1, &mut x1, n), "n = {n}");
        assert!(solve_band_generic::<2>(&mut a2, &mut x2, n), "n = {n}");
        (x1, x2)
    }

    /// The written-out forward elimination gives the generic elimination's result bit for bit,
    /// and refuses a zero pivot.
    #[test]
    fn forward_pentadiagonal_solver_matches_the_generic_one() {
        random_systems(|n, a, x| {
            let (x1, x2) = both(solve_band_forward, n, a, x);
            assert_eq!(x1, x2, "n = {n}");
        });
        let mut a = vec![1.0; 15];
        a[7] = 0.0;
        let mut x = vec![1.0; 3];
        assert!(!solve_band_forward(&mut a, &mut x, 3));
    }

    /// The two-ended elimination solves the same systems to round-off: its solution satisfies
    /// the equations to 1e-13 (relative to the largest term of a row; the systems' condition
    /// numbers are O(10)) and agrees with the generic elimination to 1e-12 relative to the
    /// largest unknown. A vanishing pivot in either half, or in the middle 2×2 system, is
    /// refused.
    #[test]
    fn two_ended_pentadiagonal_solver_matches_the_generic_one() {
        random_systems(|n, a, x| {
            let (x1, x2) = both(solve_band, n, a, x);
            let scale = x2.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (r, (u, v)) in x1.iter().zip(&x2).enumerate() {
                assert!(
                    (u - v).abs() <= 1e-12 * scale,
                    "n = {n}, row {r}: {u} vs {v}"
                );
            }
            for r in 0..n {
                let (mut s, mut big) = (-x[r], x[r].abs());
                for d in 0..5 {
                    let c = r + d;
                    if (2..n + 2).contains(&c) {
                        let t = a[5 * r + d] * x1[c - 2];
                        s += t;
                        big = big.max(t.abs());
                    }
                }
                assert!(
                    s.abs() <= 1e-13 * big.max(1.0),
                    "n = {n}, row {r}: residual {s}"
                );
            }
        });
        for zero in [2, 5 * 3 + 2, 5 * 8 + 2, 5 * 4 + 2] {
            // Identity systems of 10 rows with one zero diagonal entry: row 0 and row 3 (top
            // pivots), row 8 (a bottom pivot), row 4 (the middle pair).
            let mut a = vec![0.0; 50];
            for r in 0..10 {
                a[5 * r + 2] = 1.0;
            }
            a[zero] = 0.0;
            let mut x = vec![1.0; 10];
            assert!(!solve_band(&mut a, &mut x, 10), "zero at {zero}");
        }
    }
}
