//! The map of the dimensionless law over the groups: its specification (axes and fixed groups),
//! the map file (the law at every node and the fit's quality there), and the interpolant with its
//! error estimate (docs/law_map.md §5).
//!
//! Interpolation: tensor-product polynomial interpolation in barycentric form on
//! Chebyshev–Gauss–Lobatto nodes of each axis's coordinate (ln of the group for `log` axes, the
//! group itself otherwise). Each axis has an odd number of nodes n, so every other node is itself
//! the Chebyshev–Gauss–Lobatto set of order (n − 1)/2: the error estimate of a query is the
//! difference between the interpolants on all nodes and on that nested half set. It estimates the
//! error of the coarser interpolant and so, where the interpolation converges, bounds that of
//! the finer one from above (measured against direct characterizations in the docs). A sparse
//! map (`sparse_level`) keeps a subset of the tensor nodes and combines small tensor
//! interpolants on them (Smolyak; [`super::sparse`]), its estimate the difference from the
//! combination one level lower.

use super::sparse::{self, Smolyak};
use super::{DimensionlessLaw, LawGroups, LawMapError};
use crate::contact::{ExcitationFrequency, HarmonicSettings, QuasiStaticSettings};
use crate::ehl::EhlSettings;
use crate::material::{DensityModel, ViscosityModel};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The map file's format tag.
pub const FORMAT: &str = "ehl-bearing law map 1";

/// A dimensionless group, as an axis or a fixed value of a map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Group {
    /// Moes' M.
    M,
    /// Moes' L.
    L,
    /// Ry/Rx.
    RyOverRx,
    /// α·p0.
    AlphaP0,
    /// ln(η0/η∞).
    LnEta0Ratio,
    /// Roelands' pressure–viscosity index Z = α·p0/ln(η0/η∞) (Roelands viscosity only): an axis
    /// in place of α·p0, which a node then gets as Z·ln(η0/η∞). Mineral oils lie near one Z
    /// (≈ 0.6–0.8), so a box in (ln(η0/η∞), Z) holds them without the (α·p0, ln(η0/η∞)) box's
    /// corners no oil reaches (α·p0 5 at ln(η0/η∞) 4 is Z = 1.2). Not one of [`Group::ALL`]: the
    /// steady problem's groups stay α·p0 and ln(η0/η∞).
    RoelandsZ,
    /// The harmonic law's mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) ([`super::mass_group`]); an
    /// axis of harmonic maps only, not one of the steady problem's groups (not in
    /// [`Group::ALL`], not in [`LawGroups`]: a query gives it with the ball's mass).
    PsiH,
}

impl Group {
    /// All groups.
    pub const ALL: [Group; 5] = [
        Group::M,
        Group::L,
        Group::RyOverRx,
        Group::AlphaP0,
        Group::LnEta0Ratio,
    ];

    /// The group's name as in messages and files.
    pub fn name(self) -> &'static str {
        match self {
            Group::M => "M",
            Group::L => "L",
            Group::RyOverRx => "Ry/Rx",
            Group::AlphaP0 => "alpha_p0",
            Group::LnEta0Ratio => "ln_eta0_ratio",
            Group::RoelandsZ => "roelands_z",
            Group::PsiH => "psi_h",
        }
    }

    /// The group's value in `g` (None where the models do not need it).
    pub fn get(self, g: &LawGroups) -> Option<f64> {
        match self {
            Group::M => Some(g.m),
            Group::L => Some(g.l),
            Group::RyOverRx => Some(g.ry_over_rx),
            Group::AlphaP0 => g.alpha_p0,
            Group::LnEta0Ratio => g.ln_eta0_ratio,
            Group::RoelandsZ => g.alpha_p0.zip(g.ln_eta0_ratio).map(|(a, c)| a / c),
            Group::PsiH => None,
        }
    }

    /// Sets group `self` of `g` to `v` (nothing for Ψ_H, which is no group of [`LawGroups`], nor
    /// for Z, which sets α·p0 only with ln(η0/η∞): [`LawMapSpec::groups_at`]).
    fn set(self, g: &mut LawGroups, v: f64) {
        match self {
            Group::M => g.m = v,
            Group::L => g.l = v,
            Group::RyOverRx => g.ry_over_rx = v,
            Group::AlphaP0 => g.alpha_p0 = Some(v),
            Group::LnEta0Ratio => g.ln_eta0_ratio = Some(v),
            Group::RoelandsZ | Group::PsiH => {}
        }
    }

    fn needed(self, v: ViscosityModel, d: DensityModel) -> bool {
        match self {
            Group::M | Group::L | Group::RyOverRx => true,
            Group::AlphaP0 => v == ViscosityModel::Roelands || d == DensityModel::DowsonHigginson,
            Group::LnEta0Ratio => v == ViscosityModel::Roelands,
            Group::RoelandsZ | Group::PsiH => false,
        }
    }
}

/// One axis of a map: a group sampled on `nodes` Chebyshev–Gauss–Lobatto nodes between `min`
/// and `max`, in ln(group) when `log`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapAxis {
    /// The group.
    pub group: Group,
    /// Smallest value (> 0 for log axes).
    pub min: f64,
    /// Largest value (> min).
    pub max: f64,
    /// Number of nodes (odd, 3 to 65).
    pub nodes: usize,
    /// Interpolate in ln(group).
    pub log: bool,
}

impl MapAxis {
    /// Whether `v` lies in the axis's range; outside (or NaN), the error naming the group, the
    /// value and the range.
    fn check(&self, v: f64) -> Result<(), LawMapError> {
        if v >= self.min && v <= self.max {
            Ok(())
        } else {
            Err(LawMapError::OutsideEnvelope {
                group: self.group.name().into(),
                value: v,
                min: self.min,
                max: self.max,
            })
        }
    }

