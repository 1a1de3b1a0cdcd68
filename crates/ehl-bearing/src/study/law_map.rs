//! Generating a map through the study machinery: every node is one point file in a
//! [`PointStore`] (written atomically as soon as it is done), a rerun skips the nodes whose file
//! holds the same spec and groups (resumable), a [`Shard`] runs every count-th node (round robin,
//! as study shards; a Slurm job array runs one shard per task), and [`assemble_map`] builds the
//! map from the node files alone, so the map is byte for byte the same however it was run.

use super::{PointStore, Shard, StoreError};
use crate::contact::{characterize_harmonic, characterize_quasi_static};
use crate::law_map::{
    mass_for_group, tightened, DimensionlessLaw, LawGroups, LawKind, LawMap, LawMapError,
    LawMapSpec, NodeQuality, FORMAT,
};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use thiserror::Error;

/// An error of a map's generation or assembly: the map's own, or the store's.
#[derive(Debug, Error)]
pub enum MapGenerationError {
    /// The spec, a node or the assembled map.
    #[error(transparent)]
    Map(#[from] LawMapError),
    /// Reading or writing the store.
    #[error(transparent)]
    Store(#[from] StoreError),
}

/// Curvature radius and reduced modulus of the contacts the nodes are solved on (any values
/// give the same dimensionless law, docs/law_map.md §4): a steel pair's E′ and Rx = 5 mm.
const NODE_RX: f64 = 5e-3;
const NODE_E: f64 = 2.286e11;

/// One node's file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeRecord {
    /// Node index (the last axis fastest).
    pub index: usize,
    /// The spec the node belongs to.
    pub spec: LawMapSpec,
    /// The node's groups.
    pub groups: LawGroups,
    /// The node's mass group Ψ_H (harmonic maps).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub psi_h: Option<f64>,
    /// The dimensionless law (None if the characterization failed).
    pub law: Option<DimensionlessLaw>,
    /// The fit's quality.
    pub quality: Option<NodeQuality>,
    /// The characterization's error, if it failed.
    pub error: Option<String>,
    /// Wall time of the characterization (one thread), s.
    pub seconds: f64,
    /// CPU time of the characterization's thread, s (it runs on one thread): what the node cost
    /// even where the machine was shared or the run paused. None in files of earlier versions
    /// and where the platform has no thread clock; [`NodeRecord::cost_seconds`] then uses the
    /// wall time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_seconds: Option<f64>,
}

impl NodeRecord {
    /// What the node cost, s: its thread's CPU time where recorded, else its wall time.
    pub fn cost_seconds(&self) -> f64 {
        self.cpu_seconds.unwrap_or(self.seconds)
    }
}

/// The CPU time of the calling thread, s (None where the platform has no thread clock).
fn thread_cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid timespec for the call to write.
        let r = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        (r == 0).then_some(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

fn stem(index: usize) -> String {
    format!("node_{index:06}")
}

/// The dimensionless law at `g` by a direct quasi-static characterization with the spec's
/// settings (on a contact with Rx = 5 mm and a steel pair's E′), with its fit quality. For a
/// harmonic map use [`characterize_node`] (this needs the mass group too).
pub fn characterize_groups(
    g: &LawGroups,
    spec: &LawMapSpec,
) -> Result<(DimensionlessLaw, NodeQuality), crate::Error> {
    characterize_node(g, None, spec)
}

/// The dimensionless law at `g` (and, for a harmonic map, the mass group `psi_h`) by a direct
/// characterization with the spec's settings, on a contact with Rx = 5 mm and a steel pair's
/// E′: the quasi-static method, or the harmonic method with the mass that gives the contact
/// `psi_h` ([`mass_for_group`]). With its fit quality.
pub fn characterize_node(
    g: &LawGroups,
    psi_h: Option<f64>,
    spec: &LawMapSpec,
) -> Result<(DimensionlessLaw, NodeQuality), crate::Error> {
    characterize_node_with(g, psi_h, spec, 1.0)
}

/// [`characterize_node`] with the steady solver's tolerances times `tolerance_factor`
/// ([`tightened`]; 1: the spec's own settings).
pub fn characterize_node_with(
    g: &LawGroups,
    psi_h: Option<f64>,
    spec: &LawMapSpec,
    tolerance_factor: f64,
) -> Result<(DimensionlessLaw, NodeQuality), crate::Error> {
    let c = g.contact(NODE_RX, NODE_E)?;
    let fit = match (spec.law, psi_h) {
        (LawKind::QuasiStatic, None) => {
            let mut s = spec.settings();
            s.ehl = tightened(s.ehl, tolerance_factor)?;
            characterize_quasi_static(&c, &s)?
        }
        (LawKind::Harmonic, Some(psi)) => {
            let mut s = spec.harmonic_settings();
            s.ehl = tightened(s.ehl, tolerance_factor)?;
            characterize_harmonic(&c, mass_for_group(&c, psi)?, &s)?
        }
        (law, psi) => {
            return Err(LawMapError::Invalid {
                field: "psi_h".into(),
                value: psi.unwrap_or(f64::NAN),
                expected: format!(
                    "{} for a map of the {} law",
                    if law == LawKind::Harmonic {
                        "a value"
                    } else {
                        "none"
                    },
                    law.name()
                ),
            }
            .into())
        }
    };
    let law = DimensionlessLaw::of_fit(&fit, &c)?;
    Ok((
        law,
        NodeQuality {
            r_squared: fit.r_squared,
            rms_hat: fit.rms_residual / c.load,
            converged: fit.converged,
        },
    ))
}

/// How well the spec's grid resolves the film at the node of groups `g`
/// ([`crate::ehl::film_resolution`] of the node's contact at its operating load, on the domain
/// its quasi-static family is solved on; dimensionless, compare with
/// [`crate::ehl::FILM_RESOLUTION_MIN`]). Cheap: no solve.
pub fn node_film_resolution(g: &LawGroups, spec: &LawMapSpec) -> Result<f64, LawMapError> {
    let c = g.contact(NODE_RX, NODE_E)?;
    crate::ehl::film_resolution(&c, &spec.settings().ehl).map_err(LawMapError::Ehl)
}

/// The nodes of `spec` whose film the spec's grid does not resolve
/// ([`node_film_resolution`] below [`crate::ehl::FILM_RESOLUTION_MIN`]), as (node index, ratio),
/// least resolved first. Such nodes are slow (their steady solutions end in limit cycles and
/// run through the solver's fallback starts) and their films wrong (negative nodal films;
/// docs/ehl.md §5.9): use a finer grid or a smaller box. Errors: an invalid spec or node.
pub fn under_resolved_nodes(spec: &LawMapSpec) -> Result<Vec<(usize, f64)>, LawMapError> {
    spec.validate()?;
    let mut out = Vec::new();
    for index in 0..spec.node_count() {
        let r = node_film_resolution(&spec.node_groups(index), spec)?;
        if r < crate::ehl::FILM_RESOLUTION_MIN {
            out.push((index, r));
        }
    }
    out.sort_by(|a, b| a.1.total_cmp(&b.1));
    Ok(out)
}

fn compute(index: usize, spec: &LawMapSpec) -> NodeRecord {
    let (groups, psi_h) = (spec.node_groups(index), spec.node_psi_h(index));
    characterize_record(index, spec, groups, psi_h, 1.0)
}

/// The record of a direct characterization at `groups` (and `psi_h`) with the spec's settings
/// and tolerances times `tolerance_factor` ([`characterize_node_with`]): the law and its quality,
/// or the error; its wall and thread CPU times. `index` is the node's or held-out point's.
pub(crate) fn characterize_record(
    index: usize,
    spec: &LawMapSpec,
    groups: LawGroups,
    psi_h: Option<f64>,
    tolerance_factor: f64,
) -> NodeRecord {
    let t0 = Instant::now();
    let c0 = thread_cpu_seconds();
    let (law, quality, error) = match characterize_node_with(&groups, psi_h, spec, tolerance_factor)
    {
        Ok((l, q)) => (Some(l), Some(q), None),
        Err(e) => (None, None, Some(e.to_string())),
    };
    NodeRecord {
        index,
        spec: spec.clone(),
        groups,
        psi_h,
        law,
        quality,
        error,
        seconds: t0.elapsed().as_secs_f64(),
        cpu_seconds: thread_cpu_seconds().zip(c0).map(|(c1, c0)| c1 - c0),
    }
}

/// The records of `todo` (indices), each computed by `compute` in parallel, written to `store`
/// under `name(index)` as soon as it is done (atomically: an interrupted run keeps what was
/// done) and then passed to `on_record`; in the order of `todo`.
pub(crate) fn compute_records(
    todo: &[usize],
    store: Option<&dyn PointStore>,
    name: &(dyn Fn(usize) -> String + Sync),
    compute: &(dyn Fn(usize) -> NodeRecord + Sync),
    on_record: &(dyn Fn(&NodeRecord) + Sync),
) -> Result<Vec<NodeRecord>, MapGenerationError> {
    todo.par_iter()
        .map(|&k| {
            let r = compute(k);
            if let Some(store) = store {
                let text = serde_json::to_string_pretty(&r).expect("record serializes");
                store.save_point(&name(k), &text)?;
            }
            on_record(&r);
            Ok(r)
        })
        .collect()
}

/// An error naming the first of the `foreign` record files (files of another spec or point
/// under this run's names), none if there are none: nothing is overwritten.
pub(crate) fn refuse_foreign(foreign: &[String]) -> Result<(), LawMapError> {
    match foreign.first() {
        None => Ok(()),
        Some(first) => Err(LawMapError::ForeignNodes {
            count: foreign.len(),
            first: first.clone(),
        }),
    }
}

/// What [`generate_map`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapGeneration {
    /// Nodes of the shard.
    pub nodes: usize,
    /// Nodes computed in this run.
    pub computed: usize,
    /// Nodes found finished in the store.
    pub loaded: usize,
    /// Nodes (computed in this run) whose characterization failed.
    pub failed: usize,
    /// Sum of the computed nodes' costs ([`NodeRecord::cost_seconds`]), s.
    pub cpu_seconds: f64,
}

/// Computes the nodes of `shard` that the store does not hold yet (in parallel over the rayon
/// pool), each saved as soon as it is done; `on_node` is called after each save. A store file of
/// another spec under a node's name stops the run before anything is computed unless
/// `overwrite`. Failed nodes are saved with their error (a rerun retries them).
pub fn generate_map(
    spec: &LawMapSpec,
    store: &dyn PointStore,
    shard: Shard,
    overwrite: bool,
    on_node: &(dyn Fn(&NodeRecord) + Sync),
) -> Result<MapGeneration, MapGenerationError> {
    spec.validate()?;
    let mine: Vec<usize> = (0..spec.node_count())
        .filter(|&k| shard.contains(k))
        .collect();
    let mut todo = Vec::new();
    let mut foreign = Vec::new();
    let mut loaded = 0;
    for &k in &mine {
        match store.load_point(&stem(k))? {
            None => todo.push(k),
            Some(text) => match serde_json::from_str::<NodeRecord>(&text) {
                Ok(r) if r.spec.same_nodes(spec) && r.index == k => {
                    if r.law.is_some() {
                        loaded += 1;
                    } else {
                        todo.push(k);
                    }
                }
                Ok(_) => {
                    foreign.push(store.point_location(&stem(k)));
                    todo.push(k);
                }
                // Unreadable (truncated by a crash before atomic writes, or edited): redo.
                Err(_) => todo.push(k),
            },
        }
    }
    if !overwrite {
        refuse_foreign(&foreign)?;
    }
    let results = compute_records(&todo, Some(store), &stem, &|k| compute(k, spec), on_node)?;
    let mut failed = 0;
    let mut cpu = 0.0;
    for r in results {
        failed += r.law.is_none() as usize;
        cpu += r.cost_seconds();
    }
    Ok(MapGeneration {
        nodes: mine.len(),
        computed: todo.len(),
        loaded,
        failed,
        cpu_seconds: cpu,
    })
}

/// The shards (1-based numbers of `shards` round-robin shards, as [`Shard`]) that still have a
/// node without a characterized law of this spec in the store: those a resubmission must run.
/// Empty when every node is done (the map can be assembled). A node file of another spec, an
/// unreadable one or a failed node counts as not done, as in [`generate_map`].
pub fn shards_with_nodes_left(
    spec: &LawMapSpec,
    store: &dyn PointStore,
    shards: usize,
) -> Result<Vec<usize>, MapGenerationError> {
    spec.validate()?;
    let shards = shards.max(1);
    let mut left = vec![false; shards];
    for k in 0..spec.node_count() {
        if left[k % shards] {
            continue;
        }
        let done = store
            .load_point(&stem(k))?
            .and_then(|t| serde_json::from_str::<NodeRecord>(&t).ok())
            .is_some_and(|r| r.spec.same_nodes(spec) && r.index == k && r.law.is_some());
        if !done {
            left[k % shards] = true;
        }
    }
    Ok((1..=shards).filter(|i| left[i - 1]).collect())
}

/// The map from the store's node files (every node must be present and characterized).
pub fn assemble_map(
    spec: &LawMapSpec,
    store: &dyn PointStore,
) -> Result<LawMap, MapGenerationError> {
    spec.validate()?;
    let n = spec.node_count();
    let mut laws = Vec::with_capacity(n);
    let mut quality = Vec::with_capacity(n);
    let mut cpu = 0.0;
    let mut missing = Vec::new();
    for k in 0..n {
        let rec = store
            .load_point(&stem(k))?
            .and_then(|t| serde_json::from_str::<NodeRecord>(&t).ok())
            .filter(|r| r.spec.same_nodes(spec) && r.index == k);
        match rec {
            Some(
                r @ NodeRecord {
                    law: Some(_),
                    quality: Some(_),
                    ..
                },
            ) => {
                cpu += r.cost_seconds();
                laws.push(r.law.expect("matched"));
                quality.push(r.quality.expect("matched"));
            }
            other => {
                let why = match other {
                    Some(r) => format!(
                        "failed at M = {}, L = {}, Ry/Rx = {}: {}",
                        r.groups.m,
                        r.groups.l,
                        r.groups.ry_over_rx,
                        r.error.unwrap_or_default()
                    ),
                    None => "missing".into(),
                };
                missing.push(format!("{}: {why}", store.point_location(&stem(k))));
            }
        }
    }
    if !missing.is_empty() {
        return Err(LawMapError::Incomplete {
            missing: missing.len(),
            total: n,
            first: missing[0].clone(),
        }
        .into());
    }
    Ok(LawMap {
        format: FORMAT.into(),
        spec: spec.clone(),
        laws,
        quality,
        cpu_seconds: cpu,
    })
}
