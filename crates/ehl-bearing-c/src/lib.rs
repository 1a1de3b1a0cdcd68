//! C interface of `ehl-bearing`: cases, characterization (with progress and cancel), the dry,
//! fitted-law and trend force elements, their evaluation with caller-owned state, coefficients
//! over speed, and the last error as text. The header `include/ehl_bearing.h` is generated from
//! this file by cbindgen (see `build.rs`); its opening comment states the conventions (status
//! codes, ownership, threads). Documentation: `docs/c.md`.
//!
//! Every exported function runs its body inside [`std::panic::catch_unwind`]: no panic crosses
//! the boundary. Pointer arguments are checked for NULL and numbers for finiteness before use;
//! the error message names the argument.

#![allow(clippy::missing_safety_doc)] // The header states each function's contract.

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::case::Case;
use ehl_bearing::characterize::{
    characterize_bearing_with_control, BearingCharacterization, CharacterizationReport,
    CharacterizeSettings,
};
use ehl_bearing::force_element::{
    ElementInput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::{parse_case, read_case};
use ehl_bearing::report::{to_json_line, ProgressEvent, SpeedProgressEvent};
use std::cell::RefCell;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::ops::ControlFlow;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};

pub mod reference;

// ---------------------------------------------------------------------------------------------
// Status codes and the last error
// ---------------------------------------------------------------------------------------------

/// Success.
pub const EHL_OK: c_int = 0;
/// A required pointer argument is NULL (the message names it).
pub const EHL_ERR_NULL: c_int = 1;
/// An argument is invalid: a number that is not finite, text that is not UTF-8, a size or
/// buffer that does not fit (the message names it and its value).
pub const EHL_ERR_ARGUMENT: c_int = 2;
/// The library refused an input: a case, method, report or trend file that does not parse or
/// validate, a file that cannot be read (the library's message names the field, value, range).
pub const EHL_ERR_INPUT: c_int = 3;
/// A computation failed: an equilibrium or EHL solve that did not converge, a time limit (the
/// library's message carries the numbers).
pub const EHL_ERR_COMPUTE: c_int = 4;
/// The progress callback returned nonzero: the computation stopped and wrote no result.
pub const EHL_ERR_CANCELLED: c_int = 5;
/// An internal error of the library (a bug, caught before it crossed the boundary).
pub const EHL_ERR_INTERNAL: c_int = 6;

/// Element kind: dry Hertz laws.
pub const EHL_ELEMENT_DRY: c_int = 0;
/// Element kind: the fitted laws of a characterization.
pub const EHL_ELEMENT_FITTED: c_int = 1;
/// Element kind: a study's trend curves.
pub const EHL_ELEMENT_TREND: c_int = 2;

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_error(message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

fn clear_error() {
    LAST_ERROR.with(|e| {
        let mut e = e.borrow_mut();
        if !e.as_bytes().is_empty() {
            *e = CString::default();
        }
    });
}

/// An error on its way to the caller: status and message.
#[derive(Debug)]
struct Failure {
    status: c_int,
    message: String,
}

type R<T> = Result<T, Failure>;

fn fail(status: c_int, message: impl Into<String>) -> Failure {
    Failure {
        status,
        message: message.into(),
    }
}

/// A library error with its status: inputs that do not parse or validate are
/// [`EHL_ERR_INPUT`], failed computations [`EHL_ERR_COMPUTE`].
fn lib_err(e: impl Into<ehl_bearing::Error>) -> Failure {
    use ehl_bearing::characterize::CharacterizeError as C;
    use ehl_bearing::Error as E;
    let e: ehl_bearing::Error = e.into();
    let status = match &e {
        E::Input(_) | E::Method(_) | E::Fit(_) => EHL_ERR_INPUT,
        E::Characterize(C::Setting { .. } | C::Trend(_)) => EHL_ERR_INPUT,
        E::Bearing(b) if b.is_refused_input() => EHL_ERR_INPUT,
        _ => EHL_ERR_COMPUTE,
    };
    fail(status, e.to_string())
}

/// Run `f`, catch any panic, record the error and return the status.
fn guard(f: impl FnOnce() -> R<()>) -> c_int {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => {
            clear_error();
            EHL_OK
        }
        Ok(Err(e)) => {
            set_error(&e.message);
            e.status
        }
        Err(p) => {
            set_error(&format!(
                "internal error of ehl-bearing (a bug, please report it): {}",
                ehl_bearing::error::panic_message(p.as_ref())
            ));
            EHL_ERR_INTERNAL
        }
    }
}

/// The message of the last failed call on the calling thread ("" after a successful call).
/// Never NULL. Owned by the library: valid until the next call into the library on this thread.
#[no_mangle]
pub extern "C" fn ehl_last_error() -> *const c_char {
    catch_unwind(|| LAST_ERROR.with(|e| e.borrow().as_ptr()))
        .unwrap_or(c"ehl_last_error failed".as_ptr())
}

/// The library's version ("0.1.0"), a static string (never freed).
#[no_mangle]
pub extern "C" fn ehl_version() -> *const c_char {
    static VERSION: &CStr =
        match CStr::from_bytes_with_nul(concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes()) {
            Ok(v) => v,
            Err(_) => c"unknown",
        };
    VERSION.as_ptr()
}

// ---------------------------------------------------------------------------------------------
// Argument checks
// ---------------------------------------------------------------------------------------------

