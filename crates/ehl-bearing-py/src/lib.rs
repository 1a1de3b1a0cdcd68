//! Python bindings of `ehl-bearing` (module `ehl_bearing._native`; the Python package
//! `ehl_bearing` re-exports and documents it). Results with many fields come back as Python
//! dicts built directly from the library's typed reports (`ehl_bearing::report`: the keys of the
//! command line's JSON, SI units; docs/results.md), matrices and vectors as numpy arrays. Long computations
//! release the GIL; progress callbacks re-acquire it.

// pyo3 0.22's macros expand `?` on PyResult into a PyErr → PyErr conversion that clippy flags in
// the user's code (a known false positive of pyo3 0.22's macros, gone in later pyo3).
#![allow(clippy::useless_conversion)]

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::case::Case;
use ehl_bearing::characterize::{
    characterize_bearing_with_control, BearingCharacterization, CharacterizeSettings,
};
use ehl_bearing::force_element::{
    ElementInput, ElementOutput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::{case_from_table, parse_case, read_case, read_study, FsStore};
use ehl_bearing::report::{
    CharacterizationReport, CoefficientsReport, EhlReport, EquilibriumReport, ProgressEvent,
    SpeedProgressEvent, StudyEventReport,
};
use ehl_bearing::study::{finish_study, run_study, RunOptions, StudyEvent};
use numpy::{
    AllowTypeChange, PyArray1, PyArray2, PyArrayLike1, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::create_exception;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

mod rotor;

create_exception!(
    _native,
    EhlBearingError,
    PyValueError,
    "An error of the ehl-bearing library (invalid input, a solver that did not converge, a file \
     that could not be read); the message is the library's."
);

/// A library error as a Python `EhlBearingError` with the library's message.
pub(crate) fn err<E: std::fmt::Display>(e: E) -> PyErr {
    EhlBearingError::new_err(e.to_string())
}

/// A typed report as Python objects, built directly from it (no text in between): records as
/// dicts with the report's keys, sequences (fixed-size arrays too) as lists, numbers as floats
/// and ints, absent values as None: what the command line's JSON of the same report reads as.
pub(crate) fn to_py<T: serde::Serialize + ?Sized>(py: Python<'_>, v: &T) -> PyResult<PyObject> {
    let obj = pythonize::pythonize(py, v).map_err(err)?;
    Ok(tuples_as_lists(&obj)?.unbind())
}

/// `obj` with every tuple (pythonize's form of a fixed-size array such as a 5×5 stiffness) made
/// a list, in place where it is in a dict or a list.
fn tuples_as_lists<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    use pyo3::types::{PyList, PyTuple};
    if let Ok(t) = obj.downcast::<PyTuple>() {
        let items = t
            .iter()
            .map(|x| tuples_as_lists(&x))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(PyList::new_bound(obj.py(), items).into_any());
    }
    if let Ok(l) = obj.downcast::<PyList>() {
        for i in 0..l.len() {
            let x = l.get_item(i)?;
            let y = tuples_as_lists(&x)?;
            if !y.is(&x) {
                l.set_item(i, y)?;
            }
        }
    } else if let Ok(d) = obj.downcast::<PyDict>() {
        let items: Vec<_> = d.iter().collect();
        for (k, x) in items {
            let y = tuples_as_lists(&x)?;
            if !y.is(&x) {
                d.set_item(k, y)?;
            }
        }
    }
    Ok(obj.clone())
}

/// A dict read back into a typed report (`what` names it in the error).
fn from_report<T: serde::de::DeserializeOwned>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<T> {
    pythonize::depythonize(obj).map_err(|e| err(format!("{what}: {e}")))
}

/// A case dict (text keys; lists and tuples, bools, ints, floats, text, numpy scalars and 0-d
/// arrays) as a TOML value, walked directly: an unsupported value, None (TOML has no null) or a
/// number that is not finite is an error naming its key path (`bearing.ball_diameter_mm = NaN`).
fn from_py(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyString, PyTuple};
    let at = |p: &str| {
        if p.is_empty() {
            "<dict>".to_string()
        } else {
            p.to_string()
        }
    };
    if let Ok(d) = obj.downcast::<PyDict>() {
        let mut map = toml::Table::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                err(format!(
                    "{}: key {} is not text (keys are the case file's names, e.g. \"ball_count\")",
                    at(path),
                    k.repr().map_or_else(|_| "?".into(), |r| r.to_string())
                ))
            })?;
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            map.insert(key, from_py(&v, &sub)?);
        }
        return Ok(toml::Value::Table(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, v) in obj.iter()?.enumerate() {
            out.push(from_py(&v?, &format!("{path}[{i}]"))?);
        }
        return Ok(toml::Value::Array(out));
    }
    if obj.is_none() {
        return Err(err(format!(
            "{} = None: give a value, or leave the key out for its default",
            at(path)
        )));
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        let i: i64 = obj
            .extract()
            .map_err(|_| err(format!("{} = {obj}: an integer beyond 64 bits", at(path))))?;
        return Ok(toml::Value::Integer(i));
    }
    if obj.is_instance_of::<PyFloat>() {
        let x: f64 = obj.extract()?;
        if !x.is_finite() {
            return Err(err(format!("{} = {x}: expected a finite number", at(path))));
        }
        return Ok(toml::Value::Float(x));
    }
    // numpy scalars (int64, float32, bool_, …) and 0-d arrays: their Python value.
    if obj.hasattr("item")? && obj.hasattr("dtype")? {
        let item = obj.call_method0("item")?;
        if !item.hasattr("dtype")? {
            return from_py(&item, path);
        }
    }
    Err(err(format!(
        "{} = {}: expected a number, text, bool, list or dict (a {})",
        at(path),
        obj.repr().map_or_else(|_| "?".into(), |r| r.to_string()),
        obj.get_type()
            .name()
            .map_or_else(|_| "?".into(), |n| n.to_string())
    )))
}