    fn coord(&self, v: f64) -> f64 {
        if self.log {
            v.ln()
        } else {
            v
        }
    }

    fn value(&self, t: f64) -> f64 {
        if self.log {
            t.exp()
        } else {
            t
        }
    }

    /// The group's value at fraction `f` ∈ [0, 1] of the axis's coordinate range (of ln(group)
    /// when `log`), within [min, max].
    pub(crate) fn at_fraction(&self, f: f64) -> f64 {
        let (lo, hi) = (self.coord(self.min), self.coord(self.max));
        self.value(lo + (hi - lo) * f).clamp(self.min, self.max)
    }

    /// The node coordinates, ascending (the ends exactly at min and max).
    fn node_coords(&self) -> Vec<f64> {
        let (a, b) = (self.coord(self.min), self.coord(self.max));
        let n = self.nodes;
        (0..n)
            .map(|j| {
                if j == 0 {
                    a
                } else if j == n - 1 {
                    b
                } else {
                    0.5 * (a + b) - 0.5 * (b - a) * (PI * j as f64 / (n - 1) as f64).cos()
                }
            })
            .collect()
    }

    /// The group's values at the nodes, ascending.
    pub fn node_values(&self) -> Vec<f64> {
        let mut v: Vec<f64> = self
            .node_coords()
            .into_iter()
            .map(|t| self.value(t))
            .collect();
        // The ends exactly.
        v[0] = self.min;
        let n = v.len();
        v[n - 1] = self.max;
        v
    }

    /// Barycentric Lagrange basis at coordinate `t` on every `step`-th node (1: all, 2: the
    /// nested half set); zero on the skipped nodes.
    fn basis(&self, t: f64, step: usize) -> Vec<f64> {
        let idx: Vec<usize> = (0..self.nodes).step_by(step).collect();
        let mut out = vec![0.0; self.nodes];
        for (&j, w) in idx.iter().zip(self.basis_on(t, &idx)) {
            out[j] = w;
        }
        out
    }

    /// Barycentric Lagrange basis at coordinate `t` on the nodes `idx` (ascending, a
    /// Chebyshev–Gauss–Lobatto set of its own: all nodes, every 2^k-th, or one), aligned with
    /// `idx`.
    pub(super) fn basis_on(&self, t: f64, idx: &[usize]) -> Vec<f64> {
        let x = self.node_coords();
        let mut out = vec![0.0; idx.len()];
        if idx.len() == 1 {
            out[0] = 1.0;
            return out;
        }
        if let Some(hit) = idx.iter().position(|&j| t == x[j]) {
            out[hit] = 1.0;
            return out;
        }
        let last = idx.len() - 1;
        let mut sum = 0.0;
        for (i, &j) in idx.iter().enumerate() {
            let mut w = if i % 2 == 0 { 1.0 } else { -1.0 };
            if i == 0 || i == last {
                w *= 0.5;
            }
            let v = w / (t - x[j]);
            out[i] = v;
            sum += v;
        }
        for v in &mut out {
            *v /= sum;
        }
        out
    }

    /// The positions in `idx` (ascending node numbers) of the two nodes bracketing coordinate
    /// `t`: the last at or below `t` and the next.
    pub(super) fn bracket(&self, t: f64, idx: &[usize]) -> [usize; 2] {
        let x = self.node_coords();
        let i = idx.iter().rposition(|&j| x[j] <= t).unwrap_or(0);
        [i, (i + 1).min(idx.len() - 1)]
    }
}

/// The law a map samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawKind {
    /// The quasi-static method's law Q = K·δ^d + ΔF (the default; written nowhere in the file).
    #[default]
    QuasiStatic,
    /// The harmonic method's law Q = K·δ^d + ΔF + c·δ̇ at a relative excitation frequency
    /// Ω/ω_n; the map has the mass group Ψ_H as an axis and ĉ in every law.
    Harmonic,
}

impl LawKind {
    pub(crate) fn is_quasi_static(&self) -> bool {
        *self == LawKind::QuasiStatic
    }

    /// "quasi-static" or "harmonic".
    pub fn name(self) -> &'static str {
        match self {
            LawKind::QuasiStatic => "quasi-static",
            LawKind::Harmonic => "harmonic",
        }
    }
}

/// What a map samples: the models, the fixed groups, the axes, and the method's dimensionless
/// settings. Read from a TOML file (docs/law_map.md §5) or from a map file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LawMapSpec {
    /// Viscosity model.
    pub viscosity_model: ViscosityModel,
    /// Density model.
    pub density_model: DensityModel,
    /// Fixed value of M (when M is not an axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub m: Option<f64>,
    /// Fixed value of L (when L is not an axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub l: Option<f64>,
    /// Fixed value of Ry/Rx (when it is not an axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ry_over_rx: Option<f64>,
    /// Fixed value of α·p0 (when the models need it and it is not an axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha_p0: Option<f64>,
    /// Fixed value of ln(η0/η∞) (Roelands, when it is not an axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ln_eta0_ratio: Option<f64>,
    /// The axes (the first varies slowest in the node order).
    #[serde(rename = "axis")]
    pub axes: Vec<MapAxis>,
    /// The method's relative load amplitude ε.
    pub amplitude: f64,
    /// The quasi-static method's number of steady solutions (quasi-static maps only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<usize>,
    /// The EHL grid (points per side).
    pub grid: usize,
    /// The law sampled: `"quasi-static"` (the default, not written) or `"harmonic"`.
    #[serde(default, skip_serializing_if = "LawKind::is_quasi_static")]
    pub law: LawKind,
    /// The harmonic method's excitation frequency over the contact's natural frequency, Ω/ω_n
    /// (harmonic maps only; a relative frequency, as only those map: an absolute Ω is a new
    /// group per contact).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency_fraction: Option<f64>,
    /// The steady solver's tolerances (`tol_residual`, `tol_force`, `tol_film`) of the nodes
    /// times this factor, in (0, 1] ([`tightened`]; 1, the method's own, is the default and not
    /// written). Heavy contacts' ΔF needs it: at the method's tolerances a solution that stops
    /// at a residual of 4e-5 instead of 1e-6 moves the fitted ΔF by several percent
    /// (docs/law_map.md §5, "ΔF of heavy contacts").
    #[serde(default = "unit_factor", skip_serializing_if = "is_unit_factor")]
    pub tolerance_factor: f64,
    /// A sparse map's level q (Smolyak): only the tensor nodes whose axes' levels add up to at
    /// most q, each axis of 2^m + 1 nodes (3, 5, 9, 17, 33 or 65) with levels 0 (its middle
    /// node), 1 (ends and middle), … m (all). None (the default, not written): every tensor node.
    /// docs/law_map.md §5, "Sparse maps".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sparse_level: Option<u32>,
}

