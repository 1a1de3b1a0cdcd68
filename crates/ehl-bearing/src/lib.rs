//! # ehl-bearing
//!
//! Lubricated contacts of angular-contact ball bearings: a quasi-static 5-DOF bearing model
//! ([`bearing`]), Hertz elliptical contacts ([`hertz`]), an elastohydrodynamic point-contact solver
//! ([`ehl`]), a Levenberg–Marquardt fit of the nonlinear contact law Q = K·δ^d + ΔF ([`fit`]), and
//! case files ([`io`]).
//!
//! Units: SI everywhere inside the library (m, N, Pa, Pa·s, s, rad, rad/s). Conversions to
//! engineering units happen only at the edges (case files and human-readable tables).
#![warn(missing_docs)]

pub mod bearing;
pub mod characterize;
pub mod contact;
pub mod contact_law;
pub mod ehl;
pub mod error;
pub mod fit;
pub mod force_element;
pub mod hertz;
pub mod io;
pub mod material;
pub mod method;
pub mod study;

pub use contact_law::{ContactLaw, HertzLaw};
pub use error::{Error, Result};
