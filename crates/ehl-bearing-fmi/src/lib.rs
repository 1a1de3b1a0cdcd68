//! The ehl-bearing force element as an FMI 2.0 model-exchange unit.
//!
//! The shared library (`crate-type = "cdylib"`) exports the FMI 2.0 C functions of model exchange
//! under their plain names (`fmi2Instantiate`, `fmi2SetReal`, …); `scripts/build_fmu.sh` zips it
//! with `modelDescription.xml` (written from [`mod@variables`]) and the case and characterization or
//! trend files in `resources/` into an `.fmu`. The unit has no states and no event indicators:
//! its outputs (reactions, K, C, cage speed, contact-load maxima and flags) are algebraic in its
//! inputs (ring displacements and rates, ring speeds, cage angle) — direct feedthrough — and are
//! computed by [`ehl_bearing::force_element::ForceElement::evaluate`] when an output is read after
//! an input changed.
//!
//! Every entry point catches panics (none crosses the C boundary), checks its pointers, and
//! reports errors through the importer's logger with the library's message, returning
//! `fmi2Error`.

#![allow(non_snake_case)]
// The exported functions take raw pointers from the importer by the FMI standard's contract; they
// check them for null and are not meant to be called from Rust with arbitrary pointers.
#![allow(clippy::missing_safety_doc, clippy::not_unsafe_ptr_arg_deref)]

pub mod model;
pub mod variables;

use model::{load_resources, resource_path, Model};
use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use variables::*;

/// `fmi2Status`.
pub type Status = c_int;
/// `fmi2OK`.
pub const OK: Status = 0;
/// `fmi2Warning`.
pub const WARNING: Status = 1;
/// `fmi2Discard`.
pub const DISCARD: Status = 2;
/// `fmi2Error`.
pub const ERROR: Status = 3;
/// `fmi2Fatal`.
pub const FATAL: Status = 4;

/// `fmi2ModelExchange` (`fmi2Type`).
pub const MODEL_EXCHANGE: c_int = 0;

/// `fmi2CallbackLogger`: `(componentEnvironment, instanceName, status, category, message, ...)`,
/// `message` a printf format (this unit passes no arguments and escapes `%`).
pub type Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct CallbackFunctions {
    /// `logger`.
    pub logger: Option<Logger>,
    /// `allocateMemory` (unused: Rust's allocator serves the unit).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// `freeMemory` (unused).
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// `stepFinished` (co-simulation only; unused).
    pub step_finished: Option<unsafe extern "C" fn(*mut c_void, Status)>,
    /// `componentEnvironment`, passed back to the logger.
    pub component_environment: *mut c_void,
}

/// `fmi2EventInfo`.
#[repr(C)]
#[derive(Debug, Default)]
pub struct EventInfo {
    /// `newDiscreteStatesNeeded`.
    pub new_discrete_states_needed: c_int,
    /// `terminateSimulation`.
    pub terminate_simulation: c_int,
    /// `nominalsOfContinuousStatesChanged`.
    pub nominals_of_continuous_states_changed: c_int,
    /// `valuesOfContinuousStatesChanged`.
    pub values_of_continuous_states_changed: c_int,
    /// `nextEventTimeDefined`.
    pub next_event_time_defined: c_int,
    /// `nextEventTime`.
    pub next_event_time: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Instantiated,
    Initialization,
    Running,
    Terminated,
}

/// One instance (`fmi2Component`).
pub struct Instance {
    name: CString,
    logger: Option<Logger>,
    environment: *mut c_void,
    logging_on: bool,
    phase: Phase,
    /// The model: element and variable values.
    pub model: Model,
}

fn c_string(s: &str) -> CString {
    CString::new(s.replace('\0', " ")).unwrap_or_default()
}