fn unit_factor() -> f64 {
    1.0
}

fn is_unit_factor(f: &f64) -> bool {
    *f == 1.0
}

/// The steady solver's settings `ehl` with its tolerances (`tol_residual`, `tol_force`,
/// `tol_film`) times `factor`, in (0, 1], and below 1 its cycle limit raised to
/// 40·(1 + 2·log10(1/factor)) (dimensionless). A map's nodes with its spec's
/// `tolerance_factor`; references tighter than a map's own nodes (`law-map check
/// --tolerance-factor`; docs/law_map.md §5, "ΔF of heavy contacts").
pub fn tightened(ehl: EhlSettings, factor: f64) -> Result<EhlSettings, LawMapError> {
    if !(factor.is_finite() && factor > 0.0 && factor <= 1.0) {
        return Err(LawMapError::Invalid {
            field: "tolerance_factor".into(),
            value: factor,
            expected: "a number in (0, 1]".into(),
        });
    }
    let mut s = ehl;
    s.tol_residual *= factor;
    s.tol_force *= factor;
    s.tol_film *= factor;
    if factor < 1.0 {
        let limit = (40.0 * (1.0 + 2.0 * (1.0 / factor).log10())).ceil() as usize;
        s.max_cycles = s.max_cycles.max(limit);
    }
    Ok(s)
}

impl LawMapSpec {
    /// Parses and validates a spec file's text.
    pub fn from_toml(text: &str) -> Result<LawMapSpec, LawMapError> {
        let s: LawMapSpec = toml::from_str(text).map_err(|e| LawMapError::Parse {
            message: e.to_string(),
        })?;
        s.validate()?;
        Ok(s)
    }

    fn fixed(&self, g: Group) -> Option<f64> {
        match g {
            Group::M => self.m,
            Group::L => self.l,
            Group::RyOverRx => self.ry_over_rx,
            Group::AlphaP0 => self.alpha_p0,
            Group::LnEta0Ratio => self.ln_eta0_ratio,
            Group::RoelandsZ | Group::PsiH => None,
        }
    }

    /// Checks that every group the models need is given once (fixed or as an axis) and no other,
    /// the axes' ranges and node counts, and the method's settings.
    pub fn validate(&self) -> Result<(), LawMapError> {
        let inv = |f: &str, v: f64, e: &str| LawMapError::Invalid {
            field: f.into(),
            value: v,
            expected: e.into(),
        };
        // A Z axis stands for α·p0 (and needs Roelands' ln(η0/η∞)).
        let z_axes = self
            .axes
            .iter()
            .filter(|a| a.group == Group::RoelandsZ)
            .count();
        if z_axes > 0 && self.viscosity_model != ViscosityModel::Roelands {
            return Err(LawMapError::GroupNotUsed {
                group: Group::RoelandsZ.name(),
                viscosity_model: self.viscosity_model,
                density_model: self.density_model,
            });
        }
        for g in Group::ALL {
            let axes = self.axes.iter().filter(|a| a.group == g).count()
                + if g == Group::AlphaP0 { z_axes } else { 0 };
            let fixed = self.fixed(g).is_some() as usize;
            let needed = g.needed(self.viscosity_model, self.density_model);
            if needed && axes + fixed != 1 {
                return Err(LawMapError::GroupCount {
                    group: if g == Group::AlphaP0 && z_axes > 0 {
                        "alpha_p0 (a roelands_z axis stands for it)"
                    } else {
                        g.name()
                    },
                    axes,
                    fixed,
                    viscosity_model: self.viscosity_model,
                    density_model: self.density_model,
                });
            }
            if !needed && axes + fixed != 0 {
                return Err(LawMapError::GroupNotUsed {
                    group: g.name(),
                    viscosity_model: self.viscosity_model,
                    density_model: self.density_model,
                });
            }
            if let Some(v) = self.fixed(g) {
                if !(v.is_finite() && v > 0.0) {
                    return Err(inv(g.name(), v, "finite and > 0"));
                }
            }
        }
        tightened(EhlSettings::default(), self.tolerance_factor)?;
        let most = 5 + usize::from(self.law == LawKind::Harmonic);
        if self.axes.is_empty() || self.axes.len() > most {
            return Err(LawMapError::AxisCount {
                axes: self.axes.len(),
            });
        }
        for a in &self.axes {
            let name = format!("axis {}", a.group.name());
            if !(a.min.is_finite() && a.max.is_finite() && a.min > 0.0 && a.max > a.min) {
                return Err(LawMapError::AxisRange {
                    group: a.group.name(),
                    min: a.min,
                    max: a.max,
                });
            }
            if !(3..=65).contains(&a.nodes) || a.nodes % 2 == 0 {
                return Err(inv(
                    &format!("{name}.nodes"),
                    a.nodes as f64,
                    "odd, 3 to 65 (every other node is the nested set of the error estimate)",
                ));
            }
            if self.sparse_level.is_some() && sparse::depth(a.nodes).is_none() {
                return Err(inv(
                    &format!("{name}.nodes"),
                    a.nodes as f64,
                    "3, 5, 9, 17, 33 or 65 in a sparse map (2^m + 1: the nested levels)",
                ));
            }
        }
        if let Some(q) = self.sparse_level {
            let nodes: Vec<usize> = self.axes.iter().map(|a| a.nodes).collect();
            let full = Smolyak::full_level(&nodes).unwrap_or(0);
            if !(1..=full).contains(&q) {
                return Err(inv(
                    "sparse_level",
                    f64::from(q),
                    &format!(
                        "1 to {full}, the sum of the axes' depths m (nodes = 2^m + 1), at which \
                         every tensor node is kept"
                    ),
                ));
            }
        }
        if self.node_count() > 200_000 {
            return Err(inv(
                "number of nodes",
                self.node_count() as f64,
                "at most 200000",
            ));
        }
        self.settings().ehl.validate().map_err(LawMapError::Ehl)?;
        if !(self.amplitude.is_finite() && self.amplitude > 0.0 && self.amplitude <= 0.9) {
            return Err(inv("amplitude", self.amplitude, "0 < ε ≤ 0.9"));
        }
        self.validate_law()?;
        // Every node's groups valid (ranges of M, L, Ry/Rx): those of the box's two corners.
        let lows: Vec<f64> = self.axes.iter().map(|a| a.min).collect();
        let highs: Vec<f64> = self.axes.iter().map(|a| a.max).collect();
        self.groups_at(&lows).validate()?;
        self.groups_at(&highs).validate()?;
        Ok(())
    }

