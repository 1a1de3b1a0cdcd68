//! `ehl-bearing ehl`: one EHL contact (placeholder).
pub const PLACEHOLDER: () = ();