fn log_to(
    logger: Option<Logger>,
    environment: *mut c_void,
    name: &CStr,
    status: Status,
    message: &str,
) {
    let Some(logger) = logger else { return };
    let category = match status {
        OK => "logAll",
        WARNING => "logStatusWarning",
        _ => "logStatusError",
    };
    let category = c_string(category);
    // The message is a printf format: escape '%'.
    let message = c_string(&message.replace('%', "%%"));
    unsafe {
        logger(
            environment,
            name.as_ptr(),
            status,
            category.as_ptr(),
            message.as_ptr(),
        )
    };
}

impl Instance {
    fn log(&self, status: Status, message: &str) {
        if status == OK && !self.logging_on {
            return;
        }
        log_to(self.logger, self.environment, &self.name, status, message);
    }

    fn fail(&self, function: &str, message: &str) -> Status {
        self.log(ERROR, &format!("{function}: {message}"));
        ERROR
    }
}

/// Run `f` on the instance behind `c`, catching panics (logged, `fmi2Error`).
fn with_instance(
    c: *mut c_void,
    function: &str,
    f: impl FnOnce(&mut Instance) -> Status,
) -> Status {
    if c.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null fmi2Component is a pointer fmi2Instantiate returned (FMI contract).
    let inst = unsafe { &mut *(c as *mut Instance) };
    match catch_unwind(AssertUnwindSafe(|| f(&mut *inst))) {
        Ok(s) => s,
        Err(p) => inst.fail(
            function,
            &format!(
                "internal error (panic): {}",
                ehl_bearing::error::panic_message(p.as_ref())
            ),
        ),
    }
}

/// `values[0..n]` as a slice; None when `n > 0` and the pointer is null.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts(p, n))
    }
}

unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    if n == 0 {
        Some(&mut [])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts_mut(p, n))
    }
}