/// # Safety
/// `p` is NULL or points to a NUL-terminated string valid for the call.
unsafe fn text<'a>(p: *const c_char, name: &str) -> R<&'a str> {
    if p.is_null() {
        return Err(fail(EHL_ERR_NULL, format!("{name} is NULL")));
    }
    // SAFETY: non-null, and the caller guarantees a NUL-terminated string live for the call.
    let s = unsafe { CStr::from_ptr(p) };
    s.to_str()
        .map_err(|e| fail(EHL_ERR_ARGUMENT, format!("{name} is not UTF-8 text: {e}")))
}

/// # Safety
/// As [`text`]; NULL gives `None`.
unsafe fn text_opt<'a>(p: *const c_char, name: &str) -> R<Option<&'a str>> {
    if p.is_null() {
        Ok(None)
    } else {
        // SAFETY: forwarded contract of the caller.
        unsafe { text(p, name) }.map(Some)
    }
}

/// # Safety
/// `p` is NULL or points to a live `T` not written during the call.
unsafe fn obj<'a, T>(p: *const T, name: &str) -> R<&'a T> {
    // SAFETY: the caller guarantees a valid object or NULL.
    unsafe { p.as_ref() }.ok_or_else(|| fail(EHL_ERR_NULL, format!("{name} is NULL")))
}

/// # Safety
/// `p` is NULL or points to a live `T` not used elsewhere during the call.
unsafe fn obj_mut<'a, T>(p: *mut T, name: &str) -> R<&'a mut T> {
    // SAFETY: the caller guarantees a valid, unaliased object or NULL.
    unsafe { p.as_mut() }.ok_or_else(|| fail(EHL_ERR_NULL, format!("{name} is NULL")))
}

/// Check an out-pointer before any work, so that a NULL one fails early.
fn out_ptr<T>(p: *mut T, name: &str) -> R<()> {
    if p.is_null() {
        Err(fail(EHL_ERR_NULL, format!("{name} is NULL")))
    } else {
        Ok(())
    }
}

fn finite(name: &str, v: f64) -> R<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(fail(
            EHL_ERR_ARGUMENT,
            format!("{name} = {v}: expected a finite number"),
        ))
    }
}

/// Store a new object in `*out`.
///
/// # Safety
/// `out` is non-null (checked by [`out_ptr`]) and writable.
unsafe fn put<T>(out: *mut *mut T, value: T) {
    // SAFETY: checked non-null by the caller; the box is released by the matching *_free.
    unsafe { *out = Box::into_raw(Box::new(value)) };
}

/// Store text in `*out` as a library-owned C string (freed with [`ehl_string_free`]).
///
/// # Safety
/// `out` is non-null and writable.
unsafe fn put_text(out: *mut *mut c_char, s: String) -> R<()> {
    let c = CString::new(s).map_err(|e| fail(EHL_ERR_INTERNAL, format!("text with NUL: {e}")))?;
    // SAFETY: checked non-null by the caller.
    unsafe { *out = c.into_raw() };
    Ok(())
}

/// Release a string returned by the library (JSON, CSV). NULL does nothing.
#[no_mangle]
pub unsafe extern "C" fn ehl_string_free(s: *mut c_char) {
    if !s.is_null() {
        let _ = catch_unwind(|| {
            // SAFETY: `s` came from `CString::into_raw` in this library and is freed once.
            drop(unsafe { CString::from_raw(s) })
        });
    }
}

// ---------------------------------------------------------------------------------------------
// Case
// ---------------------------------------------------------------------------------------------

/// A validated bearing case (geometry, materials, lubricant, operating point, settings).
pub struct EhlCase {
    case: Case,
}

/// A few numbers of a case (SI).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct EhlCaseInfo {
    /// Number of balls Z.
    pub ball_count: u32,
    /// Ball diameter D, m.
    pub ball_diameter_m: f64,
    /// Pitch diameter d_m, m.
    pub pitch_diameter_m: f64,
    /// Free contact angle, rad.
    pub contact_angle_rad: f64,
    /// Inner-ring speed, rad/s.
    pub inner_speed_rad_s: f64,
    /// Outer-ring speed, rad/s.
    pub outer_speed_rad_s: f64,
}

/// Read and validate a case file (TOML, e.g. examples/7006.toml) into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_case_from_file(path: *const c_char, out: *mut *mut EhlCase) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: the caller passes a NUL-terminated path.
        let path = unsafe { text(path, "path") }?;
        let case = read_case(std::path::Path::new(path)).map_err(lib_err)?;
        // SAFETY: `out` checked above.
        unsafe { put(out, EhlCase { case }) };
        Ok(())
    })
}

/// Parse and validate a case from TOML text into `*out`; `origin` (may be NULL: `"<string>"`)
/// names the text in error messages.
#[no_mangle]
pub unsafe extern "C" fn ehl_case_from_toml(
    toml_text: *const c_char,
    origin: *const c_char,
    out: *mut *mut EhlCase,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: NUL-terminated strings from the caller.
        let t = unsafe { text(toml_text, "toml_text") }?;
        // SAFETY: as above; NULL allowed.
        let origin = unsafe { text_opt(origin, "origin") }?.unwrap_or("<string>");
        let case = parse_case(t, origin).map_err(lib_err)?;
        // SAFETY: `out` checked above.
        unsafe { put(out, EhlCase { case }) };
        Ok(())
    })
}