    /// The settings of the spec's law: `points` for the quasi-static law; `frequency_fraction`,
    /// one Ψ_H axis and the harmonic method's settings for the harmonic one; none of the other
    /// law's.
    fn validate_law(&self) -> Result<(), LawMapError> {
        let inv = |f: &str, v: f64, e: &str| LawMapError::Invalid {
            field: f.into(),
            value: v,
            expected: e.into(),
        };
        let psi_axes = self.axes.iter().filter(|a| a.group == Group::PsiH).count();
        match self.law {
            LawKind::QuasiStatic => {
                match self.points {
                    Some(p) if (4..=101).contains(&p) => {}
                    Some(p) => return Err(inv("points", p as f64, "4 to 101")),
                    None => {
                        return Err(inv(
                            "points",
                            f64::NAN,
                            "4 to 101 (the quasi-static law's number of steady solutions)",
                        ))
                    }
                }
                if let Some(f) = self.frequency_fraction {
                    return Err(inv(
                        "frequency_fraction",
                        f,
                        "none: a quasi-static map has no excitation (law = \"harmonic\" for one)",
                    ));
                }
                if psi_axes > 0 {
                    return Err(inv(
                        "axis psi_h",
                        psi_axes as f64,
                        "none: the mass group is an axis of harmonic maps only",
                    ));
                }
            }
            LawKind::Harmonic => {
                if let Some(p) = self.points {
                    return Err(inv(
                        "points",
                        p as f64,
                        "none: a harmonic map's law is fitted to the recorded period",
                    ));
                }
                match self.frequency_fraction {
                    Some(f) if f.is_finite() && f > 0.0 && f <= 10.0 => {}
                    f => {
                        return Err(inv(
                            "frequency_fraction",
                            f.unwrap_or(f64::NAN),
                            "0 < Ω/ω_n ≤ 10 (required for law = \"harmonic\")",
                        ))
                    }
                }
                if psi_axes != 1 {
                    return Err(inv(
                        "axis psi_h",
                        psi_axes as f64,
                        "exactly one [[axis]] with group = \"psi_h\" in a harmonic map",
                    ));
                }
                self.harmonic_settings()
                    .validate()
                    .map_err(|e| inv("harmonic settings", f64::NAN, &e.to_string()))?;
            }
        }
        Ok(())
    }

    /// Number of nodes: the product of the axes' node counts, or for a sparse map the tensor
    /// nodes its level keeps.
    pub fn node_count(&self) -> usize {
        match self.sparse() {
            Some(s) => s.node_count(),
            None => self.tensor_node_count(),
        }
    }

    fn tensor_node_count(&self) -> usize {
        self.axes.iter().map(|a| a.nodes).product()
    }

    /// Whether node k of `other` is node k of this spec: the specs are equal, or both are sparse
    /// and differ only in their level (sparse nodes are numbered by level, so the nodes two
    /// levels share have the same numbers: a map's nodes serve a higher level's generation).
    pub fn same_nodes(&self, other: &LawMapSpec) -> bool {
        match (self.sparse_level, other.sparse_level) {
            (Some(_), Some(_)) => {
                *self
                    == LawMapSpec {
                        sparse_level: self.sparse_level,
                        ..other.clone()
                    }
            }
            _ => self == other,
        }
    }

    /// A sparse map's grid (None for a tensor map, or a sparse one whose node counts are not all
    /// 2^m + 1, which [`LawMapSpec::validate`] refuses).
    pub(super) fn sparse(&self) -> Option<Smolyak> {
        let level = self.sparse_level?;
        let nodes: Vec<usize> = self.axes.iter().map(|a| a.nodes).collect();
        Smolyak::new(&nodes, level)
    }

    /// Node multi-index of node `index` (tensor maps: the last axis fastest; sparse maps: the
    /// hierarchical order of [`Smolyak`]).
    fn multi_index(&self, index: usize) -> Vec<usize> {
        match self.sparse() {
            Some(s) => s.multi_index(index),
            None => self.tensor_multi_index(index),
        }
    }

    /// The tensor node number of multi-index `j` (the last axis fastest).
    pub(super) fn tensor_index(&self, j: &[usize]) -> usize {
        j.iter()
            .zip(&self.axes)
            .fold(0, |acc, (&j, a)| acc * a.nodes + j)
    }

