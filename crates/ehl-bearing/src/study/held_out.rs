//! The held-out check of a map: random points inside its envelope, each characterized directly
//! with the map's settings and compared with the map's law there (docs/law_map.md §5). The
//! direct characterizations ("references") depend on the spec, the seed and the tolerance factor
//! only, not on the map's laws: with a [`PointStore`] each is written as soon as it is done, a
//! rerun reuses them (resumable), and they can be computed from the spec before the map exists
//! ([`held_out_references`]), so a slow map's check runs beside its generation.

use super::law_map::{characterize_record, compute_records, refuse_foreign, NodeRecord};
use super::{MapGenerationError, PointStore};
use crate::law_map::{
    tightened, DimensionlessLaw, Group, LawGroups, LawMap, LawMapError, LawMapSpec, MapQuery,
};
use serde::Serialize;

/// One held-out point: the map's law against a direct characterization at the same groups.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeldOutPoint {
    /// The groups.
    pub groups: LawGroups,
    /// The mass group Ψ_H (harmonic maps).
    pub psi_h: Option<f64>,
    /// The map's law and error estimate.
    pub map: MapQuery,
    /// The direct characterization's law.
    pub direct: DimensionlessLaw,
    /// Relative error of the map's force at the direct nominal approach: |Q̂_map(δ̂0) −
    /// Q̂_direct(δ̂0)|/Q̂_direct(δ̂0).
    pub force_error: f64,
    /// |d_map − d_direct|.
    pub d_error: f64,
    /// |ΔF̂_map − ΔF̂_direct|/|ΔF̂_direct|.
    pub delta_f_error: f64,
    /// |ΔF̂_map − ΔF̂_direct| (ΔF error over the load).
    pub delta_f_error_hat: f64,
    /// |ĉ_map − ĉ_direct|/|ĉ_direct| (harmonic maps).
    pub c_error: Option<f64>,
    /// Whether every solution of the direct characterization met its tolerances.
    pub direct_converged: bool,
}

/// `count` points drawn uniformly in the axes' coordinates inside the spec's envelope
/// (splitmix64 from `seed`): their groups and, for a harmonic map, their mass group Ψ_H.
pub fn held_out_points(
    spec: &LawMapSpec,
    count: usize,
    seed: u64,
) -> Vec<(LawGroups, Option<f64>)> {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let mut values = Vec::with_capacity(spec.axes.len());
            let mut psi_h = None;
            for a in &spec.axes {
                let v = a.at_fraction(next());
                if a.group == Group::PsiH {
                    psi_h = Some(v);
                }
                values.push(v);
            }
            (spec.groups_at(&values), psi_h)
        })
        .collect()
}

/// The file stem of held-out point `index` of `seed` at `tolerance_factor`.
fn stem(seed: u64, tolerance_factor: f64, index: usize) -> String {
    format!("held_out_seed{seed}_tf{tolerance_factor}_{index:06}")
}

/// What [`held_out_references`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOutReferences {
    /// One record per point, in the order drawn ([`NodeRecord::index`] the point's index; no
    /// law where the direct characterization failed, with its error).
    pub records: Vec<NodeRecord>,
    /// References computed in this run (the others were read from the store).
    pub computed: usize,
}