unsafe fn text(p: *const c_char) -> Option<String> {
    (!p.is_null()).then(|| CStr::from_ptr(p).to_string_lossy().into_owned())
}

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: reads the element from the resources; null (with the reason logged) on
/// a wrong type, GUID or resource location, or unreadable resources.
#[no_mangle]
pub extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const CallbackFunctions,
    _visible: c_int,
    logging_on: c_int,
) -> *mut c_void {
    let r = catch_unwind(|| {
        if functions.is_null() {
            return std::ptr::null_mut();
        }
        // SAFETY: non-null, points to the importer's callback struct (FMI contract).
        let f = unsafe { &*functions };
        let name = unsafe { text(instance_name) }.unwrap_or_default();
        let cname = c_string(&name);
        let fail = |m: String| {
            log_to(
                f.logger,
                f.component_environment,
                &cname,
                ERROR,
                &format!("fmi2Instantiate: {m}"),
            );
            std::ptr::null_mut()
        };
        if fmu_type != MODEL_EXCHANGE {
            return fail(format!(
                "fmuType = {fmu_type}: this FMU supports model exchange only (fmi2ModelExchange = 0)"
            ));
        }
        match unsafe { text(guid) } {
            Some(g) if g == variables::guid() => {}
            g => {
                return fail(format!(
                    "fmuGUID = {g:?} does not match this binary's {:?}: modelDescription.xml and binaries/ come from different builds",
                    variables::guid()
                ))
            }
        }
        let Some(uri) = (unsafe { text(resource_location) }) else {
            return fail(
                "fmuResourceLocation is null: the element is read from resources/".to_string(),
            );
        };
        let dir = match resource_path(&uri) {
            Ok(d) => d,
            Err(e) => return fail(e),
        };
        let loaded = match load_resources(&dir) {
            Ok(l) => l,
            Err(e) => return fail(e),
        };
        let inst = Instance {
            name: cname.clone(),
            logger: f.logger,
            environment: f.component_environment,
            logging_on: logging_on != 0,
            phase: Phase::Instantiated,
            model: Model::new(loaded),
        };
        inst.log(
            OK,
            &format!(
                "fmi2Instantiate: {} ({} balls)",
                inst.model.loaded.summary,
                inst.model.loaded.element.ball_count()
            ),
        );
        Box::into_raw(Box::new(inst)) as *mut c_void
    });
    r.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub extern "C" fn fmi2FreeInstance(c: *mut c_void) {
    if c.is_null() {
        return;
    }
    // SAFETY: a pointer fmi2Instantiate returned, freed once (FMI contract).
    let _ = catch_unwind(AssertUnwindSafe(|| {
        drop(unsafe { Box::from_raw(c as *mut Instance) })
    }));
}

#[no_mangle]
pub extern "C" fn fmi2SetDebugLogging(
    c: *mut c_void,
    logging_on: c_int,
    _n_categories: usize,
    _categories: *const *const c_char,
) -> Status {
    with_instance(c, "fmi2SetDebugLogging", |i| {
        i.logging_on = logging_on != 0;
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetupExperiment(
    c: *mut c_void,
    _tolerance_defined: c_int,
    _tolerance: f64,
    _start_time: f64,
    _stop_time_defined: c_int,
    _stop_time: f64,
) -> Status {
    with_instance(c, "fmi2SetupExperiment", |_| OK)
}

#[no_mangle]
pub extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> Status {
    with_instance(c, "fmi2EnterInitializationMode", |i| {
        i.phase = Phase::Initialization;
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> Status {
    with_instance(c, "fmi2ExitInitializationMode", |i| {
        i.phase = Phase::Running;
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2Terminate(c: *mut c_void) -> Status {
    with_instance(c, "fmi2Terminate", |i| {
        i.phase = Phase::Terminated;
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2Reset(c: *mut c_void) -> Status {
    with_instance(c, "fmi2Reset", |i| {
        i.model.reset();
        i.phase = Phase::Instantiated;
        OK
    })
}

/// `fmi2GetReal`: inputs as set, outputs evaluated at the current inputs (once per change).
#[no_mangle]
pub extern "C" fn fmi2GetReal(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut f64,
) -> Status {
    const F: &str = "fmi2GetReal";
    with_instance(c, F, |i| {
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice_mut(value, nvr) })
        else {
            return i.fail(F, &format!("null vr or value array with nvr = {nvr}"));
        };
        let mut status = OK;
        for (r, v) in vr.iter().zip(value.iter_mut()) {
            match i.model.get_real(*r) {
                Ok((x, warning)) => {
                    *v = x;
                    if let Some(w) = warning {
                        i.log(WARNING, &format!("{F}: {w}"));
                        status = WARNING;
                    }
                }
                Err(e) => return i.fail(F, &e),
            }
        }
        status
    })
}

/// `fmi2SetReal`: the inputs; a non-finite value or a value reference that is not an input is an
/// error naming the variable.
#[no_mangle]
pub extern "C" fn fmi2SetReal(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *const f64,
) -> Status {
    const F: &str = "fmi2SetReal";
    with_instance(c, F, |i| {
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice(value, nvr) })
        else {
            return i.fail(F, &format!("null vr or value array with nvr = {nvr}"));
        };
        for (r, v) in vr.iter().zip(value) {
            if let Err(e) = i.model.set_real(*r, *v) {
                return i.fail(F, &e);
            }
        }
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2GetInteger(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut c_int,
) -> Status {
    const F: &str = "fmi2GetInteger";
    with_instance(c, F, |i| {
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice_mut(value, nvr) })
        else {
            return i.fail(F, &format!("null vr or value array with nvr = {nvr}"));
        };
        for (r, v) in vr.iter().zip(value.iter_mut()) {
            *v = match *r {
                VR_ELEMENT_KIND => i.model.loaded.kind as c_int,
                VR_BALL_COUNT => i.model.loaded.element.ball_count() as c_int,
                _ => {
                    return i.fail(
                        F,
                        &format!(
                            "value reference {r} is not an Integer variable of this FMU (0 element_kind, 1 ball_count)"
                        ),
                    )
                }
            };
        }
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetInteger(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    _value: *const c_int,
) -> Status {
    const F: &str = "fmi2SetInteger";
    with_instance(c, F, |i| {
        if nvr == 0 {
            return OK;
        }
        let first = unsafe { slice(vr, nvr) }.map(|v| v[0]);
        i.fail(
            F,
            &format!(
                "value reference {first:?}: the Integer variables (element_kind, ball_count) are calculated parameters and cannot be set"
            ),
        )
    })
}

#[no_mangle]
pub extern "C" fn fmi2GetBoolean(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut c_int,
) -> Status {
    const F: &str = "fmi2GetBoolean";
    with_instance(c, F, |i| {
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice_mut(value, nvr) })
        else {
            return i.fail(F, &format!("null vr or value array with nvr = {nvr}"));
        };
        for (r, v) in vr.iter().zip(value.iter_mut()) {
            if *r != VR_WARM_START {
                return i.fail(
                    F,
                    &format!(
                        "value reference {r} is not a Boolean variable of this FMU (0 warm_start)"
                    ),
                );
            }
            *v = c_int::from(i.model.warm_start);
        }
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetBoolean(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *const c_int,
) -> Status {
    const F: &str = "fmi2SetBoolean";
    with_instance(c, F, |i| {
        let (Some(vr), Some(value)) = (unsafe { slice(vr, nvr) }, unsafe { slice(value, nvr) })
        else {
            return i.fail(F, &format!("null vr or value array with nvr = {nvr}"));
        };
        for (r, v) in vr.iter().zip(value) {
            if *r != VR_WARM_START {
                return i.fail(
                    F,
                    &format!(
                        "value reference {r} is not a Boolean variable of this FMU (0 warm_start)"
                    ),
                );
            }
            if !matches!(i.phase, Phase::Instantiated | Phase::Initialization) {
                return i.fail(
                    F,
                    "warm_start is a fixed parameter: set it before fmi2ExitInitializationMode",
                );
            }
            i.model.warm_start = *v != 0;
        }
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2GetString(
    c: *mut c_void,
    _vr: *const c_uint,
    nvr: usize,
    _value: *mut *const c_char,
) -> Status {
    with_instance(c, "fmi2GetString", |i| {
        if nvr == 0 {
            OK
        } else {
            i.fail("fmi2GetString", "this FMU has no String variables")
        }
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetString(
    c: *mut c_void,
    _vr: *const c_uint,
    nvr: usize,
    _value: *const *const c_char,
) -> Status {
    with_instance(c, "fmi2SetString", |i| {
        if nvr == 0 {
            OK
        } else {
            i.fail("fmi2SetString", "this FMU has no String variables")
        }
    })
}

fn not_supported(c: *mut c_void, function: &str, what: &str) -> Status {
    with_instance(c, function, |i| i.fail(function, what))
}

#[no_mangle]
pub extern "C" fn fmi2GetFMUstate(c: *mut c_void, _state: *mut *mut c_void) -> Status {
    not_supported(
        c,
        "fmi2GetFMUstate",
        "not supported (canGetAndSetFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2SetFMUstate(c: *mut c_void, _state: *mut c_void) -> Status {
    not_supported(
        c,
        "fmi2SetFMUstate",
        "not supported (canGetAndSetFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2FreeFMUstate(c: *mut c_void, _state: *mut *mut c_void) -> Status {
    not_supported(
        c,
        "fmi2FreeFMUstate",
        "not supported (canGetAndSetFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2SerializedFMUstateSize(
    c: *mut c_void,
    _state: *mut c_void,
    _size: *mut usize,
) -> Status {
    not_supported(
        c,
        "fmi2SerializedFMUstateSize",
        "not supported (canSerializeFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2SerializeFMUstate(
    c: *mut c_void,
    _state: *mut c_void,
    _bytes: *mut c_char,
    _size: usize,
) -> Status {
    not_supported(
        c,
        "fmi2SerializeFMUstate",
        "not supported (canSerializeFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2DeSerializeFMUstate(
    c: *mut c_void,
    _bytes: *const c_char,
    _size: usize,
    _state: *mut *mut c_void,
) -> Status {
    not_supported(
        c,
        "fmi2DeSerializeFMUstate",
        "not supported (canSerializeFMUstate = false)",
    )
}

#[no_mangle]
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: *mut c_void,
    _unknown: *const c_uint,
    _n_unknown: usize,
    _known: *const c_uint,
    _n_known: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> Status {
    not_supported(
        c,
        "fmi2GetDirectionalDerivative",
        "not provided (providesDirectionalDerivative = false); the outputs K_* and C_* are the derivatives of the reactions",
    )
}

#[no_mangle]
pub extern "C" fn fmi2EnterEventMode(c: *mut c_void) -> Status {
    with_instance(c, "fmi2EnterEventMode", |_| OK)
}

#[no_mangle]
pub extern "C" fn fmi2NewDiscreteStates(c: *mut c_void, info: *mut EventInfo) -> Status {
    with_instance(c, "fmi2NewDiscreteStates", |i| {
        if info.is_null() {
            return i.fail("fmi2NewDiscreteStates", "null fmi2EventInfo pointer");
        }
        // SAFETY: non-null, the importer's struct (FMI contract).
        unsafe { *info = EventInfo::default() };
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2EnterContinuousTimeMode(c: *mut c_void) -> Status {
    with_instance(c, "fmi2EnterContinuousTimeMode", |_| OK)
}

#[no_mangle]
pub extern "C" fn fmi2CompletedIntegratorStep(
    c: *mut c_void,
    _no_set_prior: c_int,
    enter_event_mode: *mut c_int,
    terminate_simulation: *mut c_int,
) -> Status {
    with_instance(c, "fmi2CompletedIntegratorStep", |i| {
        if enter_event_mode.is_null() || terminate_simulation.is_null() {
            return i.fail("fmi2CompletedIntegratorStep", "null output pointer");
        }
        // SAFETY: non-null, the importer's variables (FMI contract).
        unsafe {
            *enter_event_mode = 0;
            *terminate_simulation = 0;
        }
        OK
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetTime(c: *mut c_void, _time: f64) -> Status {
    with_instance(c, "fmi2SetTime", |_| OK)
}

fn no_states(c: *mut c_void, function: &str, n: usize) -> Status {
    with_instance(c, function, |i| {
        if n == 0 {
            OK
        } else {
            i.fail(
                function,
                &format!("n = {n}: this FMU has no continuous states and no event indicators (0)"),
            )
        }
    })
}

#[no_mangle]
pub extern "C" fn fmi2SetContinuousStates(c: *mut c_void, _x: *const f64, nx: usize) -> Status {
    no_states(c, "fmi2SetContinuousStates", nx)
}

#[no_mangle]
pub extern "C" fn fmi2GetDerivatives(c: *mut c_void, _dx: *mut f64, nx: usize) -> Status {
    no_states(c, "fmi2GetDerivatives", nx)
}

#[no_mangle]
pub extern "C" fn fmi2GetEventIndicators(c: *mut c_void, _z: *mut f64, ni: usize) -> Status {
    no_states(c, "fmi2GetEventIndicators", ni)
}

#[no_mangle]
pub extern "C" fn fmi2GetContinuousStates(c: *mut c_void, _x: *mut f64, nx: usize) -> Status {
    no_states(c, "fmi2GetContinuousStates", nx)
}

#[no_mangle]
pub extern "C" fn fmi2GetNominalsOfContinuousStates(
    c: *mut c_void,
    _x: *mut f64,
    nx: usize,
) -> Status {
    no_states(c, "fmi2GetNominalsOfContinuousStates", nx)
}

#[cfg(test)]
mod tests;
