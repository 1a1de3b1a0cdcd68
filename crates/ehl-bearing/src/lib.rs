//! # ehl-bearing
//!
//! Lubricated contacts of angular-contact ball bearings: a quasi-static 5-DOF bearing model
//! ([`bearing`]), Hertz elliptical contacts ([`hertz`]), an elastohydrodynamic point-contact solver
//! ([`ehl`]), a Levenberg–Marquardt fit of the nonlinear contact law Q = K·δ^d + ΔF ([`fit`]), the
//! characterization methods ([`method`]) and the coupled loop ([`characterize`]), load × speed
//! studies ([`study`]) and their trend curves ([`trends`]), the contact law made dimensionless and
//! its map over the groups ([`law_map`]), the bearing as a force element for rotor simulations
//! ([`force_element`])
//! and its linearized coefficients over speed ([`coefficients`]), case files ([`io`]), and every
//! result as a typed record for JSON, CSV, Python and C ([`report`]; the schema is docs/results.md).
//! [`prelude`] has what a typical program needs.
//!
//! Units: SI everywhere inside the library (m, N, Pa, Pa·s, s, rad, rad/s). Conversions to
//! engineering units happen only at the edges (case files and human-readable tables).
#![warn(missing_docs)]

pub mod bearing;
pub mod budget;
pub mod case;
pub mod characterize;
pub mod coefficients;
pub mod contact;
pub mod contact_law;
pub mod csv;
pub mod ehl;
pub mod error;
pub mod fit;
pub mod force_element;
pub mod hertz;
pub mod io;
pub mod law_map;
pub mod lubrication;
pub mod material;
pub mod method;
pub mod oil;
pub mod plausibility;
pub mod report;
pub mod rotor;
pub mod study;
pub mod trends;

pub use contact_law::{ContactLaw, HertzLaw};
pub use error::{Error, Result};

/// What a program that characterizes a bearing and uses it in a rotor model needs, in one import.
pub mod prelude {
    pub use crate::bearing::{Bearing, RaceControl};
    pub use crate::case::Case;
    pub use crate::characterize::{
        characterize_bearing, BearingCharacterization, CharacterizeSettings,
    };
    pub use crate::coefficients::SpeedCoefficients;
    pub use crate::force_element::{
        ElementInput, ElementOutput, ElementState, ForceElement, LawElement, LoadInterpolatedLaw,
        TrendForceElement,
    };
    pub use crate::io::{read_case, read_study, FsStore};
    pub use crate::method::Method;
    pub use crate::study::{finish_study, run_study, RunOptions, Shard, Study};
}

// The README's Rust code blocks are compiled as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
struct ReadmeDoctests;