/// A copy of `c` with the inner-ring speed set to `rpm`, into `*out`; refused like the case
/// file's own speed (not finite, or beyond the plausibility rules).
#[no_mangle]
pub unsafe extern "C" fn ehl_case_with_inner_speed_rpm(
    c: *const EhlCase,
    rpm: f64,
    out: *mut *mut EhlCase,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a case from this library or NULL.
        let c = unsafe { obj(c, "case") }?;
        finite("rpm", rpm)?;
        let mut case = c.case.clone();
        case.operating.inner_speed = rpm * std::f64::consts::PI / 30.0;
        ehl_bearing::plausibility::check_case(&case).map_err(|e| {
            fail(
                EHL_ERR_INPUT,
                format!(
                    "with_inner_speed_rpm({}): {e}",
                    ehl_bearing::case::number_text(rpm)
                ),
            )
        })?;
        // SAFETY: `out` checked above.
        unsafe { put(out, EhlCase { case }) };
        Ok(())
    })
}

/// Numbers of the case into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_case_info(c: *const EhlCase, out: *mut EhlCaseInfo) -> c_int {
    guard(|| {
        // SAFETY: a case from this library or NULL.
        let c = &unsafe { obj(c, "case") }?.case;
        // SAFETY: the caller's struct or NULL.
        let out = unsafe { obj_mut(out, "out") }?;
        let g = &c.bearing.geometry;
        *out = EhlCaseInfo {
            ball_count: g.ball_count as u32,
            ball_diameter_m: g.ball_diameter,
            pitch_diameter_m: g.pitch_diameter,
            contact_angle_rad: g.free_contact_angle,
            inner_speed_rad_s: c.operating.inner_speed,
            outer_speed_rad_s: c.operating.outer_speed,
        };
        Ok(())
    })
}

/// The dry (Hertz) equilibrium of the case's bearing under its loads as JSON (the library's
/// equilibrium record: displacements, reactions, 5×5 stiffness, contact states; SI) into
/// `*out_json` (free with ehl_string_free).
#[no_mangle]
pub unsafe extern "C" fn ehl_case_equilibrium_json(
    c: *const EhlCase,
    out_json: *mut *mut c_char,
) -> c_int {
    guard(|| {
        out_ptr(out_json, "out_json")?;
        // SAFETY: a case from this library or NULL.
        let c = &unsafe { obj(c, "case") }?.case;
        let laws = ContactLaws::hertz(&c.bearing).map_err(lib_err)?;
        let eq =
            solve_equilibrium(&c.bearing, &laws, &c.operating, &c.settings).map_err(lib_err)?;
        let v = ehl_bearing::report::EquilibriumReport::from(&eq);
        // SAFETY: checked above.
        unsafe { put_text(out_json, ehl_bearing::report::to_json_line(&v)) }
    })
}

/// Release a case. NULL does nothing.
#[no_mangle]
pub unsafe extern "C" fn ehl_case_free(c: *mut EhlCase) {
    if !c.is_null() {
        // SAFETY: `c` came from Box::into_raw in this library and is freed once.
        let _ = catch_unwind(AssertUnwindSafe(|| drop(unsafe { Box::from_raw(c) })));
    }
}

// ---------------------------------------------------------------------------------------------
// Progress and cancel
// ---------------------------------------------------------------------------------------------

/// Progress callback: called with one event as JSON text (`{"event": "iteration_started", ...}`,
/// valid during the call only) and the caller's `user` pointer, always on the thread that made
/// the call into the library and never concurrently. Return 0 to go on, nonzero to cancel: no
/// further events come, the computation stops at its next contact and the call returns
/// EHL_ERR_CANCELLED.
pub type EhlProgressFn =
    Option<unsafe extern "C" fn(event_json: *const c_char, user: *mut c_void) -> c_int>;

/// Stop the library's loop once the caller asked to cancel (after the event just reported).
fn go_on(cancel: &AtomicBool) -> ControlFlow<()> {
    if cancel.load(Ordering::SeqCst) {
        ControlFlow::Break(())
    } else {
        ControlFlow::Continue(())
    }
}

/// Event sink handed to the work: takes one event as JSON text.
type Report<'a> = dyn Fn(String) + Sync + 'a;