    fn tensor_multi_index(&self, mut index: usize) -> Vec<usize> {
        let mut out = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            out[k] = index % a.nodes;
            index /= a.nodes;
        }
        out
    }

    /// The groups of node `index`.
    pub fn node_groups(&self, index: usize) -> LawGroups {
        let values: Vec<f64> = self
            .axes
            .iter()
            .zip(self.multi_index(index))
            .map(|(a, j)| a.node_values()[j])
            .collect();
        self.groups_at(&values)
    }

    /// The groups with the axes at `values` (one per axis, in the axes' order; Ψ_H's is no
    /// group) and the fixed groups; a Z axis gives α·p0 = Z·ln(η0/η∞).
    pub fn groups_at(&self, values: &[f64]) -> LawGroups {
        let mut g = LawGroups {
            m: self.m.unwrap_or(f64::NAN),
            l: self.l.unwrap_or(f64::NAN),
            ry_over_rx: self.ry_over_rx.unwrap_or(f64::NAN),
            alpha_p0: self.alpha_p0,
            ln_eta0_ratio: self.ln_eta0_ratio,
            viscosity: self.viscosity_model,
            density: self.density_model,
        };
        let mut z = None;
        for (a, &v) in self.axes.iter().zip(values) {
            match a.group {
                Group::RoelandsZ => z = Some(v),
                grp => grp.set(&mut g, v),
            }
        }
        if let Some(z) = z {
            g.alpha_p0 = g.ln_eta0_ratio.map(|c| z * c);
        }
        g
    }

    /// The mass group Ψ_H of node `index` (harmonic maps; None for quasi-static ones).
    pub fn node_psi_h(&self, index: usize) -> Option<f64> {
        self.axes
            .iter()
            .zip(self.multi_index(index))
            .find(|(a, _)| a.group == Group::PsiH)
            .map(|(a, j)| a.node_values()[j])
    }

    /// The quasi-static method's settings of the map's nodes (its grid, amplitude and number of
    /// solutions; everything else the defaults). For a harmonic map the fallback's quasi-static
    /// settings: its grid and amplitude, the default number of solutions.
    pub fn settings(&self) -> QuasiStaticSettings {
        let d = QuasiStaticSettings::default();
        QuasiStaticSettings {
            amplitude: self.amplitude,
            points: self.points.unwrap_or(d.points),
            ehl: self.ehl_settings(d.ehl),
            ..d
        }
    }

    /// `base` on the spec's grid with its tolerances times the spec's `tolerance_factor` (a
    /// factor outside (0, 1], which [`LawMapSpec::validate`] refuses, leaves them).
    fn ehl_settings(&self, base: EhlSettings) -> EhlSettings {
        let s = EhlSettings {
            grid: self.grid,
            ..base
        };
        tightened(s, self.tolerance_factor).unwrap_or(s)
    }

    /// The harmonic method's settings of a harmonic map's nodes: its amplitude, grid and Ω/ω_n
    /// (the default 0.005 if none is given), everything else the defaults.
    pub fn harmonic_settings(&self) -> HarmonicSettings {
        let d = HarmonicSettings::default();
        HarmonicSettings {
            amplitude: self.amplitude,
            frequency: ExcitationFrequency::FractionOfNatural(
                self.frequency_fraction
                    .unwrap_or(crate::contact::DEFAULT_FREQUENCY_FRACTION),
            ),
            ehl: self.ehl_settings(d.ehl),
            ..d
        }
    }

    /// Whether `g` lies in the map's envelope: the same models, the fixed groups equal (relative
    /// 1e-9) and the axes' groups within their ranges. The error names the group, its value and
    /// the range.
    pub fn check_inside(&self, g: &LawGroups) -> Result<(), LawMapError> {
        if (g.viscosity, g.density) != (self.viscosity_model, self.density_model) {
            return Err(LawMapError::Models {
                contact: format!("{:?}/{:?}", g.viscosity, g.density),
                map: format!("{:?}/{:?}", self.viscosity_model, self.density_model),
            });
        }
        for grp in Group::ALL {
            let Some(v) = grp.get(g) else { continue };
            if let Some(f) = self.fixed(grp) {
                if (v - f).abs() > 1e-9 * f.abs() {
                    return Err(LawMapError::OutsideEnvelope {
                        group: grp.name().into(),
                        value: v,
                        min: f,
                        max: f,
                    });
                }
            }
        }
        // The mass group is no group of the steady problem: the query checks it
        // (`LawMap::query_harmonic`).
        for a in self.axes.iter().filter(|a| a.group != Group::PsiH) {
            a.check(a.group.get(g).unwrap_or(f64::NAN))?;
        }
        Ok(())
    }
}

/// The fit's quality at one node.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NodeQuality {
    /// Coefficient of determination of the fit.
    pub r_squared: f64,
    /// RMS force residual of the fit over w0.
    pub rms_hat: f64,
    /// Whether every steady solution and the fit converged.
    pub converged: bool,
}

/// The map: the spec, the law at every node and the fit's quality there, and what its
/// generation cost.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LawMap {
    /// Format tag ([`FORMAT`]).
    pub format: String,
    /// What the map samples.
    pub spec: LawMapSpec,
    /// The dimensionless law at every node (node order: the last axis fastest).
    pub laws: Vec<DimensionlessLaw>,
    /// The fit's quality at every node.
    pub quality: Vec<NodeQuality>,
    /// Sum of the nodes' characterization costs, s: each node's thread CPU time where its file
    /// records it, else its wall time on one core (node files of earlier versions).
    pub cpu_seconds: f64,
}

