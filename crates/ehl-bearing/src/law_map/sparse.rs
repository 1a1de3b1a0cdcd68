//! Sparse maps: Smolyak's combination of small tensor interpolants on the nested
//! Chebyshev–Gauss–Lobatto levels of each axis (docs/law_map.md §5, "Sparse maps").
//!
//! An axis of n = 2^m + 1 nodes has the nested levels i = 0 … m: level 0 is its middle node, level
//! i ≥ 1 every 2^(m−i)-th node (2^i + 1 nodes, themselves a Chebyshev–Gauss–Lobatto set). A
//! sparse map of level q keeps the tensor nodes whose axes' levels add up to at most q, and
//! interpolates by the combination technique: Σ c_l · I_l over the multi-levels l of the set
//! {l : l_k ≤ m_k, Σ l_k ≤ q}, with I_l the tensor interpolant on the levels l and
//! c_l = Σ_{z ∈ {0,1}^d, l + z in the set} (−1)^|z|. Its error estimate is the difference from
//! the sparse interpolant of level q − 1 (a subset of the same nodes), as the tensor maps' is the
//! difference from their nested half set.
//!
//! The node order is hierarchical: the multi-levels by their sum, then lexicographically, and
//! within each the nodes new at exactly those levels (the last axis fastest). Node 0 is the middle
//! of the box; a map's first nodes are its coarsest sparse grids.

use std::sync::{Arc, Mutex};

use super::{LawMap, LawMapError, LawMapSpec};

impl LawMap {
    /// The sparse map of level `level` on this map's nodes: the same spec with `sparse_level`,
    /// the laws and fit quality of the nodes it keeps (a subset of this map's: of a tensor map,
    /// or of a sparse map of the same axes and a level at least `level`). Its `cpu_seconds` is
    /// this map's times the share of nodes kept (map files keep no cost per node). Errors: a
    /// sparse map of a lower level, an axis whose node count is not 2^m + 1, or a level outside
    /// 1 to the sum of the depths, naming the field, the value and the valid range.
    pub fn sparse_subset(&self, level: u32) -> Result<LawMap, LawMapError> {
        let source = self.spec.sparse();
        if let Some(q) = self.spec.sparse_level.filter(|&q| q < level) {
            return Err(LawMapError::Invalid {
                field: "sparse_level".into(),
                value: f64::from(level),
                expected: format!(
                    "at most {q}: a subset is taken of a tensor map or a sparse map of a level at \
                     least its own"
                ),
            });
        }
        let spec = LawMapSpec {
            sparse_level: Some(level),
            ..self.spec.clone()
        };
        spec.validate()?;
        let grid = spec.sparse().ok_or_else(|| LawMapError::Invalid {
            field: "axis nodes".into(),
            value: f64::NAN,
            expected: "2^m + 1 on every axis".into(),
        })?;
        let source_index = source.map(|s| s.index());
        let n = grid.node_count();
        let mut kept = Vec::with_capacity(n);
        for i in 0..n {
            let j = grid.multi_index(i);
            kept.push(match &source_index {
                // A node of a sparse grid is a node of every higher level's.
                Some(index) => index.of(&j).ok_or_else(|| LawMapError::Invalid {
                    field: "sparse_level".into(),
                    value: f64::from(level),
                    expected: "a level whose nodes the source map has".into(),
                })?,
                None => self.spec.tensor_index(&j),
            });
        }
        Ok(LawMap {
            format: self.format.clone(),
            laws: kept.iter().map(|&i| self.laws[i]).collect(),
            quality: kept.iter().map(|&i| self.quality[i]).collect(),
            cpu_seconds: self.cpu_seconds * n as f64 / self.laws.len() as f64,
            spec,
        })
    }
}

/// Depth m of an axis of `nodes` = 2^m + 1 nodes (3, 5, 9, 17, 33, 65); None for other counts.
pub(crate) fn depth(nodes: usize) -> Option<u32> {
    (nodes >= 3 && (nodes - 1).is_power_of_two()).then(|| (nodes - 1).trailing_zeros())
}

/// The level at which node `j` of an axis of depth `m` appears.
fn level_of(j: usize, m: u32) -> u32 {
    let last = 1usize << m;
    if 2 * j == last {
        0
    } else if j == 0 || j == last {
        1
    } else {
        m - j.trailing_zeros()
    }
}

/// The nodes new at level `i` of an axis of depth `m`, ascending.
fn new_nodes(i: u32, m: u32) -> Vec<usize> {
    let last = 1usize << m;
    match i {
        0 => vec![last / 2],
        1 => vec![0, last],
        _ => {
            let step = 1usize << (m - i);
            (0..1usize << (i - 1)).map(|r| (2 * r + 1) * step).collect()
        }
    }
}