/// Call a Python progress callback with a dict, from any thread; errors are printed, not raised
/// (a progress display must not abort a computation).
fn report<T: serde::Serialize>(callback: &Option<PyObject>, event: &T) {
    if let Some(cb) = callback {
        Python::with_gil(|py| {
            let r = to_py(py, event).and_then(|d| cb.call1(py, (d,)));
            if let Err(e) = r {
                e.print(py);
            }
        });
    }
}

// ---------------------------------------------------------------------------------------------
// Case
// ---------------------------------------------------------------------------------------------

/// A validated bearing case (geometry, materials, lubricant, operating point, solver settings),
/// SI inside. Build with `Case.from_file`, `Case.from_toml` or `Case.from_dict`.
#[pyclass(module = "ehl_bearing._native", name = "Case", frozen)]
#[derive(Clone)]
pub struct PyCase {
    pub(crate) case: Case,
}

#[pymethods]
impl PyCase {
    /// Read and validate a case file (TOML, e.g. `examples/7006.toml`).
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        Ok(PyCase {
            case: read_case(&path).map_err(err)?,
        })
    }

    /// Parse and validate a case from TOML text (`origin` names it in error messages).
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_toml(text: &str, origin: &str) -> PyResult<Self> {
        Ok(PyCase {
            case: parse_case(text, origin).map_err(err)?,
        })
    }

    /// Build a case from a dict with the case file's tables and keys (units in the key names,
    /// as in the file: `{"bearing": {"ball_count": 11, "ball_diameter_mm": 7.0, ...},
    /// "operating": {"inner_speed_rpm": 5000.0, ...}}`); validated by the same parser.
    #[staticmethod]
    fn from_dict(values: &Bound<'_, PyAny>) -> PyResult<Self> {
        let table = match from_py(values, "")? {
            toml::Value::Table(t) => t,
            other => {
                return Err(err(format!(
                    "<dict>: a case is a dict of the case file's tables, got a {}",
                    other.type_str()
                )))
            }
        };
        Ok(PyCase {
            case: case_from_table(table, "<dict>").map_err(err)?,
        })
    }

    /// The bearing's name, if the case gives one.
    #[getter]
    fn name(&self) -> Option<String> {
        self.case.name.clone()
    }

    /// Inner-ring speed, rad/s.
    #[getter]
    fn inner_speed_rad_s(&self) -> f64 {
        self.case.operating.inner_speed
    }

    /// Outer-ring speed, rad/s.
    #[getter]
    fn outer_speed_rad_s(&self) -> f64 {
        self.case.operating.outer_speed
    }

    /// Number of balls Z.
    #[getter]
    fn ball_count(&self) -> usize {
        self.case.bearing.geometry.ball_count
    }

    /// Pitch diameter d_m, m.
    #[getter]
    fn pitch_diameter_m(&self) -> f64 {
        self.case.bearing.geometry.pitch_diameter
    }

    /// Ball diameter D, m.
    #[getter]
    fn ball_diameter_m(&self) -> f64 {
        self.case.bearing.geometry.ball_diameter
    }

    /// Free contact angle, rad.
    #[getter]
    fn contact_angle_rad(&self) -> f64 {
        self.case.bearing.geometry.free_contact_angle
    }

    /// The same case with the inner-ring speed set to `rpm`.
    /// Refused like the case file's own speed: not finite, or beyond the plausibility rules
    /// (speed factor n·d_m), with the key, the value and the range.
    fn with_inner_speed_rpm(&self, rpm: f64) -> PyResult<Self> {
        if !rpm.is_finite() {
            return Err(err(format!(
                "inner speed {rpm} rpm: expected a finite speed"
            )));
        }
        let mut c = self.case.clone();
        c.operating.inner_speed = rpm * PI / 30.0;
        ehl_bearing::plausibility::check_case(&c).map_err(|e| {
            err(format!(
                "with_inner_speed_rpm({}): {e}",
                ehl_bearing::case::number_text(rpm)
            ))
        })?;
        Ok(PyCase { case: c })
    }

    fn __repr__(&self) -> String {
        format!(
            "Case({:?}, Z={}, inner speed {:.1} rpm)",
            self.case.name.as_deref().unwrap_or("unnamed"),
            self.case.bearing.geometry.ball_count,
            self.case.operating.inner_speed * 30.0 / PI
        )
    }
}

// ---------------------------------------------------------------------------------------------
// Equilibrium, EHL, contact, characterize
// ---------------------------------------------------------------------------------------------

/// Dry (Hertz) quasi-static equilibrium of the case's bearing under its loads: a dict with the
/// displacements, reactions, 5×5 stiffness and every ball's contact states (SI).
#[pyfunction]
fn equilibrium(py: Python<'_>, case: &PyCase) -> PyResult<PyObject> {
    let c = &case.case;
    let eq = py
        .allow_threads(|| {
            let laws = ContactLaws::hertz(&c.bearing)?;
            solve_equilibrium(&c.bearing, &laws, &c.operating, &c.settings)
        })
        .map_err(err)?;
    to_py(py, &EquilibriumReport::from(&eq))
}

