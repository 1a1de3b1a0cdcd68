//! The lubricant's rheology at the nodes of the multigrid solver: ρ̄(P) and η̄(P) at p = p_h·P.
//!
//! [`Rheology`] evaluates the models exactly (the same operations as
//! [`Lubricant::viscosity_ratio`](crate::material::Lubricant::viscosity_ratio) and
//! [`Lubricant::density_ratio`](crate::material::Lubricant::density_ratio)); the film update
//! calls it at every loaded node after every relaxation sweep, and its `pow` and `exp` were a
//! fifth of a steady solve (BENCHMARKS.md, "Rheology table"). [`RheologyTable`] holds
//! η̄ on a uniform grid in P, interpolated by cubic Hermite with the exact derivative, with the
//! step chosen from the largest slope of ln η̄ so that the relative interpolation error stays
//! below [`TABLE_REL_ERROR`] (bound (h·max|d ln η̄/dP|)⁴/384 of the leading term); pressures
//! beyond the table, and problems whose table would exceed [`TABLE_MAX_NODES`], are evaluated
//! exactly. Tables are kept per thread and per (p_h, lubricant), so a steady solve builds its
//! table once and a family or a transient run reuses it.

use crate::material::{DensityModel, Lubricant, ViscosityModel, ROELANDS_LN_ETA_INF, ROELANDS_P0};
use std::cell::RefCell;
use std::sync::Arc;

/// Relative interpolation error aimed at by the table (of η̄; dimensionless).
pub(crate) const TABLE_REL_ERROR: f64 = 1e-9;
/// Largest dimensionless pressure P = p/p_h held in the table (beyond it: exact).
pub(crate) const TABLE_P_MAX: f64 = 4.0;
/// Largest number of table nodes (beyond it the problem is evaluated exactly).
pub(crate) const TABLE_MAX_NODES: usize = 1 << 15;
/// Tables kept per thread (least recently built dropped first).
const CACHE_ENTRIES: usize = 16;

/// The rheology of a problem with its constants evaluated once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rheology {
    /// Hertz pressure p_h, Pa.
    ph: f64,
    roelands: bool,
    /// Roelands: ln η0 + 9.67; Barus: α, 1/Pa.
    c: f64,
    /// Roelands' exponent z.
    z: f64,
    dowson_higginson: bool,
}

impl Rheology {
    pub(crate) fn new(lub: &Lubricant, ph: f64) -> Self {
        let roelands = lub.viscosity_model == ViscosityModel::Roelands;
        Rheology {
            ph,
            roelands,
            c: if roelands {
                lub.viscosity.ln() + ROELANDS_LN_ETA_INF
            } else {
                lub.pressure_viscosity
            },
            z: if roelands { lub.roelands_z() } else { 0.0 },
            dowson_higginson: lub.density_model == DensityModel::DowsonHigginson,
        }
    }

    /// η̄ at P ≥ 0, exactly.
    #[inline]
    pub(crate) fn viscosity(&self, pp: f64) -> f64 {
        let p = self.ph * pp;
        if self.roelands {
            (self.c * (-1.0 + (1.0 + p / ROELANDS_P0).powf(self.z))).exp()
        } else {
            (self.c * p).exp()
        }
    }

    /// d ln η̄ / dP at P ≥ 0.
    fn log_slope(&self, pp: f64) -> f64 {
        let a = self.ph / ROELANDS_P0;
        if self.roelands {
            self.c * self.z * a * (1.0 + a * pp).powf(self.z - 1.0)
        } else {
            self.c * self.ph
        }
    }

    /// ρ̄ at P ≥ 0.
    #[inline]
    pub(crate) fn density(&self, pp: f64) -> f64 {
        if self.dowson_higginson {
            let p = self.ph * pp;
            (5.9e8 + 1.34 * p) / (5.9e8 + p)
        } else {
            1.0
        }
    }

    fn key(&self) -> [u64; 5] {
        [
            self.ph.to_bits(),
            self.c.to_bits(),
            self.z.to_bits(),
            self.roelands as u64,
            self.dowson_higginson as u64,
        ]
    }
}

/// η̄(P) tabulated for cubic Hermite interpolation, with the exact model beyond it.
#[derive(Debug, Clone)]
pub(crate) struct RheologyTable {
    exact: Rheology,
    /// 1/h, h the table step in P.
    inv_h: f64,
    /// Number of intervals (0: no table, everything exact).
    n: usize,
    /// Per node k (P = k·h): [η̄, h·dη̄/dP].
    nodes: Vec<[f64; 2]>,
}

impl RheologyTable {
    pub(crate) fn new(exact: Rheology) -> Self {
        // The largest |d ln η̄/dP| over [0, P_max]: at P = 0 for Roelands (z < 1) and Barus;
        // at P_max when z > 1.
        let slope = exact
            .log_slope(0.0)
            .abs()
            .max(exact.log_slope(TABLE_P_MAX).abs());
        let h_max = (384.0 * TABLE_REL_ERROR).powf(0.25) / slope.max(1e-300);
        let n = (TABLE_P_MAX / h_max).ceil();
        if !(n.is_finite() && n >= 1.0 && n <= TABLE_MAX_NODES as f64) {
            return RheologyTable {
                exact,
                inv_h: 0.0,
                n: 0,
                nodes: Vec::new(),
            };
        }
        let n = n as usize;
        let h = TABLE_P_MAX / n as f64;
        let nodes = (0..=n)
            .map(|k| {
                let pp = k as f64 * h;
                let v = exact.viscosity(pp);
                [v, h * v * exact.log_slope(pp)]
            })
            .collect();
        RheologyTable {
            exact,
            inv_h: 1.0 / h,
            n,
            nodes,
        }
    }

