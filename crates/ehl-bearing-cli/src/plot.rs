//! Plots: SVG and PNG (placeholder).
pub const PLACEHOLDER: () = ();