/// The map's answer at some groups: the interpolated law and its error estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapQuery {
    /// The interpolated dimensionless law.
    pub law: DimensionlessLaw,
    /// Error estimate of each component (|all nodes − nested half set|): K̂, d, ΔF̂,
    /// approach, range.
    pub error: DimensionlessLaw,
    /// Estimated error of Q/w0 at the interpolated nominal approach (the two interpolants'
    /// laws evaluated there).
    pub force_error: f64,
    /// Largest RMS fit residual over w0 among the nodes the query's cell touches (the map's
    /// fit quality there).
    pub node_rms_hat: f64,
    /// Smallest coefficient of determination of the fit among those nodes.
    pub node_r_squared: f64,
    /// Whether all those nodes converged.
    pub nodes_converged: bool,
}

/// An embedded map file: its name (the stem of its example spec, `examples/law_map_<name>.toml`),
/// its bytes, and the law it samples (so a query parses only the maps of its law, and those only
/// up to the first that holds it).
struct Embedded {
    name: &'static str,
    bytes: &'static [u8],
    law: LawKind,
}

/// The [`Embedded`] entry of the map `name` on `grid`² of the law `law`: the file
/// `data/law_map_<name>_g<grid>.bin`.
macro_rules! embedded {
    ($name:literal, $grid:literal, $law:ident) => {
        Embedded {
            name: $name,
            bytes: include_bytes!(concat!("../../data/law_map_", $name, "_g", $grid, ".bin")),
            law: LawKind::$law,
        }
    };
}

/// The embedded map files in query order.
const EMBEDDED: [Embedded; 27] = [
    embedded!("seed_oil", 129, QuasiStatic),
    embedded!("seed_oil_high_l", 129, QuasiStatic),
    embedded!("seed_oil_low_m", 129, QuasiStatic),
    embedded!("seed_oil_high_m", 129, QuasiStatic),
    embedded!("mineral_oils", 129, QuasiStatic),
    embedded!("mineral_oils_light", 129, QuasiStatic),
    embedded!("mineral_oils_heavy", 129, QuasiStatic),
    embedded!("mineral_oils_low_l", 129, QuasiStatic),
    embedded!("mineral_oils_low_l_light", 129, QuasiStatic),
    embedded!("mineral_oils_high_l", 129, QuasiStatic),
    embedded!("mineral_oils_lightest", 129, QuasiStatic),
    embedded!("mineral_oils_heaviest", 129, QuasiStatic),
    embedded!("mineral_oils_low_l_heavy", 257, QuasiStatic),
    embedded!("mineral_oils_very_heavy", 257, QuasiStatic),
    embedded!("mineral_oils_ultra_heavy", 257, QuasiStatic),
    embedded!("mineral_oils_lightest_low_ry", 129, QuasiStatic),
    embedded!("mineral_oils_lightest_high_ry", 129, QuasiStatic),
    embedded!("mineral_oils_lightest_high_ry_m82", 129, QuasiStatic),
    embedded!("mineral_oils_light_high_l", 129, QuasiStatic),
    embedded!("mineral_oils_heavy_high_ry", 129, QuasiStatic),
    embedded!("seed_oil_harmonic", 129, Harmonic),
    embedded!("mineral_oils_harmonic", 129, Harmonic),
    embedded!("mineral_oils_lightest_harmonic", 129, Harmonic),
    embedded!("mineral_oils_heavy_harmonic", 129, Harmonic),
    embedded!("mineral_oils_low_l_harmonic", 129, Harmonic),
    embedded!("mineral_oils_low_l_heavy_harmonic", 129, Harmonic),
    embedded!("mineral_oils_low_l_light_harmonic", 129, Harmonic),
];

/// Embedded map `index` of [`EMBEDDED`], parsed on its first use. The files are valid and of
/// the law the table says (checked by the embedded maps' tests, which parse them all).
fn embedded_map(index: usize) -> &'static LawMap {
    static MAPS: [std::sync::OnceLock<LawMap>; EMBEDDED.len()] =
        [const { std::sync::OnceLock::new() }; EMBEDDED.len()];
    MAPS[index].get_or_init(|| {
        let e = &EMBEDDED[index];
        let map = LawMap::from_binary(e.bytes).expect("the embedded maps are valid");
        assert_eq!(map.spec.law, e.law, "embedded map {}: its law", e.name);
        map
    })
}

pub(super) fn law_of(v: &[f64; 7], harmonic: bool) -> DimensionlessLaw {
    DimensionlessLaw {
        k_hat: v[0],
        d: v[1],
        delta_f_hat: v[2],
        approach_hat: v[3],
        range_hat: [v[4], v[5]],
        c_hat: harmonic.then_some(v[6]),
    }
}

pub(super) fn values_of(l: &DimensionlessLaw) -> [f64; 7] {
    [
        l.k_hat,
        l.d,
        l.delta_f_hat,
        l.approach_hat,
        l.range_hat[0],
        l.range_hat[1],
        l.c_hat.unwrap_or(0.0),
    ]
}