/// Run `work` with progress events delivered to the C callback on the calling thread.
///
/// Without a callback the work runs on the calling thread. With one, it runs on a scoped worker
/// thread; each event is sent to the calling thread, which calls the callback and answers
/// whether to cancel before the worker goes on (so a cancel takes effect at the next contact,
/// deterministically). A cancel request gives [`EHL_ERR_CANCELLED`] whatever the work returned.
fn with_progress<T: Send>(
    progress: EhlProgressFn,
    user: *mut c_void,
    work: impl FnOnce(&Report<'_>, &AtomicBool) -> R<T> + Send,
) -> R<T> {
    let cancel = AtomicBool::new(false);
    let Some(callback) = progress else {
        return work(&|_| {}, &cancel);
    };
    let cancel_ref = &cancel;
    let (tx, rx) = mpsc::channel::<(String, mpsc::SyncSender<bool>)>();
    let joined = std::thread::scope(|s| {
        let worker = s.spawn(move || {
            let report = |event: String| {
                if cancel_ref.load(Ordering::SeqCst) {
                    return; // cancelled: no more events
                }
                let (reply_tx, reply_rx) = mpsc::sync_channel(1);
                if tx.send((event, reply_tx)).is_ok() && reply_rx.recv() == Ok(true) {
                    cancel_ref.store(true, Ordering::SeqCst);
                }
            };
            work(&report, cancel_ref)
        });
        for (event, reply) in rx {
            let text = CString::new(event).unwrap_or_default();
            // SAFETY: the caller's callback with its own `user` pointer, on the caller's thread;
            // the text lives during the call.
            let stop = unsafe { callback(text.as_ptr(), user) } != 0;
            let _ = reply.send(stop);
        }
        worker.join()
    });
    let result = match joined {
        Ok(r) => r,
        Err(p) => Err(fail(
            EHL_ERR_INTERNAL,
            format!(
                "internal error of ehl-bearing (a bug, please report it): {}",
                ehl_bearing::error::panic_message(p.as_ref())
            ),
        )),
    };
    if cancel.load(Ordering::SeqCst) {
        return Err(fail(
            EHL_ERR_CANCELLED,
            "cancelled: the progress callback returned nonzero",
        ));
    }
    result
}

// ---------------------------------------------------------------------------------------------
// Characterization
// ---------------------------------------------------------------------------------------------

/// The coupled characterization of a case (fitted laws, their equilibrium, the iterations).
pub struct EhlCharacterization {
    case: Case,
    inner: BearingCharacterization,
}

/// A summary of a characterization (SI).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct EhlCharacterizationSummary {
    /// 1 if the coupled loop converged, 0 if not.
    pub converged: c_int,
    /// Iterations of the coupled loop.
    pub iterations: u32,
    /// Equilibrium displacements x, y, z (m) and tilts θy, θz (rad).
    pub displacement: [f64; 5],
    /// Lubricated stiffness at the equilibrium, row-major.
    pub stiffness: [f64; 25],
    /// Dry Hertz stiffness at the same loads, row-major.
    pub dry_stiffness: [f64; 25],
}

fn flat(m: &[[f64; 5]; 5]) -> [f64; 25] {
    let mut out = [0.0; 25];
    for (i, row) in m.iter().enumerate() {
        out[5 * i..5 * i + 5].copy_from_slice(row);
    }
    out
}

/// Characterize the bearing of `c` with `method` ("hertz", "synthetic", "quasi-static",
/// "harmonic"; NULL: the case file's method, else quasi-static) into `*out`. `progress` (may be
/// NULL) gets each loop event, see EhlProgressFn. The EHL methods take seconds to minutes.
#[no_mangle]
pub unsafe extern "C" fn ehl_characterize(
    c: *const EhlCase,
    method: *const c_char,
    progress: EhlProgressFn,
    user: *mut c_void,
    out: *mut *mut EhlCharacterization,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a case from this library or NULL.
        let case = &unsafe { obj(c, "case") }?.case;
        // SAFETY: NUL-terminated or NULL.
        let method = unsafe { text_opt(method, "method") }?;
        let m = case.method_or(method).map_err(lib_err)?;
        let settings = CharacterizeSettings::default();
        let ch = with_progress(progress, user, |report, cancel| {
            characterize_bearing_with_control(case, &m, &settings, None, &|p| {
                report(to_json_line(&ProgressEvent::from(&p)));
                go_on(cancel)
            })
            .map_err(lib_err)
        })?;
        // SAFETY: `out` checked above.
        unsafe {
            put(
                out,
                EhlCharacterization {
                    case: case.clone(),
                    inner: ch,
                },
            )
        };
        Ok(())
    })
}

/// The summary of a characterization into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_characterization_summary(
    ch: *const EhlCharacterization,
    out: *mut EhlCharacterizationSummary,
) -> c_int {
    guard(|| {
        // SAFETY: a characterization from this library or NULL.
        let ch = &unsafe { obj(ch, "characterization") }?.inner;
        // SAFETY: the caller's struct or NULL.
        let out = unsafe { obj_mut(out, "out") }?;
        *out = EhlCharacterizationSummary {
            converged: ch.converged as c_int,
            iterations: ch.iterations as u32,
            displacement: ch.equilibrium.displacement,
            stiffness: flat(&ch.ehl_stiffness()),
            dry_stiffness: flat(&ch.dry_stiffness()),
        };
        Ok(())
    })
}

/// The characterization report as JSON text (the `characterize --json` record, SI; with
/// `timing` nonzero also the times) into `*out_json` (free with ehl_string_free).
#[no_mangle]
pub unsafe extern "C" fn ehl_characterization_json(
    ch: *const EhlCharacterization,
    timing: c_int,
    out_json: *mut *mut c_char,
) -> c_int {
    guard(|| {
        out_ptr(out_json, "out_json")?;
        // SAFETY: a characterization from this library or NULL.
        let ch = &unsafe { obj(ch, "characterization") }?.inner;
        let s = serde_json::to_string_pretty(&ch.report(timing != 0))
            .map_err(|e| fail(EHL_ERR_INTERNAL, format!("report as JSON: {e}")))?;
        // SAFETY: checked above.
        unsafe { put_text(out_json, s) }
    })
}

/// Release a characterization. NULL does nothing.
#[no_mangle]
pub unsafe extern "C" fn ehl_characterization_free(ch: *mut EhlCharacterization) {
    if !ch.is_null() {
        // SAFETY: from Box::into_raw in this library, freed once.
        let _ = catch_unwind(AssertUnwindSafe(|| drop(unsafe { Box::from_raw(ch) })));
    }
}

