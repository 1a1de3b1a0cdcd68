//! The crate error: one variant per module, each carrying the module's own error.

use thiserror::Error;

/// Any error of the library.
#[derive(Debug, Error)]
pub enum Error {
    /// Hertz contact.
    #[error(transparent)]
    Hertz(#[from] crate::hertz::HertzError),
    /// Bearing model and equilibrium.
    #[error(transparent)]
    Bearing(#[from] crate::bearing::BearingError),
    /// Case files and other inputs.
    #[error(transparent)]
    Input(#[from] crate::case::InputError),
    /// EHL contact solver.
    #[error(transparent)]
    Ehl(#[from] crate::ehl::EhlError),
    /// Contact-law fit.
    #[error(transparent)]
    Fit(#[from] crate::fit::FitError),
    /// Characterization methods and their settings.
    #[error(transparent)]
    Method(#[from] crate::method::MethodError),
    /// Characterization loop and trend curves.
    #[error(transparent)]
    Characterize(#[from] crate::characterize::CharacterizeError),
    /// Rotor model and time response.
    #[error(transparent)]
    Rotor(#[from] crate::rotor::RotorError),
    /// Dimensionless laws and their map.
    #[error(transparent)]
    LawMap(#[from] crate::law_map::LawMapError),
    /// Running, merging and storing studies.
    #[error(transparent)]
    Study(#[from] crate::study::StudyError),
}

/// Result with the crate error.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A trend error is a characterization error (as before the trend model had its own module).
impl From<crate::trends::TrendError> for Error {
    fn from(e: crate::trends::TrendError) -> Self {
        Error::Characterize(crate::characterize::CharacterizeError::Trend(e))
    }
}

/// The message of a caught panic's payload (`std::panic::catch_unwind`): the `&str` or `String`
/// it was raised with, else "unknown panic". For the foreign-language layers (C, FMI), which
/// turn every panic into an error status instead of unwinding into the caller.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}