impl LawMap {
    /// The maps embedded in the library (generated by `ehl-bearing law-map`, docs/law_map.md §5,
    /// which lists each with its box, cost and held-out errors), in query order, each parsed on
    /// its first use (the first call parses them all). All are Roelands and Dowson–Higginson, ε =
    /// 0.2. Twenty of the quasi-static law: four for the seed's oil (α·p0 = 4.312, ln(η0/η∞) =
    /// 6.451 fixed; `examples/law_map_seed_oil*.toml`) over M 64–8000, L 19–34, Ry/Rx 10–65;
    /// sixteen with the rheology groups as axes too (mineral oils,
    /// `examples/law_map_mineral_oils*.toml`: α·p0 and ln(η0/η∞), or ln(η0/η∞) and Roelands' Z =
    /// α·p0/ln(η0/η∞)) over M 60–30000, L 8–36, Ry/Rx 13.9–45, the last five over a narrow Z
    /// 0.70–0.74 at the envelope's edges (the lightest contacts at speed below M 90, light
    /// contacts at high L from M 115, heavy contacts of inner raceways above L 23). They are on
    /// 129² (the quasi-static method's default grid) but the three heaviest boxes (M 3900–10000
    /// at L 8–12.5, M 9000–15000 at L 8–23, M 15000–30000 at L 9.8–17: sparse maps of level 3),
    /// on 257² where 129² does not resolve the film; the heavy boxes' nodes were solved with the
    /// steady solver's tolerances × 0.1. The others are of the harmonic law (ĉ and the mass group
    /// Ψ_H, Ω = 0.005·ω_n, on 129²): the seed's oil, 11 × 5 × 9 × 3 nodes over M 120–4000, L
    /// 19–26, Ry/Rx 10–65 and Ψ_H 0.4–8 (`examples/law_map_seed_oil_harmonic.toml`), and sparse
    /// maps over six groups for mineral oils (`examples/law_map_mineral_oils*_harmonic.toml`):
    /// their main box, their lightest contacts, their heavy contacts to M 5000 and the contacts
    /// of slow large bearings (L 8–12.5, M 500–2700, 2700–3900 and 100–500). Each map has a
    /// name, the stem of its spec ([`LawMap::embedded_names`]). A query uses the first map of its
    /// law that holds it; its law is of that map's grid.
    pub fn embedded_maps() -> &'static [&'static LawMap] {
        static ALL: std::sync::OnceLock<Vec<&'static LawMap>> = std::sync::OnceLock::new();
        ALL.get_or_init(|| (0..EMBEDDED.len()).map(embedded_map).collect())
    }

    /// The names of the embedded maps, in the order of [`LawMap::embedded_maps`]: each the stem of
    /// the spec that generated it, `examples/law_map_<name>.toml` (e.g. `"seed_oil"`,
    /// `"mineral_oils_heavy_harmonic"`).
    pub fn embedded_names() -> impl ExactSizeIterator<Item = &'static str> {
        EMBEDDED.iter().map(|e| e.name)
    }

    /// The embedded map named `name` (one of [`LawMap::embedded_names`]), parsing only it.
    pub fn embedded_named(name: &str) -> Option<&'static LawMap> {
        let index = EMBEDDED.iter().position(|e| e.name == name)?;
        Some(embedded_map(index))
    }

    /// The first embedded map (M 120–4000, L 19–26, Ry/Rx 10–65), the only one parsed.
    pub fn embedded() -> &'static LawMap {
        embedded_map(0)
    }

    /// The first embedded map of the law `law` (parsing only it).
    pub fn embedded_first(law: LawKind) -> Option<&'static LawMap> {
        let index = EMBEDDED.iter().position(|e| e.law == law)?;
        Some(embedded_map(index))
    }

    /// The query of the first embedded map of the quasi-static law whose envelope holds `g`,
    /// with that map; outside all of them an error listing why each refused.
    pub fn query_embedded(g: &LawGroups) -> Result<(MapQuery, &'static LawMap), LawMapError> {
        Self::query_embedded_law(g, None)
    }

    /// The query of the first embedded map of the harmonic law whose envelope holds `g` and the
    /// mass group `psi_h` ([`super::mass_group`]), with that map; outside all of them an error
    /// listing why each refused.
    pub fn query_embedded_harmonic(
        g: &LawGroups,
        psi_h: f64,
    ) -> Result<(MapQuery, &'static LawMap), LawMapError> {
        Self::query_embedded_law(g, Some(psi_h))
    }

    fn query_embedded_law(
        g: &LawGroups,
        psi_h: Option<f64>,
    ) -> Result<(MapQuery, &'static LawMap), LawMapError> {
        let kind = match psi_h {
            Some(_) => LawKind::Harmonic,
            None => LawKind::QuasiStatic,
        };
        let mut reasons = Vec::new();
        for (i, e) in EMBEDDED.iter().enumerate().filter(|(_, e)| e.law == kind) {
            let m = embedded_map(i);
            match m.query_at(g, psi_h) {
                Ok(q) => return Ok((q, m)),
                Err(err) => reasons.push(format!("{}: {err}", e.name)),
            }
        }
        Err(LawMapError::OutsideEveryMap {
            reasons: reasons.join("; "),
            method: kind.name(),
        })
    }

    /// The interpolated law at `g` with its error estimate; an error if `g` lies outside the
    /// envelope (naming the group, its value and the range), or the map is of the harmonic law
    /// (see [`LawMap::query_harmonic`]).
    pub fn query(&self, g: &LawGroups) -> Result<MapQuery, LawMapError> {
        self.query_at(g, None)
    }

    /// The interpolated harmonic law (with ĉ) at `g` and the mass group `psi_h`
    /// ([`super::mass_group`]) with its error estimate; an error outside the envelope (naming
    /// the group, its value and the range) or if the map is of the quasi-static law.
    pub fn query_harmonic(&self, g: &LawGroups, psi_h: f64) -> Result<MapQuery, LawMapError> {
        self.query_at(g, Some(psi_h))
    }

    fn query_at(&self, g: &LawGroups, psi_h: Option<f64>) -> Result<MapQuery, LawMapError> {
        let harmonic = self.spec.law == LawKind::Harmonic;
        if harmonic != psi_h.is_some() {
            return Err(LawMapError::Invalid {
                field: "psi_h".into(),
                value: psi_h.unwrap_or(f64::NAN),
                expected: format!(
                    "{} for a map of the {} law",
                    if harmonic {
                        "the mass group Ψ_H (query_harmonic)"
                    } else {
                        "none"
                    },
                    self.spec.law.name()
                ),
            });
        }
        self.spec.check_inside(g)?;
        let axes = &self.spec.axes;
        let value = |a: &MapAxis| match a.group {
            Group::PsiH => psi_h.unwrap_or(f64::NAN),
            grp => grp.get(g).unwrap_or(f64::NAN),
        };
        for a in axes.iter().filter(|a| a.group == Group::PsiH) {
            a.check(value(a))?;
        }
        let t: Vec<f64> = axes.iter().map(|a| a.coord(value(a))).collect();
        let sums = match self.spec.sparse() {
            Some(grid) => self.sparse_sums(&grid, &t),
            None => self.tensor_sums(&t),
        };
        let (vf, vh) = (sums.fine, sums.coarse);
        let law = law_of(&vf, harmonic);
        let coarse = law_of(&vh, harmonic);
        let mut err = [0.0; 7];
        for c in 0..7 {
            err[c] = (vf[c] - vh[c]).abs();
        }
        let a0 = law.approach_hat;
        Ok(MapQuery {
            law,
            error: law_of(&err, harmonic),
            force_error: (law.force_hat(a0) - coarse.force_hat(a0)).abs(),
            node_rms_hat: sums.rms_hat,
            node_r_squared: sums.r_squared,
            nodes_converged: sums.converged,
        })
    }

    /// The tensor interpolants on all nodes and on the nested half set at coordinates `t`, and
    /// the fit quality of the nodes of the cell holding `t`.
    fn tensor_sums(&self, t: &[f64]) -> Sums {
        let axes = &self.spec.axes;
        let full: Vec<Vec<f64>> = axes.iter().zip(t).map(|(a, &t)| a.basis(t, 1)).collect();
        let half: Vec<Vec<f64>> = axes.iter().zip(t).map(|(a, &t)| a.basis(t, 2)).collect();
        // The nodes next to the query on each axis (for the fit quality there; on all nodes a
        // position is the node's number).
        let near: Vec<[usize; 2]> = axes
            .iter()
            .zip(t)
            .map(|(a, &t)| a.bracket(t, &(0..a.nodes).collect::<Vec<_>>()))
            .collect();
        let mut sums = Sums::new();
        for index in 0..self.spec.node_count() {
            let mi = self.spec.tensor_multi_index(index);
            let wf: f64 = mi.iter().enumerate().map(|(k, &j)| full[k][j]).product();
            let wh: f64 = mi.iter().enumerate().map(|(k, &j)| half[k][j]).product();
            if wf == 0.0 && wh == 0.0 {
                continue;
            }
            sums.add(&self.laws[index], wf, wh);
            if mi.iter().zip(&near).all(|(&j, n)| n.contains(&j)) {
                sums.quality(&self.quality[index]);
            }
        }
        sums
    }

    /// A sparse map's combinations of level q and q − 1 at coordinates `t`, and the fit
    /// quality of the nodes of the cells holding `t` in its tensor terms.
    fn sparse_sums(&self, grid: &Smolyak, t: &[f64]) -> Sums {
        let axes = &self.spec.axes;
        let plan = grid.plan();
        // Per axis and level: the basis at the query on its nodes and the positions of the two
        // bracketing nodes among them (the terms share them).
        let per_level: Vec<Vec<AxisLevel>> = axes
            .iter()
            .zip(t)
            .map(|(a, &t)| {
                let m = sparse::depth(a.nodes).unwrap_or(1);
                (0..=m)
                    .map(|i| {
                        let nodes = sparse::level_nodes(i, m);
                        AxisLevel {
                            basis: a.basis_on(t, &nodes),
                            near: a.bracket(t, &nodes),
                        }
                    })
                    .collect()
            })
            .collect();
        let mut sums = Sums::new();
        let mut at_level: Vec<&AxisLevel> = Vec::with_capacity(axes.len());
        let mut at = vec![0usize; axes.len()];
        for term in &plan.terms {
            at_level.clear();
            at_level.extend(
                per_level
                    .iter()
                    .zip(&term.levels)
                    .map(|(levels, &i)| &levels[i as usize]),
            );
            at.fill(0);
            // Every node of the term's tensor grid (the last axis fastest), in the plan's order.
            for &node in &term.nodes {
                let w: f64 = at.iter().zip(&at_level).map(|(&i, x)| x.basis[i]).product();
                if node != usize::MAX {
                    if w != 0.0 {
                        sums.add(&self.laws[node], term.fine * w, term.coarse * w);
                    }
                    if term.fine != 0.0 && at.iter().zip(&at_level).all(|(i, x)| x.near.contains(i))
                    {
                        sums.quality(&self.quality[node]);
                    }
                }
                sparse::advance(&mut at, |k| at_level[k].basis.len());
            }
        }
        sums
    }
}