// ---------------------------------------------------------------------------------------------
// Force elements
// ---------------------------------------------------------------------------------------------

/// A bearing as a force element: dry Hertz laws, the fitted laws of a characterization, or a
/// study's trend curves. Immutable: one element may serve several states and threads.
pub struct EhlElement {
    element: Arc<dyn ForceElement>,
    kind: c_int,
    has_damping: bool,
}

/// A few numbers of an element.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct EhlElementInfo {
    /// EHL_ELEMENT_DRY, EHL_ELEMENT_FITTED or EHL_ELEMENT_TREND.
    pub kind: c_int,
    /// 1 if the laws carry damping terms (harmonic method), else 0.
    pub has_damping: c_int,
    /// Number of balls Z.
    pub ball_count: u32,
    /// Ball diameter D, m.
    pub ball_diameter_m: f64,
    /// Pitch diameter d_m, m.
    pub pitch_diameter_m: f64,
}

/// Caller-owned warm-start state of an element: one per bearing and caller; results do not
/// depend on it beyond the solvers' tolerances. Also keeps the per-ball loads and approaches of
/// the last successful evaluation (ehl_state_contacts).
pub struct EhlState {
    state: ElementState,
    loads: Vec<[f64; 2]>,
    approaches: Vec<[f64; 2]>,
}

/// The inputs of one evaluation (SI).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct EhlInput {
    /// Inner-ring displacement relative to the outer ring: x, y, z (m), θy, θz (rad).
    pub displacement: [f64; 5],
    /// Its rates (m/s, rad/s).
    pub velocity: [f64; 5],
    /// Inner-ring speed about +x, rad/s.
    pub inner_speed_rad_s: f64,
    /// Outer-ring speed about +x, rad/s.
    pub outer_speed_rad_s: f64,
    /// Cage angle, rad: ball j at azimuth 2πj/Z + cage angle (advance it at the cage speed for
    /// the varying compliance; hold it fixed for a time-invariant bearing).
    pub cage_angle_rad: f64,
}

/// The result of one evaluation (SI).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct EhlOutput {
    /// Load on the inner ring in equilibrium with the balls: Fx, Fy, Fz (N), My, Mz (N·m),
    /// damping term included (the bearing acts on the shaft with the opposite).
    pub reaction: [f64; 5],
    /// ∂reaction/∂q, row-major (N/m, N, N·m/rad); not symmetrized.
    pub stiffness: [f64; 25],
    /// ∂reaction/∂q̇, row-major (N·s/m, N·s, N·m·s/rad); zero for laws without damping.
    pub damping: [f64; 25],
    /// Loaded contacts outside the range their law was fitted on (or the trends' load range).
    pub outside_range: u32,
    /// Contacts beyond 2 % of the ball diameter: a displacement no bearing survives; the numbers
    /// are returned as computed.
    pub overloaded: u32,
    /// 1 if the speed is outside a trend element's speed range (laws at the nearest end).
    pub speed_outside: c_int,
    /// Cage speed at this state, rad/s: the load-weighted mean of the balls' orbital speeds of
    /// the bearing model (advance the cage angle at it for the ball-pass excitation).
    pub cage_speed_rad_s: f64,
}

impl Default for EhlOutput {
    fn default() -> Self {
        EhlOutput {
            reaction: [0.0; 5],
            stiffness: [0.0; 25],
            damping: [0.0; 25],
            outside_range: 0,
            overloaded: 0,
            speed_outside: 0,
            cage_speed_rad_s: 0.0,
        }
    }
}

/// # Safety
/// `out` non-null (checked), writable.
unsafe fn put_element(out: *mut *mut EhlElement, element: Arc<dyn ForceElement>, kind: c_int) {
    // SAFETY: forwarded.
    unsafe {
        put(
            out,
            EhlElement {
                element,
                kind,
                has_damping: false,
            },
        )
    }
}

/// # Safety
/// `out` non-null (checked), writable.
unsafe fn put_law_element(out: *mut *mut EhlElement, element: LawElement, kind: c_int) {
    let has_damping = element.has_damping();
    // SAFETY: forwarded.
    unsafe {
        put(
            out,
            EhlElement {
                element: Arc::new(element),
                kind,
                has_damping,
            },
        )
    }
}

/// Dry Hertz laws for the bearing, race control and kinematics model of case `c`, into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_hertz(c: *const EhlCase, out: *mut *mut EhlElement) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a case from this library or NULL.
        let case = &unsafe { obj(c, "case") }?.case;
        let e = LawElement::hertz_case(case).map_err(lib_err)?;
        // SAFETY: checked above.
        unsafe { put_law_element(out, e, EHL_ELEMENT_DRY) };
        Ok(())
    })
}

/// The fitted laws of a characterization as an element, into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_from_characterization(
    ch: *const EhlCharacterization,
    out: *mut *mut EhlElement,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a characterization from this library or NULL.
        let ch = unsafe { obj(ch, "characterization") }?;
        let e = LawElement::from_characterization(&ch.case, &ch.inner).map_err(lib_err)?;
        // SAFETY: checked above.
        unsafe { put_law_element(out, e, EHL_ELEMENT_FITTED) };
        Ok(())
    })
}