/// Steady EHL solution of one point contact given as contact-file TOML text (the `ehl`
/// command's input: `load_n`, `rx_mm`, `ry_mm`, `sum_velocity_m_s`, lubricant, materials).
/// Returns a dict (SI): film thicknesses, pressure, Moes parameters, convergence; with
/// `fields=True` also the pressure and film fields on the grid.
#[pyfunction]
#[pyo3(signature = (contact_toml, grid = None, fields = false))]
fn ehl(
    py: Python<'_>,
    contact_toml: &str,
    grid: Option<usize>,
    fields: bool,
) -> PyResult<PyObject> {
    use ehl_bearing::ehl::{solve_steady, EhlSettings};
    use ehl_bearing::io::contact::parse_contact_file;
    let file = parse_contact_file(contact_toml).map_err(err)?;
    let mut s = EhlSettings::default();
    if let Some(g) = grid {
        s.grid = g;
    }
    let sol = py
        .allow_threads(|| solve_steady(&file.contact, &s))
        .map_err(err)?;
    to_py(py, &EhlReport::new(&sol, fields))
}

/// Characterize one EHL point contact (contact-file TOML text) with `method`
/// ("quasi-static" or "harmonic"; the harmonic method needs the ball mass from the file):
/// the fitted law Q = K·δ^d + ΔF (+ c·δ̇) and its samples, as a dict (SI). The quasi-static
/// method also gives the Richardson estimate of the central film and the approach at w0
/// (`film`, as the `contact` command; `film_extrapolation=False` skips its extra solution).
/// `grid`: points per side of the EHL solutions (2^k + 1; default 129), as `contact --grid`.
/// `method_options`: the method's other settings as a case file's `[method_options]` (e.g.
/// `{"steps_per_period": 32, "step_tol_film": 7e-7}` for the harmonic method; docs/study.md),
/// checked by the same parser: an unknown key or a value out of range is an error naming
/// `method_options.KEY`, the value and the range.
/// The dict has the keys of `contact --json` (docs/results.md).
#[pyfunction]
#[pyo3(signature = (contact_toml, method = "quasi-static", film_extrapolation = true, grid = None, method_options = None))]
fn contact(
    py: Python<'_>,
    contact_toml: &str,
    method: &str,
    film_extrapolation: bool,
    grid: Option<usize>,
    method_options: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyObject> {
    use ehl_bearing::contact::{characterize_harmonic, characterize_quasi_static};
    use ehl_bearing::io::contact::parse_contact_file;
    use ehl_bearing::method::Method;
    let file = parse_contact_file(contact_toml).map_err(err)?;
    let mut options = match method_options
        .map(|o| from_py(o, "method_options"))
        .transpose()?
    {
        None => toml::Table::new(),
        Some(toml::Value::Table(t)) => t,
        Some(other) => {
            return Err(err(format!(
                "method_options: a dict of the method's settings, got a {}",
                other.type_str()
            )))
        }
    };
    if grid.is_some() && options.contains_key("grid") {
        return Err(err(
            "grid is given twice (grid= and method_options[\"grid\"]): give it once",
        ));
    }
    if let Some(g) = grid {
        options.insert(
            "grid".into(),
            toml::Value::Integer(g.min(i64::MAX as usize) as i64),
        );
    }
    let m = Method::parse(method, Some(&options))
        .map_err(|e| err(e.to_string().replace("method_options.grid", "grid")))?;
    let fit = py
        .allow_threads(|| match m {
            Method::Harmonic(s) => match file.ball_mass.or(s.mass) {
                Some(mass) => characterize_harmonic(&file.contact, mass, &s).map_err(err),
                None => Err(err(
                    "the harmonic method needs the ball's mass: give ball_mass_kg or ball_diameter_mm in the contact file",
                )),
            },
            Method::QuasiStatic(s) => {
                let s = ehl_bearing::contact::QuasiStaticSettings {
                    film_extrapolation,
                    ..s
                };
                characterize_quasi_static(&file.contact, &s).map_err(err)
            }
            other => Err(err(format!(
                "method {other} does not characterize a single contact"
            ))),
        })?;
    to_py(py, &fit)
}

/// The coupled characterization of a case (fitted laws, their equilibrium, the iterations).
/// `report()` gives the dict of `characterization.json`; `law_element()` the bearing with the
/// fitted laws as a force element.
#[pyclass(module = "ehl_bearing._native", frozen)]
pub struct Characterization {
    case: Case,
    inner: Arc<BearingCharacterization>,
}

#[pymethods]
impl Characterization {
    /// The characterization as a dict (the `characterize` command's JSON, SI).
    #[pyo3(signature = (timing = false))]
    fn report(&self, py: Python<'_>, timing: bool) -> PyResult<PyObject> {
        to_py(py, &self.inner.report(timing))
    }

    /// Whether the coupled loop converged.
    #[getter]
    fn converged(&self) -> bool {
        self.inner.converged
    }

    /// Equilibrium ring displacements x, y, z (m) and tilts θy, θz (rad), shape (5,).
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice_bound(py, &self.inner.equilibrium.displacement)
    }

    /// Lubricated stiffness at the equilibrium, (5, 5), SI.
    #[getter]
    fn stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.inner.ehl_stiffness())
    }

    /// Dry Hertz stiffness at the same loads, (5, 5), SI.
    #[getter]
    fn dry_stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.inner.dry_stiffness())
    }

    /// The bearing with the fitted laws as a force element (`LawElement`): each contact's law
    /// fixed at its position in the case, or with `by_load=True` every ball taking, at any cage
    /// angle, the law of the load it carries (interpolated over the characterized laws of its
    /// raceway): the form for rolling cages and ball-pass studies.
    #[pyo3(signature = (by_load = false))]
    fn law_element(&self, by_load: bool) -> PyResult<PyLawElement> {
        let e = if by_load {
            LawElement::by_load_from_characterization(&self.case, &self.inner)
        } else {
            LawElement::from_characterization(&self.case, &self.inner)
        }
        .map_err(err)?;
        Ok(PyLawElement::new(Arc::new(e), false, &self.case))
    }
}