/// One level of one axis of a sparse map at a query: the interpolation basis of its nodes at the
/// query's coordinate and the positions of the two nodes bracketing it among them.
struct AxisLevel {
    basis: Vec<f64>,
    near: [usize; 2],
}

/// A query's two interpolants (the map's and the coarser one of its error estimate) and the
/// fit quality of the nodes around it.
struct Sums {
    fine: [f64; 7],
    coarse: [f64; 7],
    rms_hat: f64,
    r_squared: f64,
    converged: bool,
}

impl Sums {
    fn new() -> Sums {
        Sums {
            fine: [0.0; 7],
            coarse: [0.0; 7],
            rms_hat: 0.0,
            r_squared: 1.0,
            converged: true,
        }
    }

    fn add(&mut self, law: &DimensionlessLaw, w_fine: f64, w_coarse: f64) {
        for ((f, c), v) in self
            .fine
            .iter_mut()
            .zip(&mut self.coarse)
            .zip(values_of(law))
        {
            *f += w_fine * v;
            *c += w_coarse * v;
        }
    }

    fn quality(&mut self, q: &NodeQuality) {
        self.rms_hat = self.rms_hat.max(q.rms_hat);
        self.r_squared = self.r_squared.min(q.r_squared);
        self.converged &= q.converged;
    }
}