fn report_element(case: &Case, json: &str, origin: &str) -> R<LawElement> {
    let r: CharacterizationReport = serde_json::from_str(json).map_err(|e| {
        fail(
            EHL_ERR_INPUT,
            format!("{origin}: not a characterization report: {e}"),
        )
    })?;
    let e =
        LawElement::from_report(&case.bearing, case.operating.race_control, &r).map_err(lib_err)?;
    Ok(e.with_kinematics(case.settings.kinematics))
}

/// The fitted laws of a characterization report (JSON text: `characterize --json`,
/// ehl_characterization_json, a study point's `result`) for the bearing of case `c`, into
/// `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_from_report_json(
    c: *const EhlCase,
    json: *const c_char,
    out: *mut *mut EhlElement,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a case from this library or NULL.
        let case = &unsafe { obj(c, "case") }?.case;
        // SAFETY: NUL-terminated text.
        let json = unsafe { text(json, "json") }?;
        let e = report_element(case, json, "report")?;
        // SAFETY: checked above.
        unsafe { put_law_element(out, e, EHL_ELEMENT_FITTED) };
        Ok(())
    })
}

fn read_file(path: &str) -> R<String> {
    std::fs::read_to_string(path).map_err(|e| fail(EHL_ERR_INPUT, format!("reading {path}: {e}")))
}

/// As ehl_element_from_report_json, from a report file.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_from_report_file(
    c: *const EhlCase,
    path: *const c_char,
    out: *mut *mut EhlElement,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: a case from this library or NULL.
        let case = &unsafe { obj(c, "case") }?.case;
        // SAFETY: NUL-terminated text.
        let path = unsafe { text(path, "path") }?;
        let e = report_element(case, &read_file(path)?, path)?;
        // SAFETY: checked above.
        unsafe { put_law_element(out, e, EHL_ELEMENT_FITTED) };
        Ok(())
    })
}

/// The trend element of a study's trend curves (JSON text of `trends.json`), into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_trend_from_json(
    json: *const c_char,
    out: *mut *mut EhlElement,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: NUL-terminated text.
        let json = unsafe { text(json, "json") }?;
        let e = TrendForceElement::from_json(json).map_err(lib_err)?;
        // SAFETY: checked above.
        unsafe { put_element(out, Arc::new(e), EHL_ELEMENT_TREND) };
        Ok(())
    })
}

/// As ehl_element_trend_from_json, from a trend file (`trends.json`).
#[no_mangle]
pub unsafe extern "C" fn ehl_element_trend_from_file(
    path: *const c_char,
    out: *mut *mut EhlElement,
) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: NUL-terminated text.
        let path = unsafe { text(path, "path") }?;
        let e = TrendForceElement::from_json(&read_file(path)?)
            .map_err(|e| fail(EHL_ERR_INPUT, format!("{path}: {e}")))?;
        // SAFETY: checked above.
        unsafe { put_element(out, Arc::new(e), EHL_ELEMENT_TREND) };
        Ok(())
    })
}

/// Numbers of an element into `*out`.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_info(e: *const EhlElement, out: *mut EhlElementInfo) -> c_int {
    guard(|| {
        // SAFETY: an element from this library or NULL.
        let e = unsafe { obj(e, "element") }?;
        // SAFETY: the caller's struct or NULL.
        let out = unsafe { obj_mut(out, "out") }?;
        let g = &e.element.bearing().geometry;
        *out = EhlElementInfo {
            kind: e.kind,
            has_damping: e.has_damping as c_int,
            ball_count: g.ball_count as u32,
            ball_diameter_m: g.ball_diameter,
            pitch_diameter_m: g.pitch_diameter,
        };
        Ok(())
    })
}

/// Cage speed under pure rolling at the free contact angle, at ring speeds `inner_speed_rad_s`,
/// `outer_speed_rad_s` (rad/s) into `*out` (rad/s): ω_c = ½·[ω_i·(1 − γ) + ω_o·(1 + γ)],
/// γ = D·cos α0/d_m — the unloaded bearing's. A loaded bearing's cage runs at the operating
/// cage speed, `EhlOutput::cage_speed_rad_s` of [`ehl_evaluate`] (the balls' orbital speeds at
/// their operating contact angles; up to 12 % faster at high speed).
#[no_mangle]
pub unsafe extern "C" fn ehl_element_cage_speed(
    e: *const EhlElement,
    inner_speed_rad_s: f64,
    outer_speed_rad_s: f64,
    out: *mut f64,
) -> c_int {
    guard(|| {
        // SAFETY: an element from this library or NULL.
        let e = unsafe { obj(e, "element") }?;
        // SAFETY: the caller's number or NULL.
        let out = unsafe { obj_mut(out, "out") }?;
        let wi = finite("inner_speed_rad_s", inner_speed_rad_s)?;
        let wo = finite("outer_speed_rad_s", outer_speed_rad_s)?;
        *out = e.element.cage_speed(wi, wo);
        Ok(())
    })
}