/// The nodes of level `i` (those of every level up to `i`) of an axis of depth `m`, ascending.
pub(crate) fn level_nodes(i: u32, m: u32) -> Vec<usize> {
    let last = 1usize << m;
    if i == 0 {
        vec![last / 2]
    } else {
        (0..=last).step_by(1usize << (m - i)).collect()
    }
}

/// Number of nodes new at level `i`.
fn new_count(i: u32) -> usize {
    match i {
        0 => 1,
        1 => 2,
        _ => 1usize << (i - 1),
    }
}

/// The sparse grid of a map: the axes' depths and the level.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Smolyak {
    depths: Vec<u32>,
    level: u32,
}

impl Smolyak {
    /// The grid of axes of `nodes` each (every count 2^m + 1) at level `level`; None if a count
    /// is not of that form.
    pub(crate) fn new(nodes: &[usize], level: u32) -> Option<Smolyak> {
        let depths = nodes
            .iter()
            .map(|&n| depth(n))
            .collect::<Option<Vec<_>>>()?;
        Some(Smolyak { depths, level })
    }

    /// The largest useful level: the sum of the depths (the full tensor grid).
    pub(crate) fn full_level(nodes: &[usize]) -> Option<u32> {
        nodes.iter().map(|&n| depth(n)).sum()
    }

    /// The multi-levels with sum at most `q` (each within its axis's depth), in the node order:
    /// by sum, then lexicographically.
    fn levels(&self, q: u32) -> Vec<Vec<u32>> {
        let mut out = Vec::new();
        let mut l = vec![0u32; self.depths.len()];
        loop {
            if l.iter().sum::<u32>() <= q {
                out.push(l.clone());
            }
            // Next multi-level in the box (last axis fastest).
            let mut k = l.len();
            loop {
                if k == 0 {
                    out.sort_by_key(|l| (l.iter().sum::<u32>(), l.clone()));
                    return out;
                }
                k -= 1;
                if l[k] < self.depths[k] {
                    l[k] += 1;
                    break;
                }
                l[k] = 0;
            }
        }
    }

    fn block_size(l: &[u32]) -> usize {
        l.iter().map(|&i| new_count(i)).product()
    }

    /// Number of nodes.
    pub(crate) fn node_count(&self) -> usize {
        self.levels(self.level)
            .iter()
            .map(|l| Self::block_size(l))
            .sum()
    }

    /// The tensor multi-index (node number on each axis) of sparse node `index` (< node_count).
    pub(crate) fn multi_index(&self, mut index: usize) -> Vec<usize> {
        for l in self.levels(self.level) {
            let size = Self::block_size(&l);
            if index < size {
                let mut out = vec![0; l.len()];
                for k in (0..l.len()).rev() {
                    let new = new_nodes(l[k], self.depths[k]);
                    out[k] = new[index % new.len()];
                    index /= new.len();
                }
                return out;
            }
            index -= size;
        }
        // Past the last node: the last one's (callers stay below node_count).
        vec![0; self.depths.len()]
    }

    /// The combination's terms: every multi-level of the set of sum ≤ `q` with its nonzero
    /// coefficient.
    pub(crate) fn terms(&self, q: u32) -> Vec<(Vec<u32>, f64)> {
        let d = self.depths.len();
        let inside = |l: &[u32]| {
            l.iter().sum::<u32>() <= q && l.iter().zip(&self.depths).all(|(&i, &m)| i <= m)
        };
        self.levels(q)
            .into_iter()
            .filter_map(|l| {
                let mut c = 0.0;
                for z in 0..1usize << d {
                    let up: Vec<u32> = (0..d).map(|k| l[k] + ((z >> k) & 1) as u32).collect();
                    if inside(&up) {
                        c += if z.count_ones() % 2 == 0 { 1.0 } else { -1.0 };
                    }
                }
                (c != 0.0).then_some((l, c))
            })
            .collect()
    }

    /// A lookup from tensor multi-indices of the grid's nodes to their sparse index.
    pub(crate) fn index(&self) -> SparseIndex {
        let radix: Vec<usize> = self.depths.iter().map(|&m| m as usize + 1).collect();
        let mut offsets = vec![usize::MAX; radix.iter().product()];
        let mut offset = 0;
        for l in self.levels(self.level) {
            offsets[mixed(&l, &radix)] = offset;
            offset += Self::block_size(&l);
        }
        SparseIndex {
            depths: self.depths.clone(),
            radix,
            offsets,
        }
    }
}

/// What a query of a sparse map needs that depends on its grid only, made once per grid
/// ([`Smolyak::plan`]) and shared by every map of that grid: the tensor terms of the map's
/// combination (level q) and of its error estimate's (level q − 1), each with its two
/// coefficients and the sparse index of every node of its tensor grid.
#[derive(Debug)]
pub(crate) struct SparsePlan {
    pub(crate) terms: Vec<PlanTerm>,
}