fn method_of(case: &Case, method: Option<&str>) -> PyResult<ehl_bearing::method::Method> {
    case.method_or(method).map_err(err)
}

/// Characterize the bearing of `case` with `method` (default: the case file's method, else
/// quasi-static; "harmonic" also fits each contact's damping): the coupled loop of EHL contact
/// characterizations and bearing equilibrium. `progress`, if given, is called with a dict per
/// event (`{"event": "iteration_started" | "contact_done" | "iteration_done", ...}`), from worker
/// threads. An exception raised in it, or Ctrl-C, stops the run: no further contact starts, and
/// the exception is raised once those running finish (seconds). `time_limit_s` bounds the wall
/// time (the error gives the iterations done). Releases the GIL. About 15 s for the seed case on
/// 2 cores.
#[pyfunction]
#[pyo3(signature = (case, method = None, progress = None, time_limit_s = None))]
fn characterize(
    py: Python<'_>,
    case: &PyCase,
    method: Option<&str>,
    progress: Option<PyObject>,
    time_limit_s: Option<f64>,
) -> PyResult<Characterization> {
    let progress = callable(py, progress, "progress")?;
    let c = case.case.clone();
    let m = method_of(&c, method)?;
    let settings = CharacterizeSettings::default();
    let mut deadline = None;
    if let Some(t) = time_limit_s {
        deadline = Some(
            ehl_bearing::budget::Deadline::after_seconds(t).ok_or_else(|| {
                err(format!(
                    "time_limit_s = {t}: expected a finite number of seconds > 0 (at most a year)"
                ))
            })?,
        );
    }
    let control = Control::new(progress);
    let r = py.allow_threads(|| {
        characterize_bearing_with_control(&c, &m, &settings, deadline, &|p| {
            control.event(&ProgressEvent::from(&p))
        })
    });
    control.finish()?;
    Ok(Characterization {
        case: c,
        inner: Arc::new(r.map_err(err)?),
    })
}

/// A progress callback that can stop a run: Ctrl-C or an exception raised in the callback asks
/// the library to stop ([`std::ops::ControlFlow::Break`]); [`Control::finish`] then raises it.
struct Control {
    progress: Option<PyObject>,
    raised: Mutex<Option<PyErr>>,
}

impl Control {
    fn new(progress: Option<PyObject>) -> Self {
        Control {
            progress,
            raised: Mutex::new(None),
        }
    }

    /// Check Ctrl-C and call the callback with `event` (from any thread).
    fn event<T: serde::Serialize>(&self, event: &T) -> std::ops::ControlFlow<()> {
        let r = Python::with_gil(|py| {
            py.check_signals()?;
            if let Some(cb) = &self.progress {
                cb.call1(py, (to_py(py, event)?,))?;
            }
            Ok::<(), PyErr>(())
        });
        match r {
            Ok(()) => std::ops::ControlFlow::Continue(()),
            Err(e) => {
                self.raised
                    .lock()
                    .unwrap_or_else(|p| p.into_inner())
                    .get_or_insert(e);
                std::ops::ControlFlow::Break(())
            }
        }
    }

