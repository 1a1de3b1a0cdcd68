//! Load × speed studies of a bearing's fitted contact laws, and trend curves a rotor model can
//! evaluate without any EHL run.
//!
//! - [`Study`]: a study file (TOML; see [`crate::io::study::parse_study`]) — a case, inner-ring speeds, load scales,
//!   the characterization [`Method`](crate::method::Method) and the loop settings; its points
//!   ([`StudyPoint`]) and the fixed subsets that shards run ([`Shard`]).
//! - [`run_study`]: run all points or one shard, resuming from a [`PointStore`] (the file-system
//!   one is [`crate::io::FsStore`]); every finished point is one [`PointRecord`] written
//!   atomically. [`merge_points`] gathers shards run in separate folders; [`finish_study`] builds
//!   `results.csv`, `points.csv` and `trends.json` from the point files, identical for one run,
//!   a resumed run or merged shards.
//! - [`fit_trends`]: trend curves K(Q), d(Q), ΔF(Q, n) per raceway with fit quality and validity
//!   range from the study's rows, as a [`TrendModel`] (JSON with [`TrendModel::to_json`] /
//!   [`TrendModel::from_json`]), evaluated as a force element by
//!   [`crate::force_element::TrendForceElement`]. The model, its fit and its evaluation live in
//!   [`crate::trends`]; [`trend_reaction_error`] compares the element with a point.
//!
//! The library prints nothing: progress goes through a callback ([`StudyEvent`]). Forms, fits
//! and measured figures: `docs/study.md`.

mod held_out;
mod law_map;
mod point;
mod runner;
mod spec;
mod store;
mod trends;

// The trend model and its force element under their former paths (they live in
// crate::trends and crate::force_element; the study imports them, never the reverse).
pub use crate::force_element::{JacobianMode, TrendEvalOptions, TrendForce, TrendForceElement};
pub use crate::law_map::tightened;
pub use crate::trends::{RaceTrends, TrendBearing, TrendCurve, TrendModel, TREND_VERSION};
pub use held_out::{
    held_out_check, held_out_check_with, held_out_compare, held_out_points, held_out_references,
    HeldOutPoint, HeldOutReferences,
};
pub use law_map::{
    assemble_map, characterize_groups, characterize_node, characterize_node_with, generate_map,
    node_film_resolution, shards_with_nodes_left, under_resolved_nodes, MapGeneration,
    MapGenerationError, NodeRecord,
};
pub use point::{
    points_csv, results_csv, ContactLubrication, PointRecord, PointSpec, ResultRow,
    POINTS_CSV_HEADER, POINTS_CSV_LUBRICATION_HEADER,
};
pub use runner::{
    finish_study, merge_points, run_point, run_point_within, run_study, LubricationExtreme,
    LubricationSummary, RunOptions, StudyError, StudyEvent, StudyOutputs, StudyRun,
};
pub use spec::{Shard, Study, StudyPoint};
pub use store::{MemoryStore, PointStore, StoreError};
pub use trends::{fit_trends, trend_reaction_error};
