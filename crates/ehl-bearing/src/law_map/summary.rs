//! What a map file holds, in brief: its spec (models, fixed groups, axes, the method's settings),
//! its node count, what its generation cost and the fits' quality — the one report `law-map info`
//! prints for a map file or the embedded maps, and `law-map assemble` for the file it wrote.

use super::map::{LawMap, LawMapSpec};
use serde::Serialize;

/// A map file in brief (all values dimensionless but the CPU time).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapSummary {
    /// An embedded map's name, the stem of the spec that generated it
    /// (`examples/law_map_<name>.toml`); `None` (JSON `null`) for a map file.
    pub name: Option<&'static str>,
    /// The law sampled: "quasi-static" or "harmonic".
    pub law: &'static str,
    /// Number of nodes.
    pub nodes: usize,
    /// Sum of the nodes' characterization times, s (one core each).
    pub cpu_seconds: f64,
    /// Nodes whose steady solutions or fit did not all converge (their laws are in the map,
    /// flagged; a query touching them reports it).
    pub nodes_not_converged: usize,
    /// Largest RMS fit residual over w0 of any node.
    pub worst_node_rms_hat: f64,
    /// Smallest coefficient of determination of any node's fit.
    pub worst_node_r_squared: f64,
    /// What the map samples, as in its file.
    pub spec: LawMapSpec,
}

impl LawMap {
    /// The map in brief (`name` `None`: see [`LawMap::embedded_summaries`]).
    pub fn summary(&self) -> MapSummary {
        MapSummary {
            name: None,
            law: self.spec.law.name(),
            nodes: self.laws.len(),
            cpu_seconds: self.cpu_seconds,
            nodes_not_converged: self.quality.iter().filter(|q| !q.converged).count(),
            worst_node_rms_hat: self.quality.iter().map(|q| q.rms_hat).fold(0.0, f64::max),
            worst_node_r_squared: self.quality.iter().map(|q| q.r_squared).fold(1.0, f64::min),
            spec: self.spec.clone(),
        }
    }

    /// The embedded maps in brief, in the order a query tries them, each with its name — what
    /// `law-map info`, Python's `law_maps()` and C's `ehl_law_maps_json` show.
    pub fn embedded_summaries() -> Vec<MapSummary> {
        Self::embedded_maps()
            .iter()
            .zip(Self::embedded_names())
            .map(|(m, name)| MapSummary {
                name: Some(name),
                ..m.summary()
            })
            .collect()
    }
}

impl std::fmt::Display for MapSummary {
    /// Three lines: the law, grid, settings, nodes and cost; the models and fixed groups; the
    /// axes (range, nodes, log or linear).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = &self.spec;
        write!(f, "{} law, grid {}², ε = {}", self.law, s.grid, s.amplitude)?;
        if let Some(p) = s.points {
            write!(f, ", {p} solutions")?;
        }
        if let Some(x) = s.frequency_fraction {
            write!(f, ", Ω = {x}·ω_n")?;
        }
        if s.tolerance_factor != 1.0 {
            write!(f, ", tolerances × {}", s.tolerance_factor)?;
        }
        if let Some(q) = s.sparse_level {
            write!(f, ", sparse level {q}")?;
        }
        writeln!(
            f,
            "; {} nodes, {:.2} CPU hours ({:.0} s), {} flagged not converged, worst node fit RMS/w0 {:.2e}",
            self.nodes,
            self.cpu_seconds / 3600.0,
            self.cpu_seconds,
            self.nodes_not_converged,
            self.worst_node_rms_hat
        )?;
        write!(
            f,
            "  viscosity {}, density {}",
            file_name_of(&s.viscosity_model),
            file_name_of(&s.density_model)
        )?;
        let fixed = [
            ("M", s.m),
            ("L", s.l),
            ("Ry/Rx", s.ry_over_rx),
            ("alpha_p0", s.alpha_p0),
            ("ln_eta0_ratio", s.ln_eta0_ratio),
        ];
        for (name, v) in fixed.iter().filter_map(|(n, v)| v.map(|v| (n, v))) {
            write!(f, "; {name} = {v}")?;
        }
        writeln!(f)?;
        let axes: Vec<String> = s
            .axes
            .iter()
            .map(|a| {
                format!(
                    "{} {}–{} ({} nodes{})",
                    a.group.name(),
                    a.min,
                    a.max,
                    a.nodes,
                    if a.log { ", log" } else { "" }
                )
            })
            .collect();
        write!(f, "  axes: {}", axes.join(" · "))
    }
}

/// A model's name as in spec and map files (e.g. "roelands", "dowson-higginson").
fn file_name_of<T: Serialize>(v: &T) -> String {
    serde_json::to_string(v)
        .unwrap_or_default()
        .trim_matches('"')
        .to_owned()
}