/// Equilibrium of element `e` under the loads of case `c` (its load-controlled DOFs; the others
/// imposed) at the case's speeds: displacement into `displacement[5]`, and, where not NULL,
/// stiffness and damping there into `stiffness[25]`, `damping[25]` (row-major).
#[no_mangle]
pub unsafe extern "C" fn ehl_element_equilibrium(
    e: *const EhlElement,
    c: *const EhlCase,
    displacement: *mut f64,
    stiffness: *mut f64,
    damping: *mut f64,
) -> c_int {
    guard(|| {
        // SAFETY: library objects or NULL.
        let e = unsafe { obj(e, "element") }?;
        // SAFETY: as above.
        let case = &unsafe { obj(c, "case") }?.case;
        out_ptr(displacement, "displacement")?;
        let laws = ContactLaws::hertz(&case.bearing).map_err(lib_err)?;
        let dry = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
            .map_err(lib_err)?;
        let (q, out) = ehl_bearing::coefficients::element_equilibrium(
            e.element.as_ref(),
            case,
            dry.displacement,
        )
        .map_err(lib_err)?;
        // SAFETY: the caller provides 5 (and 25) writable doubles behind non-null pointers.
        unsafe {
            std::ptr::copy_nonoverlapping(q.as_ptr(), displacement, 5);
            if !stiffness.is_null() {
                std::ptr::copy_nonoverlapping(flat(&out.stiffness).as_ptr(), stiffness, 25);
            }
            if !damping.is_null() {
                std::ptr::copy_nonoverlapping(flat(&out.damping).as_ptr(), damping, 25);
            }
        }
        Ok(())
    })
}

/// Release an element. NULL does nothing.
#[no_mangle]
pub unsafe extern "C" fn ehl_element_free(e: *mut EhlElement) {
    if !e.is_null() {
        // SAFETY: from Box::into_raw in this library, freed once.
        let _ = catch_unwind(AssertUnwindSafe(|| drop(unsafe { Box::from_raw(e) })));
    }
}

/// A new, cold state into `*out` (free with ehl_state_free).
#[no_mangle]
pub unsafe extern "C" fn ehl_state_new(out: *mut *mut EhlState) -> c_int {
    guard(|| {
        out_ptr(out, "out")?;
        // SAFETY: checked above.
        unsafe {
            put(
                out,
                EhlState {
                    state: ElementState::default(),
                    loads: Vec::new(),
                    approaches: Vec::new(),
                },
            )
        };
        Ok(())
    })
}

/// Release a state. NULL does nothing.
#[no_mangle]
pub unsafe extern "C" fn ehl_state_free(s: *mut EhlState) {
    if !s.is_null() {
        // SAFETY: from Box::into_raw in this library, freed once.
        let _ = catch_unwind(AssertUnwindSafe(|| drop(unsafe { Box::from_raw(s) })));
    }
}

/// Evaluate element `e` at `*input`, warm-started from and updating `*state`: reaction,
/// stiffness and damping into `*output`. A failed evaluation (a ball whose equilibrium does not
/// converge, a non-finite input) leaves the state usable and `*output` unchanged.
#[no_mangle]
pub unsafe extern "C" fn ehl_evaluate(
    e: *const EhlElement,
    state: *mut EhlState,
    input: *const EhlInput,
    output: *mut EhlOutput,
) -> c_int {
    guard(|| {
        // SAFETY: library objects or NULL; the state is not used by another call meanwhile.
        let e = unsafe { obj(e, "element") }?;
        // SAFETY: as above.
        let st = unsafe { obj_mut(state, "state") }?;
        // SAFETY: the caller's structs or NULL.
        let i = unsafe { obj(input, "input") }?;
        // SAFETY: as above.
        let o = unsafe { obj_mut(output, "output") }?;
        for k in 0..5 {
            finite(&format!("input->displacement[{k}]"), i.displacement[k])?;
            finite(&format!("input->velocity[{k}]"), i.velocity[k])?;
        }
        finite("input->inner_speed_rad_s", i.inner_speed_rad_s)?;
        finite("input->outer_speed_rad_s", i.outer_speed_rad_s)?;
        finite("input->cage_angle_rad", i.cage_angle_rad)?;
        let input = ElementInput {
            displacement: i.displacement,
            velocity: i.velocity,
            inner_speed: i.inner_speed_rad_s,
            outer_speed: i.outer_speed_rad_s,
            cage_angle: i.cage_angle_rad,
        };
        let r = e.element.evaluate(&input, &mut st.state).map_err(lib_err)?;
        o.reaction = r.reaction;
        o.stiffness = flat(&r.stiffness);
        o.damping = flat(&r.damping);
        o.outside_range = r.outside_range.len() as u32;
        o.overloaded = r.overloaded.len() as u32;
        o.speed_outside = r.speed_outside as c_int;
        o.cage_speed_rad_s = r.cage_speed;
        st.loads = r.loads;
        st.approaches = r.approaches;
        Ok(())
    })
}