/// The direct characterizations of [`held_out_points`] (`count`, `seed`) with the spec's settings
/// and its steady tolerances times `tolerance_factor` ([`tightened`]). With a store, each is
/// read from it if a file of the same spec, point and groups is there, else computed and written
/// at once (atomically: an interrupted run resumes); a file of another spec or point under the
/// same name is an error naming it (nothing is overwritten). A factor outside (0, 1] is an error
/// before any point is drawn.
pub fn held_out_references(
    spec: &LawMapSpec,
    count: usize,
    seed: u64,
    tolerance_factor: f64,
    store: Option<&dyn PointStore>,
    on_point: &(dyn Fn(&NodeRecord) + Sync),
) -> Result<HeldOutReferences, MapGenerationError> {
    tightened(spec.settings().ehl, tolerance_factor)?;
    spec.validate()?;
    // The references depend on the envelope and the method's settings, not on which nodes a
    // map keeps: a sparse map and the tensor map of its axes share them.
    let spec = &LawMapSpec {
        sparse_level: None,
        ..spec.clone()
    };
    let points = held_out_points(spec, count, seed);
    let mut known: Vec<Option<NodeRecord>> = vec![None; count];
    let mut foreign = Vec::new();
    if let Some(store) = store {
        for (k, (g, psi)) in points.iter().enumerate() {
            let name = stem(seed, tolerance_factor, k);
            let Some(text) = store.load_point(&name)? else {
                continue;
            };
            match serde_json::from_str::<NodeRecord>(&text) {
                Ok(r) if r.spec == *spec && r.index == k && r.groups == *g && r.psi_h == *psi => {
                    known[k] = Some(r);
                }
                Ok(_) => foreign.push(store.point_location(&name)),
                // Unreadable (edited or damaged): computed again.
                Err(_) => {}
            }
        }
    }
    refuse_foreign(&foreign)?;
    let todo: Vec<usize> = (0..count).filter(|&k| known[k].is_none()).collect();
    let compute = |k: usize| {
        let (g, psi_h) = points[k];
        characterize_record(k, spec, g, psi_h, tolerance_factor)
    };
    let name = |k: usize| stem(seed, tolerance_factor, k);
    for r in compute_records(&todo, store, &name, &compute, on_point)? {
        let k = r.index;
        known[k] = Some(r);
    }
    Ok(HeldOutReferences {
        records: known
            .into_iter()
            .map(|r| r.expect("every point done"))
            .collect(),
        computed: todo.len(),
    })
}

/// `count` points drawn uniformly in the axes' coordinates inside the map's envelope
/// (splitmix64 from `seed`), each characterized directly with the map's settings and compared
/// with the map. Points whose direct characterization fails are left out (the count returned
/// says how many remain).
pub fn held_out_check(map: &LawMap, count: usize, seed: u64) -> Vec<HeldOutPoint> {
    held_out_check_with(map, count, seed, 1.0).expect("the tolerance factor 1 is valid")
}

/// [`held_out_check`] against direct characterizations with the map's steady tolerances (its
/// spec's `tolerance_factor` included) times `tolerance_factor` ([`tightened`]; the fitted ΔF
/// of heavy contacts follows the steady solutions' iteration error, docs/law_map.md §5). Points
/// whose direct characterization fails are left out; a factor outside (0, 1] is an error before
/// any point is drawn.
pub fn held_out_check_with(
    map: &LawMap,
    count: usize,
    seed: u64,
    tolerance_factor: f64,
) -> Result<Vec<HeldOutPoint>, LawMapError> {
    let none = |_: &NodeRecord| {};
    match held_out_references(&map.spec, count, seed, tolerance_factor, None, &none) {
        Ok(r) => Ok(held_out_compare(map, &r.records)),
        Err(MapGenerationError::Map(e)) => Err(e),
        Err(MapGenerationError::Store(_)) => unreachable!("no store"),
    }
}

/// The map against each reference with a law ([`held_out_references`]; those whose direct
/// characterization failed are left out).
pub fn held_out_compare(map: &LawMap, references: &[NodeRecord]) -> Vec<HeldOutPoint> {
    references
        .iter()
        .filter_map(|r| {
            let (direct, quality) = (r.law?, r.quality?);
            let g = &r.groups;
            let q = match r.psi_h {
                Some(p) => map.query_harmonic(g, p).ok()?,
                None => map.query(g).ok()?,
            };
            let a0 = direct.approach_hat;
            let qd = direct.force_hat(a0);
            Some(HeldOutPoint {
                groups: *g,
                psi_h: r.psi_h,
                map: q,
                direct,
                force_error: (q.law.force_hat(a0) - qd).abs() / qd,
                d_error: (q.law.d - direct.d).abs(),
                delta_f_error: (q.law.delta_f_hat - direct.delta_f_hat).abs()
                    / direct.delta_f_hat.abs(),
                delta_f_error_hat: (q.law.delta_f_hat - direct.delta_f_hat).abs(),
                c_error: match (q.law.c_hat, direct.c_hat) {
                    (Some(a), Some(b)) => Some((a - b).abs() / b.abs()),
                    _ => None,
                },
                direct_converged: quality.converged,
            })
        })
        .collect()
}