    /// The first exception the callback raised (or KeyboardInterrupt), if any.
    fn finish(self) -> PyResult<()> {
        match self.raised.into_inner().unwrap_or_else(|p| p.into_inner()) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

/// `value` if it is None or callable; otherwise a TypeError naming the argument.
fn callable(py: Python<'_>, value: Option<PyObject>, what: &str) -> PyResult<Option<PyObject>> {
    match value {
        Some(v) if !v.bind(py).is_callable() => Err(PyTypeError::new_err(format!(
            "{what}: expected a function called with one dict per event, or None; got {}",
            v.bind(py)
                .get_type()
                .name()
                .map_or_else(|_| "?".into(), |n| n.to_string())
        ))),
        v => Ok(v),
    }
}

/// What `study()` returns (a dict with these keys).
#[derive(serde::Serialize)]
struct StudySummary {
    points: usize,
    computed: usize,
    loaded: usize,
    failed: Vec<FailedPoint>,
    not_converged: usize,
    results_csv: String,
    points_csv: String,
    trends_json: Option<String>,
    trend_error: Option<String>,
    worst_trend_error: f64,
    lubrication: Option<ehl_bearing::study::LubricationSummary>,
}

/// A study point that failed, in `study()`'s summary.
#[derive(serde::Serialize)]
struct FailedPoint {
    inner_speed_rpm: f64,
    load_scale: f64,
    error: String,
}

/// Run a load × speed study file into `output_dir` (resumable point files, `results.csv`,
/// `points.csv`, `trends.json` when the trends fit): all points, with `method` overriding the
/// file's. When the case describes its oil or gives roughness, both tables carry the lubrication
/// figures (film, Λ, κ, thermal reduction; docs/lubricant.md §2.5) and the summary's
/// `lubrication` gives the smallest Λ and largest thermal reduction with where they occur (None
/// otherwise). `progress` is called with a dict per event (`planned`, `point_started`, `loop`,
/// `point_done`); an exception raised in it is printed and the study goes on (finished points
/// are kept on disk, so a study stopped by other means resumes where it stopped). Returns a
/// summary dict with the paths written and the trend model's JSON path (None if the trends could
/// not be fitted, with the reason). Releases the GIL.
#[pyfunction]
#[pyo3(signature = (study_file, output_dir, method = None, progress = None))]
fn study(
    py: Python<'_>,
    study_file: std::path::PathBuf,
    output_dir: std::path::PathBuf,
    method: Option<&str>,
    progress: Option<PyObject>,
) -> PyResult<PyObject> {
    let progress = callable(py, progress, "progress")?;
    let mut s = read_study(&study_file).map_err(err)?;
    if let Some(m) = method {
        s.set_method(m).map_err(err)?;
    }
    let store = FsStore::create(&output_dir).map_err(err)?;
    let summary = py.allow_threads(|| -> PyResult<StudySummary> {
        let events = |e: StudyEvent| report(&progress, &StudyEventReport::from(&e));
        let run = run_study(&s, &store, &RunOptions::default(), &events).map_err(err)?;
        // finish_study writes results.csv, points.csv and trends.json (if the trends fit).
        let out = finish_study(&s, &store).map_err(err)?;
        let path = |name: &str| store.dir().join(name).display().to_string();
        Ok(StudySummary {
            points: run.points,
            computed: run.computed,
            loaded: run.loaded,
            failed: out
                .failed
                .iter()
                .map(|(p, e)| FailedPoint {
                    inner_speed_rpm: p.inner_speed_rpm,
                    load_scale: p.load_scale,
                    error: e.clone(),
                })
                .collect(),
            not_converged: out.not_converged(),
            results_csv: path("results.csv"),
            points_csv: path("points.csv"),
            trends_json: out.trends.is_ok().then(|| path("trends.json")),
            trend_error: out.trends.as_ref().err().cloned(),
            worst_trend_error: out.worst_trend_error(),
            lubrication: out.lubrication_summary(),
        })
    })?;
    to_py(py, &summary)
}

// ---------------------------------------------------------------------------------------------
// Force elements
// ---------------------------------------------------------------------------------------------

pub(crate) fn mat<'py>(py: Python<'py>, m: &[[f64; 5]; 5]) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = m.iter().map(|r| r.to_vec()).collect();
    PyArray2::from_vec2_bound(py, &rows).expect("5×5 rows")
}

fn vec5(a: &PyReadonlyArray1<'_, f64>, what: &str) -> PyResult<[f64; 5]> {
    // Any layout (e.g. a row or column of a 2-D array): copy element-wise.
    let s: Vec<f64> = a.as_array().iter().copied().collect();
    let n = s.len();
    s.try_into()
        .map_err(|_| err(format!("{what}: expected 5 values, got {n}")))
}

/// Shared implementation of the Python force-element classes: the element and one warm-start
/// state per Python object.
pub(crate) struct ElementCore {
    pub(crate) element: Arc<dyn ForceElement>,
    state: Mutex<ElementState>,
}

impl ElementCore {
    fn new(element: Arc<dyn ForceElement>) -> Self {
        ElementCore {
            element,
            state: Mutex::new(ElementState::default()),
        }
    }

    // The arguments are the Python keyword interface.
    #[allow(clippy::too_many_arguments)]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        displacement: PyArrayLike1<'_, f64, AllowTypeChange>,
        velocity: Option<PyArrayLike1<'_, f64, AllowTypeChange>>,
        inner_speed_rad_s: f64,
        outer_speed_rad_s: f64,
        cage_angle_rad: f64,
        full: bool,
    ) -> PyResult<PyObject> {
        let q = vec5(&displacement, "displacement")?;
        let v = match &velocity {
            Some(v) => vec5(v, "velocity")?,
            None => [0.0; 5],
        };
        let input = ElementInput {
            displacement: q,
            velocity: v,
            inner_speed: inner_speed_rad_s,
            outer_speed: outer_speed_rad_s,
            cage_angle: cage_angle_rad,
        };
        let out: ElementOutput = py
            .allow_threads(|| {
                let mut st = self.state.lock().unwrap_or_else(|p| p.into_inner());
                self.element.evaluate(&input, &mut st)
            })
            .map_err(err)?;
        if !out.overloaded.is_empty() {
            let (j, race) = out.overloaded[0];
            let msg = format!(
                "{} contact(s) beyond {} % of the ball diameter (first: ball {j} {race:?}, \
                 approach {:.3e} m, load {:.4e} N) at displacement {q:?}: no bearing survives \
                 this; the numbers are returned as computed (full=True lists them in \
                 `overloaded`)",
                out.overloaded.len(),
                ehl_bearing::force_element::OVERLOAD_DEFLECTION_RATIO * 100.0,
                out.approaches[j][race as usize],
                out.loads[j][race as usize],
            );
            PyErr::warn_bound(
                py,
                &py.get_type_bound::<pyo3::exceptions::PyRuntimeWarning>(),
                &msg,
                1,
            )?;
        }
        let r = PyArray1::from_slice_bound(py, &out.reaction);
        let k = mat(py, &out.stiffness);
        let c = mat(py, &out.damping);
        if !full {
            return Ok((r, k, c).into_py(py));
        }
        let d = PyDict::new_bound(py);
        d.set_item("reaction", r)?;
        d.set_item("stiffness", k)?;
        d.set_item("damping", c)?;
        let loads: Vec<Vec<f64>> = out.loads.iter().map(|l| l.to_vec()).collect();
        let appr: Vec<Vec<f64>> = out.approaches.iter().map(|l| l.to_vec()).collect();
        d.set_item("loads", PyArray2::from_vec2_bound(py, &loads).map_err(err)?)?;
        d.set_item(
            "approaches",
            PyArray2::from_vec2_bound(py, &appr).map_err(err)?,
        )?;
        let outside: Vec<(usize, String)> = out
            .outside_range
            .iter()
            .map(|(b, r)| (*b, format!("{r:?}").to_lowercase()))
            .collect();
        d.set_item("outside_range", outside)?;
        let overloaded: Vec<(usize, String)> = out
            .overloaded
            .iter()
            .map(|(b, r)| (*b, format!("{r:?}").to_lowercase()))
            .collect();
        d.set_item("overloaded", overloaded)?;
        d.set_item("speed_outside", out.speed_outside)?;
        d.set_item(
            "orbital_speeds",
            PyArray1::from_slice_bound(py, &out.orbital_speeds),
        )?;
        d.set_item("cage_speed", out.cage_speed)?;
        Ok(d.into_any().unbind())
    }
}