/// One tensor term of a [`SparsePlan`].
#[derive(Debug)]
pub(crate) struct PlanTerm {
    /// The term's level on each axis.
    pub(crate) levels: Vec<u32>,
    /// Its coefficient in the combination of level q (the map).
    pub(crate) fine: f64,
    /// Its coefficient in the combination of level q − 1 (the error estimate).
    pub(crate) coarse: f64,
    /// The sparse index of each node of the term's tensor grid, the last axis fastest (the
    /// nodes of [`level_nodes`] on each axis).
    pub(crate) nodes: Vec<usize>,
}

impl Smolyak {
    /// The grid's query plan, made on the first call for this grid (axes' depths and level) in
    /// the process and shared afterwards: building it costs about as much as a thousand queries
    /// (the terms' coefficients run over every multi-level of the box and 2^d neighbours each).
    pub(crate) fn plan(&self) -> Arc<SparsePlan> {
        static PLANS: Mutex<Vec<(Smolyak, Arc<SparsePlan>)>> = Mutex::new(Vec::new());
        // A poisoned lock only means another thread panicked while holding it; the list is
        // never left half-written (a plan is pushed whole).
        let mut plans = PLANS.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, plan)) = plans.iter().find(|(g, _)| g == self) {
            return Arc::clone(plan);
        }
        let plan = Arc::new(self.make_plan());
        plans.push((self.clone(), Arc::clone(&plan)));
        plan
    }

    fn make_plan(&self) -> SparsePlan {
        let q = self.level;
        let mut terms: Vec<PlanTerm> = self
            .terms(q)
            .into_iter()
            .map(|(levels, c)| PlanTerm {
                levels,
                fine: c,
                coarse: 0.0,
                nodes: Vec::new(),
            })
            .collect();
        for (l, c) in self.terms(q.saturating_sub(1)) {
            match terms.iter_mut().find(|t| t.levels == l) {
                Some(term) => term.coarse = c,
                None => terms.push(PlanTerm {
                    levels: l,
                    fine: 0.0,
                    coarse: c,
                    nodes: Vec::new(),
                }),
            }
        }
        let index = self.index();
        for term in &mut terms {
            let axes: Vec<Vec<usize>> = term
                .levels
                .iter()
                .zip(&self.depths)
                .map(|(&i, &m)| level_nodes(i, m))
                .collect();
            let count: usize = axes.iter().map(Vec::len).product();
            let mut at = vec![0usize; axes.len()];
            let mut j = vec![0usize; axes.len()];
            term.nodes.reserve(count);
            for _ in 0..count {
                for ((x, &i), n) in j.iter_mut().zip(&at).zip(&axes) {
                    *x = n[i];
                }
                // Every node of a term of the set is a node of the sparse grid
                // (`terms_nodes_are_nodes_of_the_grid`).
                term.nodes.push(index.of(&j).unwrap_or(usize::MAX));
                advance(&mut at, |k| axes[k].len());
            }
        }
        SparsePlan { terms }
    }
}

/// The next multi-index `at` of a tensor grid of `len(k)` nodes on axis k, the last axis
/// fastest (back to all zeros after the last).
pub(super) fn advance(at: &mut [usize], len: impl Fn(usize) -> usize) {
    for k in (0..at.len()).rev() {
        at[k] += 1;
        if at[k] < len(k) {
            return;
        }
        at[k] = 0;
    }
}

fn mixed(l: &[u32], radix: &[usize]) -> usize {
    l.iter()
        .zip(radix)
        .fold(0, |acc, (&i, &r)| acc * r + i as usize)
}

/// Sparse index of tensor multi-indices ([`Smolyak::index`]).
pub(crate) struct SparseIndex {
    depths: Vec<u32>,
    radix: Vec<usize>,
    offsets: Vec<usize>,
}

impl SparseIndex {
    /// The sparse index of the node at tensor multi-index `j`; None if the sparse grid has no
    /// such node.
    pub(crate) fn of(&self, j: &[usize]) -> Option<usize> {
        // The block of the node's levels, then its place among the nodes new at those levels
        // (no allocation: a query looks up every node of every term).
        let mut block = 0;
        let mut local = 0;
        for ((&j, &m), &r) in j.iter().zip(&self.depths).zip(&self.radix) {
            let i = level_of(j, m);
            block = block * r + i as usize;
            local = local * new_count(i) + new_position(j, i, m);
        }
        match *self.offsets.get(block)? {
            usize::MAX => None,
            offset => Some(offset + local),
        }
    }
}