    /// (ρ̄, η̄) at P > 0.
    #[inline]
    pub(crate) fn at(&self, pp: f64) -> (f64, f64) {
        let t = pp * self.inv_h;
        let eta = if t < self.n as f64 {
            let k = t as usize;
            let s = t - k as f64;
            let [f0, d0] = self.nodes[k];
            let [f1, d1] = self.nodes[k + 1];
            let s2 = s * s;
            let s3 = s2 * s;
            (2.0 * s3 - 3.0 * s2 + 1.0) * f0
                + (s3 - 2.0 * s2 + s) * d0
                + (3.0 * s2 - 2.0 * s3) * f1
                + (s3 - s2) * d1
        } else {
            self.exact.viscosity(pp)
        };
        (self.exact.density(pp), eta)
    }

    /// Whether η̄ is tabulated (false: every node exact).
    #[cfg(test)]
    fn tabulated(&self) -> bool {
        self.n > 0
    }
}

thread_local! {
    static TABLES: RefCell<Vec<([u64; 5], Arc<RheologyTable>)>> = const { RefCell::new(Vec::new()) };
}

/// The table of a lubricant at Hertz pressure `ph` (Pa), from this thread's cache or built.
pub(crate) fn table(lub: &Lubricant, ph: f64) -> Arc<RheologyTable> {
    let exact = Rheology::new(lub, ph);
    let key = exact.key();
    TABLES.with(|t| {
        let mut t = t.borrow_mut();
        if let Some(pos) = t.iter().position(|(k, _)| *k == key) {
            let e = t.remove(pos);
            let tab = e.1.clone();
            t.push(e);
            return tab;
        }
        let tab = Arc::new(RheologyTable::new(exact));
        if t.len() >= CACHE_ENTRIES {
            t.remove(0);
        }
        t.push((key, tab.clone()));
        tab
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lub(model: ViscosityModel, alpha: f64, eta0: f64) -> Lubricant {
        Lubricant {
            viscosity: eta0,
            pressure_viscosity: alpha,
            viscosity_model: model,
            density_model: DensityModel::DowsonHigginson,
            ..Lubricant::DEFAULT_MINERAL_OIL
        }
    }

    /// The table reproduces the exact model within its error target (with a factor 10 for the
    /// neglected higher-order terms of the bound) at 200 001 pressures over and beyond its range,
    /// for the project's oil from light to heavy contacts and for Barus up to αp_h = 30.
    #[test]
    fn table_matches_the_exact_model() {
        let cases = [
            (lub(ViscosityModel::Roelands, 2.2e-8, 0.04), 0.3e9),
            (lub(ViscosityModel::Roelands, 2.2e-8, 0.04), 2.0e9),
            (lub(ViscosityModel::Roelands, 2.2e-8, 0.04), 4.0e9),
            (lub(ViscosityModel::Roelands, 1.0e-8, 0.01), 1.5e9),
            (lub(ViscosityModel::Barus, 2.2e-8, 0.04), 1.0e9),
            (lub(ViscosityModel::Barus, 1.5e-8, 0.04), 2.0e9),
        ];
        for (l, ph) in cases {
            let t = RheologyTable::new(Rheology::new(&l, ph));
            assert!(t.tabulated(), "{l:?} at {ph}");
            let mut worst = 0.0_f64;
            for k in 0..=200_000 {
                let pp = 5.0 * k as f64 / 200_000.0;
                let (r, eta) = t.at(pp);
                let p = ph * pp;
                let (er, ee) = (l.density_ratio(p), l.viscosity_ratio(p));
                assert!((r - er).abs() <= 1e-15 * er, "ρ̄ at P = {pp}: {r} vs {er}");
                worst = worst.max((eta - ee).abs() / ee);
            }
            assert!(
                worst <= 10.0 * TABLE_REL_ERROR,
                "{l:?} at p_h = {ph}: worst relative error of η̄ {worst:.3e}"
            );
        }
    }

    /// Beyond TABLE_MAX_NODES the table is not built and every node is exact.
    #[test]
    fn steep_barus_is_evaluated_exactly() {
        let l = lub(ViscosityModel::Barus, 2.0e-7, 0.04);
        let ph = 3.0e9; // αp_h = 600
        let t = RheologyTable::new(Rheology::new(&l, ph));
        assert!(!t.tabulated());
        assert_eq!(t.at(0.7).1, l.viscosity_ratio(0.7 * ph));
    }

    #[test]
    fn cache_returns_the_same_table_for_the_same_problem() {
        let l = lub(ViscosityModel::Roelands, 2.2e-8, 0.04);
        let a = table(&l, 1.9e9);
        let b = table(&l, 1.9e9);
        assert!(Arc::ptr_eq(&a, &b));
        let c = table(&l, 1.8e9);
        assert!(!Arc::ptr_eq(&a, &c));
    }
}