macro_rules! element_methods {
    ($t:ty) => {
        #[pymethods]
        impl $t {
            /// Evaluate the bearing at ring displacement `displacement` (x, y, z in m; θy, θz in
            /// rad; inner relative to outer ring, x axial), rates `velocity` (m/s, rad/s; default
            /// zero), ring speeds (rad/s) and cage angle (rad; ball j at 2πj/Z + cage angle).
            /// Returns `(reaction (5,), stiffness (5, 5), damping (5, 5))` as numpy arrays: the
            /// load on the inner ring (N, N·m; the bearing acts on the shaft with the opposite),
            /// ∂reaction/∂q and ∂reaction/∂q̇ (SI). With `full=True` a dict that also has the
            /// per-ball contact `loads` and `approaches` (Z, 2) [inner, outer] and the range flags.
            /// The object keeps warm starts between calls (results do not depend on them beyond
            /// the solvers' tolerances). Raises `EhlBearingError` if a ball's equilibrium fails.
            #[pyo3(signature = (displacement, velocity = None, inner_speed_rad_s = 0.0, outer_speed_rad_s = 0.0, cage_angle_rad = 0.0, full = false))]
            // The arguments are the Python keyword interface.
            #[allow(clippy::too_many_arguments)]
            fn evaluate(
                &self,
                py: Python<'_>,
                displacement: PyArrayLike1<'_, f64, AllowTypeChange>,
                velocity: Option<PyArrayLike1<'_, f64, AllowTypeChange>>,
                inner_speed_rad_s: f64,
                outer_speed_rad_s: f64,
                cage_angle_rad: f64,
                full: bool,
            ) -> PyResult<PyObject> {
                self.core.evaluate(
                    py,
                    displacement,
                    velocity,
                    inner_speed_rad_s,
                    outer_speed_rad_s,
                    cage_angle_rad,
                    full,
                )
            }

            /// No-load cage speed at ring speeds `inner_speed_rad_s`, `outer_speed_rad_s`, rad/s:
            /// pure rolling at the free contact angle, ω_c = ½·[ω_i·(1 − γ) + ω_o·(1 + γ)],
            /// γ = D·cos α0/d_m. At an operating point the balls orbit faster (their operating
            /// contact angles): use `cage_speed_at`.
            #[pyo3(signature = (inner_speed_rad_s, outer_speed_rad_s = 0.0))]
            fn cage_speed(&self, inner_speed_rad_s: f64, outer_speed_rad_s: f64) -> PyResult<f64> {
                for (name, v) in [
                    ("inner_speed_rad_s", inner_speed_rad_s),
                    ("outer_speed_rad_s", outer_speed_rad_s),
                ] {
                    if !v.is_finite() {
                        return Err(err(format!("{name} = {v}: expected a finite speed in rad/s")));
                    }
                }
                Ok(self
                    .core
                    .element
                    .cage_speed(inner_speed_rad_s, outer_speed_rad_s))
            }

            /// Cage speed at the operating state (ring displacement `displacement` in m and rad,
            /// ring speeds in rad/s, cage angle in rad), rad/s: the load-weighted mean orbital
            /// speed of the balls in the bearing model (the `cage_speed` of
            /// `evaluate(..., full=True)`; its `orbital_speeds` are the balls' own). The ball-pass
            /// frequency is Z times it over 2π.
            #[pyo3(signature = (displacement, inner_speed_rad_s, outer_speed_rad_s = 0.0, cage_angle_rad = 0.0))]
            fn cage_speed_at(
                &self,
                py: Python<'_>,
                displacement: PyArrayLike1<'_, f64, AllowTypeChange>,
                inner_speed_rad_s: f64,
                outer_speed_rad_s: f64,
                cage_angle_rad: f64,
            ) -> PyResult<f64> {
                let input = ElementInput {
                    displacement: vec5(&displacement, "displacement")?,
                    velocity: [0.0; 5],
                    inner_speed: inner_speed_rad_s,
                    outer_speed: outer_speed_rad_s,
                    cage_angle: cage_angle_rad,
                };
                py.allow_threads(|| {
                    let mut st = self.core.state.lock().unwrap_or_else(|p| p.into_inner());
                    self.core.element.cage_speed_at(&input, &mut st)
                })
                .map_err(err)
            }

            /// Number of balls Z.
            #[getter]
            fn ball_count(&self) -> usize {
                self.core.element.ball_count()
            }

            /// Pitch diameter d_m, m.
            #[getter]
            fn pitch_diameter_m(&self) -> f64 {
                self.core.element.bearing().geometry.pitch_diameter
            }

            /// Equilibrium of the element under `case`'s loads (its load-controlled DOFs; the
            /// others imposed) at the case's speeds, by Newton from the dry equilibrium: returns
            /// `(displacement (5,), stiffness (5, 5), damping (5, 5))`.
            fn equilibrium<'py>(
                &self,
                py: Python<'py>,
                case: &PyCase,
            ) -> PyResult<(
                Bound<'py, PyArray1<f64>>,
                Bound<'py, PyArray2<f64>>,
                Bound<'py, PyArray2<f64>>,
            )> {
                let c = &case.case;
                let e = self.core.element.clone();
                let (q, out) = py
                    .allow_threads(|| -> Result<_, ehl_bearing::Error> {
                        let laws = ContactLaws::hertz(&c.bearing)?;
                        let dry = solve_equilibrium(&c.bearing, &laws, &c.operating, &c.settings)?;
                        ehl_bearing::coefficients::element_equilibrium(
                            e.as_ref(),
                            c,
                            dry.displacement,
                        )
                    })
                    .map_err(err)?;
                Ok((
                    PyArray1::from_slice_bound(py, &q),
                    mat(py, &out.stiffness),
                    mat(py, &out.damping),
                ))
            }
        }
    };
}