/// The per-ball contact loads (N, without the damping term) and approaches (m, negative:
/// separated) of the state's last successful evaluation: ball j's [inner, outer] at
/// `loads[2*j]`, `loads[2*j + 1]`. `capacity` is the length of each array (at least 2·Z);
/// `*count` receives 2·Z. Either array may be NULL.
#[no_mangle]
pub unsafe extern "C" fn ehl_state_contacts(
    state: *const EhlState,
    loads: *mut f64,
    approaches: *mut f64,
    capacity: usize,
    count: *mut usize,
) -> c_int {
    guard(|| {
        // SAFETY: a state from this library or NULL.
        let st = unsafe { obj(state, "state") }?;
        // SAFETY: the caller's number or NULL.
        let count = unsafe { obj_mut(count, "count") }?;
        let n = 2 * st.loads.len();
        if (!loads.is_null() || !approaches.is_null()) && capacity < n {
            return Err(fail(
                EHL_ERR_ARGUMENT,
                format!("capacity = {capacity}: the state holds {n} contacts (2·Z)"),
            ));
        }
        // SAFETY: the caller provides `capacity` ≥ n writable doubles behind each non-null
        // pointer; [f64; 2] rows are contiguous.
        unsafe {
            if !loads.is_null() {
                std::ptr::copy_nonoverlapping(st.loads.as_ptr().cast::<f64>(), loads, n);
            }
            if !approaches.is_null() {
                std::ptr::copy_nonoverlapping(st.approaches.as_ptr().cast::<f64>(), approaches, n);
            }
        }
        *count = n;
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------
// Coefficients
// ---------------------------------------------------------------------------------------------

/// Linearized 5×5 stiffness and damping of the bearing of case `c` at each of the `n` inner-ring
/// speeds `speeds_rpm`: from the coupled characterization with `method` (NULL: the case's, else
/// quasi-static) or, if `element` is not NULL, from that element's equilibrium (no EHL run).
/// The result is JSON text (a list of records: inner_speed_rpm, inner_speed_rad_s,
/// displacement, stiffness, damping, dry_stiffness, converged, source; matrices as nested
/// lists) into `*out_json` (free with ehl_string_free). `progress` as for ehl_characterize
/// (events carry "speed_index").
#[no_mangle]
// The arguments are the C interface (ehl_coefficients in include/ehl_bearing.h): not grouped.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ehl_coefficients(
    c: *const EhlCase,
    speeds_rpm: *const f64,
    n: usize,
    method: *const c_char,
    element: *const EhlElement,
    progress: EhlProgressFn,
    user: *mut c_void,
    out_json: *mut *mut c_char,
) -> c_int {
    guard(|| {
        out_ptr(out_json, "out_json")?;
        // SAFETY: a case from this library or NULL.
        let case = &unsafe { obj(c, "case") }?.case;
        if speeds_rpm.is_null() {
            return Err(fail(EHL_ERR_NULL, "speeds_rpm is NULL"));
        }
        if n == 0 || n > 100_000 {
            return Err(fail(
                EHL_ERR_ARGUMENT,
                format!("n = {n}: expected 1 to 100000 speeds"),
            ));
        }
        // SAFETY: the caller provides n readable doubles.
        let speeds = unsafe { std::slice::from_raw_parts(speeds_rpm, n) }.to_vec();
        // SAFETY: NUL-terminated or NULL.
        let method = unsafe { text_opt(method, "method") }?;
        // SAFETY: an element from this library or NULL.
        let element = unsafe { element.as_ref() };
        let out = match element {
            Some(e) => ehl_bearing::coefficients::from_element(
                case,
                &speeds,
                e.element.as_ref(),
                "element",
            )
            .map_err(lib_err)?,
            None => {
                let m = case.method_or(method).map_err(lib_err)?;
                with_progress(progress, user, |report, cancel| {
                    ehl_bearing::coefficients::from_characterization(
                        case,
                        &speeds,
                        &m,
                        &CharacterizeSettings::default(),
                        &|i, p| {
                            report(to_json_line(&SpeedProgressEvent::new(i, &p)));
                            go_on(cancel)
                        },
                    )
                    .map_err(lib_err)
                })?
            }
        };
        let s = serde_json::to_string(&out)
            .map_err(|e| fail(EHL_ERR_INTERNAL, format!("coefficients as JSON: {e}")))?;
        // SAFETY: checked above.
        unsafe { put_text(out_json, s) }
    })
}

/// ROSS's speed-dependent bearing table (CSV: frequency in rad/s, kxx, kxy, kyx, kyy, cxx, cxy,
/// cyx, cyy, kzz, czz; ROSS x ← our y, y ← our z, z ← our x) of the JSON of ehl_coefficients,
/// into `*out_csv` (free with ehl_string_free).
#[no_mangle]
pub unsafe extern "C" fn ehl_ross_table_csv(
    coefficients_json: *const c_char,
    out_csv: *mut *mut c_char,
) -> c_int {
    guard(|| {
        out_ptr(out_csv, "out_csv")?;
        // SAFETY: NUL-terminated text.
        let json = unsafe { text(coefficients_json, "coefficients_json") }?;
        let c: Vec<ehl_bearing::coefficients::SpeedCoefficients> = serde_json::from_str(json)
            .map_err(|e| fail(EHL_ERR_INPUT, format!("coefficients_json: {e}")))?;
        // SAFETY: checked above.
        unsafe { put_text(out_csv, ehl_bearing::coefficients::ross_table_csv(&c)) }
    })
}

/// The law maps embedded in the library (`method = "map"`), in the order a query tries them, as
/// one JSON array into `*out_json` (free with ehl_string_free): per map its name, law, nodes,
/// generation CPU time (s), nodes flagged not converged, worst node fit and spec (models, fixed
/// groups, axes with range and nodes; groups dimensionless) — the keys of `ehl-bearing law-map
/// info --json` and Python's `law_maps()`.
#[no_mangle]
pub unsafe extern "C" fn ehl_law_maps_json(out_json: *mut *mut c_char) -> c_int {
    guard(|| {
        out_ptr(out_json, "out_json")?;
        let s = ehl_bearing::law_map::LawMap::embedded_summaries();
        // SAFETY: checked above.
        unsafe { put_text(out_json, ehl_bearing::report::to_json_line(&s)) }
    })
}
