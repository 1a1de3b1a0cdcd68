//! The study file and its points: [`Study`] (read and validated from a TOML study file by
//! [`crate::io::study::parse_study`]),
//! [`StudyPoint`], and the fixed subsets of points that shards run ([`Shard`]).

use super::point::PointSpec;
use crate::bearing::Control;
use crate::case::{Case, InputError};
use crate::characterize::CharacterizeSettings;
use crate::method::{Method, MethodError};
use std::f64::consts::PI;

/// A validated study.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The base case (its speeds and loads are replaced per point).
    pub case: Case,
    /// Where the case came from (file path as given, or `inline`).
    pub case_origin: String,
    /// Characterization method with its settings (`method` and `[method_options]`; default
    /// quasi-static).
    pub method: Method,
    /// The `[method_options]` table as given (kept so that a command-line override of the
    /// method name can apply the same options).
    pub method_options: Option<toml::Table>,
    /// Inner-ring speeds, rpm (the outer ring speed is the case's).
    pub inner_speeds_rpm: Vec<f64>,
    /// Factors applied to the case's load-controlled DOFs (forces and moments); imposed
    /// displacements and tilts are kept.
    pub load_scales: Vec<f64>,
    /// Loop settings.
    pub settings: CharacterizeSettings,
}

/// One point of a study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudyPoint {
    /// Index in the study (speeds outer, load scales inner).
    pub index: usize,
    /// Inner-ring speed, rpm.
    pub inner_speed_rpm: f64,
    /// Load scale (dimensionless).
    pub load_scale: f64,
}

impl StudyPoint {
    /// File stem of the point, e.g. `n3000rpm_s1.5`: Rust's shortest round-trip formatting, so
    /// a value always maps to the same name, and distinct values to distinct names. Values whose
    /// positional form is longer than 20 characters (e.g. 1e-300, which would be 302) are written
    /// in exponent form (`n3000rpm_s1e-300`), so a name stays under 60 bytes for every valid value.
    pub fn file_stem(&self) -> String {
        format!(
            "n{}rpm_s{}",
            crate::case::number_text(self.inner_speed_rpm),
            crate::case::number_text(self.load_scale)
        )
    }
}

impl Study {
    /// All points, speeds outer, load scales inner.
    pub fn points(&self) -> Vec<StudyPoint> {
        let mut out = Vec::new();
        for &n in &self.inner_speeds_rpm {
            for &s in &self.load_scales {
                out.push(StudyPoint {
                    index: out.len(),
                    inner_speed_rpm: n,
                    load_scale: s,
                });
            }
        }
        out
    }

    /// The case of a point: inner speed replaced, load-controlled DOFs scaled.
    pub fn point_case(&self, p: &StudyPoint) -> Case {
        let mut c = self.case.clone();
        c.operating.inner_speed = p.inner_speed_rpm * PI / 30.0;
        for dof in c.operating.dofs.iter_mut() {
            if let Control::Load(f) = dof {
                *f *= p.load_scale;
            }
        }
        c
    }

    /// Everything a point's result depends on: written into the point file and compared on
    /// resume (a point file with a different spec is recomputed).
    pub fn point_spec(&self, p: &StudyPoint) -> PointSpec {
        let c = self.point_case(p);
        PointSpec {
            inner_speed_rpm: p.inner_speed_rpm,
            load_scale: p.load_scale,
            method: self.method,
            settings: self.settings,
            bearing: c.bearing,
            lubricant: c.lubricant,
            operating: c.operating,
            equilibrium: c.settings,
            oil: c.oil,
            roughness: c.roughness,
            ring_oils: c.ring_oils,
            inlet_meniscus_distance_m: c.inlet_meniscus_distance_m,
        }
    }

    /// Replace the method by `name` (a command-line override): the study file's
    /// `[method_options]` apply if the name is the file's own method, the defaults otherwise.
    pub fn set_method(&mut self, name: &str) -> Result<(), MethodError> {
        let options = if name == self.method.name() {
            self.method_options.as_ref()
        } else {
            None
        };
        self.method = Method::parse(name, options)?;
        Ok(())
    }

    /// The points of shard `shard` ([`Shard::contains`]), in study order.
    pub fn shard_points(&self, shard: Shard) -> Vec<StudyPoint> {
        self.points()
            .into_iter()
            .filter(|p| shard.contains(p.index))
            .collect()
    }
}

/// A fixed subset of a study's points: shard `index` of `count` (1-based, as `--shard 2/3`)
/// holds the points whose index k satisfies k mod count = index − 1 — round robin over the study
/// order (speeds outer, load scales inner), so every shard gets a share of every speed and of
/// the heavy and light loads. The whole study is shard 1/1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Shard number, 1 to `count`.
    pub index: usize,
    /// Number of shards, ≥ 1.
    pub count: usize,
}

impl Shard {
    /// The whole study.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Shard `index` of `count`; errors unless 1 ≤ index ≤ count ≤ 100 000.
    pub fn new(index: usize, count: usize) -> Result<Self, InputError> {
        if !(1..=100_000).contains(&count) {
            return Err(InputError::field(
                "shard",
                format!("{index}/{count}"),
                "i/N with N from 1 to 100000",
            ));
        }
        if !(1..=count).contains(&index) {
            return Err(InputError::field(
                "shard",
                format!("{index}/{count}"),
                format!("i/N with i from 1 to N = {count}"),
            ));
        }
        Ok(Shard { index, count })
    }

    /// Whether point `k` (0-based study index) belongs to this shard.
    pub fn contains(&self, k: usize) -> bool {
        k % self.count == self.index - 1
    }
}

impl std::str::FromStr for Shard {
    type Err = InputError;
    /// Parse `i/N`, e.g. `2/3`.
    fn from_str(s: &str) -> Result<Self, InputError> {
        let bad = || InputError::field("shard", s, "i/N with 1 ≤ i ≤ N, e.g. 2/3");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        Shard::new(i, n)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}