/// The place of node `j` (of level `i` on an axis of depth `m`) among [`new_nodes`]`(i, m)`.
fn new_position(j: usize, i: u32, m: u32) -> usize {
    match i {
        0 => 0,
        1 => usize::from(j != 0),
        _ => (j >> (m - i)) / 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classic_node_counts() {
        // Clenshaw–Curtis sparse grids (order 2^level + 1, order 1 at level 0) in two
        // dimensions: 1, 5, 13, 29, 65 points at levels 0–4 (J. Burkardt, SPARSE_GRID_CC, the
        // table of sparse grid sizes).
        for (q, n) in [(0, 1), (1, 5), (2, 13), (3, 29), (4, 65)] {
            assert_eq!(
                Smolyak::new(&[17, 17], q).unwrap().node_count(),
                n,
                "level {q}"
            );
        }
        // Three dimensions: 1, 7, 25, 69 (the same table).
        for (q, n) in [(0, 1), (1, 7), (2, 25), (3, 69)] {
            assert_eq!(
                Smolyak::new(&[9, 9, 9], q).unwrap().node_count(),
                n,
                "level {q}"
            );
        }
        // At the full level, every tensor node.
        assert_eq!(Smolyak::new(&[5, 3, 9], 6).unwrap().node_count(), 5 * 3 * 9);
    }

    #[test]
    fn indices_round_trip_and_are_distinct() {
        let s = Smolyak::new(&[9, 5, 3, 17], 5).unwrap();
        let index = s.index();
        let n = s.node_count();
        let mut seen = std::collections::HashSet::new();
        for i in 0..n {
            let j = s.multi_index(i);
            assert!(seen.insert(j.clone()), "node {i} repeated");
            assert_eq!(index.of(&j), Some(i));
            let levels: u32 = j.iter().zip(&s.depths).map(|(&j, &m)| level_of(j, m)).sum();
            assert!(levels <= 5);
        }
        // A node outside the sparse grid has none.
        assert_eq!(index.of(&[1, 1, 1, 1]), None);
        assert_eq!(s.multi_index(0), vec![4, 2, 1, 8], "node 0 is the middle");
    }

    #[test]
    fn coefficients_sum_to_one() {
        // The combination reproduces constants: Σ c_l = 1 at every level.
        for q in 0..=7 {
            let s = Smolyak::new(&[9, 5, 3, 17, 3], q).unwrap();
            let sum: f64 = s.terms(q).iter().map(|(_, c)| c).sum();
            assert_eq!(sum, 1.0, "level {q}");
        }
        // Isotropic and uncapped: c_l = (−1)^(q−|l|)·C(d−1, q−|l|) for q − d + 1 ≤ |l| ≤ q
        // (G. W. Wasilkowski, H. Woźniakowski, "Explicit cost bounds of algorithms for
        // multivariate tensor product problems", J. Complexity 11 (1995) 1–56).
        let s = Smolyak::new(&[65, 65, 65], 4).unwrap();
        for (l, c) in s.terms(4) {
            let k = 4 - l.iter().sum::<u32>();
            let expected = [1.0, -2.0, 1.0][k as usize];
            assert_eq!(c, expected, "{l:?}");
        }
    }

    #[test]
    fn terms_nodes_are_nodes_of_the_grid() {
        for q in 0..=6 {
            let s = Smolyak::new(&[9, 5, 3, 17, 3], q).unwrap();
            let plan = s.plan();
            let n = s.node_count();
            for t in &plan.terms {
                let size: usize = t
                    .levels
                    .iter()
                    .zip(&s.depths)
                    .map(|(&i, &m)| level_nodes(i, m).len())
                    .product();
                assert_eq!(t.nodes.len(), size, "level {q}, term {:?}", t.levels);
                assert!(
                    t.nodes.iter().all(|&k| k < n),
                    "level {q}, term {:?}",
                    t.levels
                );
            }
            // The same grid gets the same plan, made once.
            assert!(Arc::ptr_eq(&plan, &s.plan()));
        }
    }

    #[test]
    fn levels_of_nodes() {
        assert_eq!(level_nodes(2, 3), vec![0, 2, 4, 6, 8]);
        assert_eq!(level_nodes(0, 3), vec![4]);
        assert_eq!(new_nodes(3, 3), vec![1, 3, 5, 7]);
        let lv: Vec<u32> = (0..9).map(|j| level_of(j, 3)).collect();
        assert_eq!(lv, vec![1, 3, 2, 3, 0, 3, 2, 3, 1]);
        for m in 1..=6 {
            for i in 0..=m {
                for (p, &j) in new_nodes(i, m).iter().enumerate() {
                    assert_eq!(new_position(j, i, m), p, "node {j}, level {i}, depth {m}");
                }
            }
        }
    }
}
