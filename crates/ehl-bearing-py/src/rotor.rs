//! Rotor time response (bindings of `ehl_bearing::rotor`): registered once the integrator lands.

use pyo3::prelude::*;

pub(crate) fn register(_m: &Bound<'_, PyModule>) -> PyResult<()> {
    Ok(())
}