/// A bearing whose contacts have fixed laws: dry Hertz (`LawElement.hertz(case)`) or the fitted
/// laws of a characterization (`Characterization.law_element()`), with each contact's damping
/// c·δ̇ where the harmonic method fitted one.
#[pyclass(module = "ehl_bearing._native", name = "LawElement", frozen)]
pub struct PyLawElement {
    pub(crate) core: ElementCore,
    #[pyo3(get)]
    /// Whether this is the dry Hertz element.
    dry: bool,
    /// The case the element was built for (its loads give the default preload offset).
    case: Case,
}

impl PyLawElement {
    fn new(e: Arc<LawElement>, dry: bool, case: &Case) -> Self {
        PyLawElement {
            core: ElementCore::new(e),
            dry,
            case: case.clone(),
        }
    }
}

#[pymethods]
impl PyLawElement {
    /// Dry Hertz laws for the bearing, race control and kinematics model of `case`.
    #[staticmethod]
    fn hertz(case: &PyCase) -> PyResult<Self> {
        Ok(Self::new(
            Arc::new(LawElement::hertz_case(&case.case).map_err(err)?),
            true,
            &case.case,
        ))
    }

    /// The case the element was built for (`hertz`, `from_report` or
    /// `Characterization.law_element`): its loads and speed are the element's own equilibrium
    /// (`equilibrium(element.case)`), e.g. the default preload offset of a rotor bearing.
    #[getter]
    fn case(&self) -> PyCase {
        PyCase {
            case: self.case.clone(),
        }
    }

    /// The fitted laws of a characterization report dict (a study point's `result` or
    /// `Characterization.report()`) for the bearing of `case`; `by_load=True` as in
    /// `Characterization.law_element` (laws by load, for rolling cages).
    #[staticmethod]
    #[pyo3(signature = (case, report, by_load = false))]
    fn from_report(case: &PyCase, report: &Bound<'_, PyAny>, by_load: bool) -> PyResult<Self> {
        let r: CharacterizationReport = from_report(report, "characterization report")?;
        let (bearing, rc) = (&case.case.bearing, case.case.operating.race_control);
        let e = if by_load {
            LawElement::by_load_from_report(bearing, rc, &r)
        } else {
            LawElement::from_report(bearing, rc, &r)
        }
        .map_err(err)?;
        Ok(Self::new(
            Arc::new(e.with_kinematics(case.case.settings.kinematics)),
            false,
            &case.case,
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "LawElement({}, Z={})",
            if self.dry { "dry Hertz" } else { "fitted laws" },
            self.core.element.ball_count()
        )
    }
}
element_methods!(PyLawElement);

/// The bearing with contact laws from a study's trend curves (`trends.json`): load- and
/// speed-dependent, no EHL run.
#[pyclass(module = "ehl_bearing._native", name = "TrendForceElement", frozen)]
pub struct PyTrendElement {
    pub(crate) core: ElementCore,
}

#[pymethods]
impl PyTrendElement {
    /// From trend JSON text (a study's `trends.json`).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let e = TrendForceElement::from_json(text).map_err(err)?;
        Ok(PyTrendElement {
            core: ElementCore::new(Arc::new(e)),
        })
    }

    /// From a trend file (a study's `trends.json`).
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        let text = ehl_bearing::io::read_text(&path).map_err(err)?;
        Self::from_json(&text)
    }

    fn __repr__(&self) -> String {
        format!("TrendForceElement(Z={})", self.core.element.ball_count())
    }
}
element_methods!(PyTrendElement);

/// The force element inside a Python element object (for the rotor model).
pub(crate) fn element_of(obj: &Bound<'_, PyAny>) -> PyResult<Arc<dyn ForceElement>> {
    if let Ok(e) = obj.downcast::<PyLawElement>() {
        return Ok(e.get().core.element.clone());
    }
    if let Ok(e) = obj.downcast::<PyTrendElement>() {
        return Ok(e.get().core.element.clone());
    }
    Err(err("expected a LawElement or TrendForceElement"))
}

// ---------------------------------------------------------------------------------------------
// Coefficients
// ---------------------------------------------------------------------------------------------

/// Linearized 5×5 stiffness and damping of the lubricated bearing of `case` at each inner-ring
/// speed in `speeds_rpm`: from the coupled characterization with `method` (default: the case's,
/// else quasi-static; "harmonic" gives damping) or, with `element`, from that force element's
/// equilibrium (e.g. a `TrendForceElement`: no EHL run). Returns a list of dicts (SI):
/// `inner_speed_rpm`, `inner_speed_rad_s`, `displacement`, `stiffness`, `damping`,
/// `dry_stiffness`, `converged`, `source`; matrices as nested lists in the order x, y, z, θy, θz.
/// `progress` as in `characterize` (its events carry `speed_index`); an exception raised in it, or
/// Ctrl-C, stops the run and is raised.
#[pyfunction]
#[pyo3(signature = (case, speeds_rpm, method = None, element = None, progress = None))]
fn coefficients(
    py: Python<'_>,
    case: &PyCase,
    speeds_rpm: Vec<f64>,
    method: Option<&str>,
    element: Option<&Bound<'_, PyAny>>,
    progress: Option<PyObject>,
) -> PyResult<PyObject> {
    let progress = callable(py, progress, "progress")?;
    let c = case.case.clone();
    let out = match element {
        Some(e) => {
            let e = element_of(e)?;
            py.allow_threads(|| {
                ehl_bearing::coefficients::from_element(&c, &speeds_rpm, e.as_ref(), "element")
            })
            .map_err(err)?
        }
        None => {
            let m = method_of(&c, method)?;
            let control = Control::new(progress);
            let r = py.allow_threads(|| {
                ehl_bearing::coefficients::from_characterization(
                    &c,
                    &speeds_rpm,
                    &m,
                    &CharacterizeSettings::default(),
                    &|i, p| control.event(&SpeedProgressEvent::new(i, &p)),
                )
            });
            control.finish()?;
            r.map_err(err)?
        }
    };
    to_py(py, &out)
}

/// ROSS's speed-dependent bearing table (CSV text: frequency in rad/s, kxx, kxy, kyx, kyy, cxx,
/// cxy, cyx, cyy, kzz, czz) of coefficient dicts from `coefficients`, in ROSS's axes (ROSS
/// x ← our y, y ← our z, z ← our x).
#[pyfunction]
fn ross_table_csv(coefficients: &Bound<'_, PyAny>) -> PyResult<String> {
    let c: Vec<CoefficientsReport> = from_report(coefficients, "coefficients")?;
    Ok(ehl_bearing::coefficients::ross_table_csv(&c))
}

/// Check a 2-D array's shape.
pub(crate) fn square(a: &PyReadonlyArray2<'_, f64>, n: usize, what: &str) -> PyResult<Vec<f64>> {
    let s = a.shape();
    if s != [n, n] {
        return Err(err(format!("{what}: expected shape ({n}, {n}), got {s:?}")));
    }
    Ok(a.as_array().iter().copied().collect())
}

/// The law maps embedded in the library, in the order a `method = "map"` query tries them: one
/// dict per map with the keys of `ehl-bearing law-map info --json` (`name`, `law`, `nodes`,
/// `cpu_seconds` in s, `nodes_not_converged`, `worst_node_rms_hat`, `worst_node_r_squared`, and
/// `spec`: the models, fixed groups, axes with `group`, `min`, `max`, `nodes`, `log`, and the
/// method's settings; groups dimensionless), docs/law_map.md §5.
#[pyfunction]
fn law_maps(py: Python<'_>) -> PyResult<PyObject> {
    let s = ehl_bearing::law_map::LawMap::embedded_summaries();
    to_py(py, &s)
}

/// The native module.
/// The keys of a result record, in order, for results Python builds as dicts of numpy arrays:
/// `"rotor_run"` (`RotorModel.simulate`) and `"rotor_static"` (`RotorModel.static_equilibrium`);
/// the other results reach Python from their records directly (docs/results.md).
#[pyfunction]
fn result_keys(kind: &str) -> PyResult<Vec<String>> {
    use ehl_bearing::report::{record_keys, RotorRunReport, RotorStaticReport};
    match kind {
        "rotor_run" => Ok(record_keys(&RotorRunReport::default())),
        "rotor_static" => Ok(record_keys(&RotorStaticReport::default())),
        other => Err(err(format!(
            "result_keys({other:?}): expected \"rotor_run\" or \"rotor_static\""
        ))),
    }
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add(
        "EhlBearingError",
        m.py().get_type_bound::<EhlBearingError>(),
    )?;
    m.add_class::<PyCase>()?;
    m.add_class::<Characterization>()?;
    m.add_class::<PyLawElement>()?;
    m.add_class::<PyTrendElement>()?;
    m.add_function(wrap_pyfunction!(equilibrium, m)?)?;
    m.add_function(wrap_pyfunction!(ehl, m)?)?;
    m.add_function(wrap_pyfunction!(contact, m)?)?;
    m.add_function(wrap_pyfunction!(characterize, m)?)?;
    m.add_function(wrap_pyfunction!(study, m)?)?;
    m.add_function(wrap_pyfunction!(coefficients, m)?)?;
    m.add_function(wrap_pyfunction!(ross_table_csv, m)?)?;
    m.add_function(wrap_pyfunction!(result_keys, m)?)?;
    m.add_function(wrap_pyfunction!(law_maps, m)?)?;
    rotor::register(m)?;
    Ok(())
}
