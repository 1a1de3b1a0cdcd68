//! The C functions called directly: instantiation from resources, set/get against the library,
//! and the error paths (bad resources, GUID, type, non-finite inputs, wrong value references,
//! null pointers), each with its logged message.

use super::*;
use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::force_element::{ElementInput, ElementState, ForceElement, LawElement};
use ehl_bearing::io::parse_case;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

const SEED: &str = include_str!("../../../examples/7006.toml");
const REPORT: &str =
    include_str!("../../ehl-bearing-py/tests/data/fitted_7006_3000rpm_harmonic.json");
const TRENDS: &str = include_str!("../../../docs/figures/study_7006_quasi_static_trends.json");

type Log = Mutex<Vec<(Status, String)>>;

extern "C" fn logger(
    env: *mut c_void,
    _name: *const c_char,
    status: Status,
    _category: *const c_char,
    message: *const c_char,
) {
    let log = unsafe { &*(env as *const Log) };
    let m = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    log.lock().unwrap().push((status, m));
}

/// A fresh resources folder with `files` (name, text).
fn resources(files: &[(&str, &str)]) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "ehl-bearing-fmi-test-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

struct Fmu {
    c: *mut c_void,
    log: Box<Log>,
    _functions: Box<CallbackFunctions>,
}

impl Fmu {
    fn try_new(dir: &Path, guid: &str, fmu_type: c_int) -> Result<Fmu, Vec<(Status, String)>> {
        let log: Box<Log> = Box::default();
        // SAFETY: a non-variadic logger called without variadic arguments (as FMPy's is).
        let l = unsafe {
            std::mem::transmute::<
                extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char),
                Logger,
            >(logger)
        };
        let functions = Box::new(CallbackFunctions {
            logger: Some(l),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: &*log as *const Log as *mut c_void,
        });
        let uri = c_string(&format!("file://{}", dir.display()));
        let guid = c_string(guid);
        let c = fmi2Instantiate(
            c"bearing".as_ptr(),
            fmu_type,
            guid.as_ptr(),
            uri.as_ptr(),
            &*functions,
            0,
            1,
        );
        if c.is_null() {
            return Err(log.lock().unwrap().clone());
        }
        Ok(Fmu {
            c,
            log,
            _functions: functions,
        })
    }

    fn new(dir: &Path) -> Fmu {
        let f = Fmu::try_new(dir, variables::guid(), MODEL_EXCHANGE).unwrap();
        assert_eq!(fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(f.c), OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), OK);
        f
    }

    fn set(&self, vr: &[u32], v: &[f64]) -> Status {
        fmi2SetReal(self.c, vr.as_ptr(), vr.len(), v.as_ptr())
    }

    fn get(&self, vr: &[u32]) -> (Status, Vec<f64>) {
        let mut v = vec![f64::NAN; vr.len()];
        let s = fmi2GetReal(self.c, vr.as_ptr(), vr.len(), v.as_mut_ptr());
        (s, v)
    }

    fn set_input(&self, input: &ElementInput) -> Status {
        let mut v = Vec::new();
        v.extend_from_slice(&input.displacement);
        v.extend_from_slice(&input.velocity);
        v.extend([input.inner_speed, input.outer_speed, input.cage_angle]);
        self.set(&(0..N_INPUTS).collect::<Vec<_>>(), &v)
    }

    fn last_message(&self) -> String {
        self.log
            .lock()
            .unwrap()
            .last()
            .map(|m| m.1.clone())
            .unwrap_or_default()
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        assert_eq!(fmi2Terminate(self.c), OK);
        fmi2FreeInstance(self.c);
    }
}

/// A loaded position: the dry Hertz equilibrium of the seed case, with rates and a turned cage.
fn seed_input() -> ElementInput {
    let case = parse_case(SEED, "7006.toml").unwrap();
    let q = solve_equilibrium(
        &case.bearing,
        &ContactLaws::hertz(&case.bearing).unwrap(),
        &case.operating,
        &case.settings,
    )
    .unwrap()
    .displacement;
    let mut input = ElementInput::at(q, case.operating.inner_speed, 0.0);
    input.velocity = [1e-4, -2e-4, 1e-4, 1e-3, -1e-3];
    input.cage_angle = 0.1;
    input
}

fn all_outputs() -> Vec<u32> {
    (N_INPUTS..N_REAL).collect()
}

/// The FMU's outputs equal the library's, bit for bit, for the same (cold) evaluation.
fn check_against(fmu: &Fmu, element: &dyn ForceElement, input: &ElementInput) {
    assert_eq!(fmu.set_input(input), OK, "{}", fmu.last_message());
    let (s, got) = fmu.get(&all_outputs());
    assert_eq!(s, OK, "{}", fmu.last_message());
    let out = element
        .evaluate(input, &mut ElementState::default())
        .unwrap();
    let mut want = vec![0.0; N_REAL as usize];
    model::write_outputs(&mut want, &out);
    for (k, g) in got.iter().enumerate() {
        let vr = N_INPUTS as usize + k;
        assert_eq!(
            g.to_bits(),
            want[vr].to_bits(),
            "{}: {g} vs {}",
            real_variable(vr as u32).unwrap().name,
            want[vr]
        );
    }
    // The inputs read back as set.
    let (s, q) = fmu.get(&[VR_Q, VR_Q + 4, VR_CAGE_ANGLE]);
    assert_eq!(s, OK);
    assert_eq!(
        q,
        [
            input.displacement[0],
            input.displacement[4],
            input.cage_angle
        ]
    );
}

#[test]
fn dry_hertz_outputs_equal_the_library() {
    let dir = resources(&[("case.toml", SEED)]);
    let fmu = Fmu::new(&dir);
    let mut kind = [-1];
    assert_eq!(
        fmi2GetInteger(fmu.c, [VR_ELEMENT_KIND].as_ptr(), 1, kind.as_mut_ptr()),
        OK
    );
    assert_eq!(kind[0], 0);
    let case = parse_case(SEED, "7006.toml").unwrap();
    let element = LawElement::hertz_case(&case).unwrap();
    // Cold evaluations: the first call, and every call with warm_start = false.
    check_against(&fmu, &element, &seed_input());
    let (_, r) = fmu.get(&[VR_REACTION, VR_REACTION + 1, VR_K + 6]);
    assert!(r[0] > 500.0 && r[1] > 500.0 && r[2] > 1e7, "{r:?}");
    let (_, c) = fmu.get(&[VR_C, VR_C + 6]);
    assert_eq!(c, [0.0, 0.0], "dry Hertz has no damping");
    assert!(fmu.log.lock().unwrap()[0].1.contains("dry Hertz"));
}

#[test]
fn fitted_laws_outputs_equal_the_library() {
    let dir = resources(&[("case.toml", SEED), ("characterization.json", REPORT)]);
    let fmu = Fmu::new(&dir);
    let mut v = [0; 2];
    assert_eq!(
        fmi2GetInteger(
            fmu.c,
            [VR_ELEMENT_KIND, VR_BALL_COUNT].as_ptr(),
            2,
            v.as_mut_ptr()
        ),
        OK
    );
    assert_eq!(v, [1, 11]);
    let case = parse_case(SEED, "7006.toml").unwrap();
    let report = serde_json::from_str(REPORT).unwrap();
    let element = LawElement::from_report(&case.bearing, case.operating.race_control, &report)
        .unwrap()
        .with_kinematics(case.settings.kinematics);
    // Cold: set warm_start = false before initialization.
    assert_eq!(fmi2Reset(fmu.c), OK);
    assert_eq!(
        fmi2SetBoolean(fmu.c, [VR_WARM_START].as_ptr(), 1, [0].as_ptr()),
        OK
    );
    assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    let mut input = seed_input();
    for step in 0..5 {
        input.displacement[1] += 1e-7 * step as f64;
        input.cage_angle += 0.05;
        check_against(&fmu, &element, &input);
    }
    let (_, c) = fmu.get(&[VR_C + 6]);
    assert!(c[0] > 0.0, "fitted harmonic laws carry damping: {c:?}");
    // Warm starts change the results only within the solvers' tolerances.
    let warm = Fmu::new(&dir);
    let (_, want) = fmu.get(&all_outputs());
    let mut input2 = seed_input();
    input2.displacement[1] += 1.0e-6;
    assert_eq!(warm.set_input(&input2), OK);
    warm.get(&all_outputs());
    assert_eq!(warm.set_input(&input), OK);
    let (_, got) = warm.get(&all_outputs());
    for k in 0..5 {
        let scale = want[k].abs().max(1.0);
        assert!(
            (got[k] - want[k]).abs() <= 1e-9 * scale,
            "{k}: {got:?} {want:?}"
        );
    }
}

#[test]
fn trends_resource_gives_a_trend_element() {
    let dir = resources(&[("trends.json", TRENDS)]);
    let fmu = Fmu::new(&dir);
    let mut kind = [-1];
    assert_eq!(
        fmi2GetInteger(fmu.c, [VR_ELEMENT_KIND].as_ptr(), 1, kind.as_mut_ptr()),
        OK
    );
    assert_eq!(kind[0], 2);
    let element = ehl_bearing::force_element::TrendForceElement::from_json(TRENDS).unwrap();
    check_against(&fmu, &element, &seed_input());
}

#[test]
fn invalid_inputs_are_errors_naming_the_variable() {
    let dir = resources(&[("case.toml", SEED)]);
    let fmu = Fmu::new(&dir);
    assert_eq!(fmu.set(&[VR_Q + 1], &[f64::NAN]), ERROR);
    let m = fmu.last_message();
    assert!(
        m.contains("fmi2SetReal") && m.contains("q_y_m = NaN") && m.contains("finite"),
        "{m}"
    );
    assert_eq!(fmu.set(&[VR_INNER_SPEED], &[f64::INFINITY]), ERROR);
    assert!(
        fmu.last_message().contains("inner_speed_rad_s = inf"),
        "{}",
        fmu.last_message()
    );
    assert_eq!(fmu.set(&[VR_REACTION], &[1.0]), ERROR);
    assert!(fmu
        .last_message()
        .contains("reaction_Fx_N (value reference 13) is an output"));
    assert_eq!(fmu.set(&[500], &[1.0]), ERROR);
    assert!(fmu
        .last_message()
        .contains("value reference 500 is not a Real variable"));
    assert_eq!(fmu.get(&[N_REAL]).0, ERROR);
    // The values set before stay: the unit still evaluates.
    assert_eq!(fmu.set_input(&seed_input()), OK);
    assert_eq!(fmu.get(&[VR_REACTION]).0, OK);
    // Null arrays with values asked for, and a null instance.
    assert_eq!(
        fmi2GetReal(fmu.c, std::ptr::null(), 2, std::ptr::null_mut()),
        ERROR
    );
    assert!(fmu
        .last_message()
        .contains("null vr or value array with nvr = 2"));
    assert_eq!(
        fmi2GetReal(fmu.c, std::ptr::null(), 0, std::ptr::null_mut()),
        OK
    );
    assert_eq!(
        fmi2SetReal(std::ptr::null_mut(), [0].as_ptr(), 1, [0.0].as_ptr()),
        ERROR
    );
    assert_eq!(
        fmi2GetReal(std::ptr::null_mut(), [0].as_ptr(), 1, [0.0].as_mut_ptr()),
        ERROR
    );
    // Integer and Boolean errors.
    assert_eq!(fmi2SetInteger(fmu.c, [0].as_ptr(), 1, [1].as_ptr()), ERROR);
    assert_eq!(
        fmi2GetBoolean(fmu.c, [3].as_ptr(), 1, [0].as_mut_ptr()),
        ERROR
    );
    assert_eq!(
        fmi2SetBoolean(fmu.c, [VR_WARM_START].as_ptr(), 1, [0].as_ptr()),
        ERROR
    );
    assert!(fmu.last_message().contains("fixed parameter"));
    // Unsupported functions say so.
    assert_eq!(fmi2GetFMUstate(fmu.c, std::ptr::null_mut()), ERROR);
    assert!(fmu.last_message().contains("canGetAndSetFMUstate = false"));
    // No states: zero-length calls are fine.
    assert_eq!(fmi2GetDerivatives(fmu.c, std::ptr::null_mut(), 0), OK);
    assert_eq!(
        fmi2GetEventIndicators(fmu.c, std::ptr::null_mut(), 1),
        ERROR
    );
    let mut info = EventInfo {
        new_discrete_states_needed: 1,
        ..Default::default()
    };
    assert_eq!(fmi2NewDiscreteStates(fmu.c, &mut info), OK);
    assert_eq!(info.new_discrete_states_needed, 0);
}

#[test]
fn a_failing_evaluation_is_an_error_with_the_library_message() {
    let dir = resources(&[("case.toml", SEED), ("characterization.json", REPORT)]);
    let fmu = Fmu::new(&dir);
    let mut input = seed_input();
    // A tilt of 1 rad: the library either fails (message passed on) or flags the overload.
    input.displacement[3] = 1.0;
    assert_eq!(fmu.set_input(&input), OK);
    let (s, v) = fmu.get(&[VR_REACTION, VR_OVERLOADED]);
    let m = fmu.last_message();
    match s {
        ERROR => assert!(m.contains("force element evaluation failed at q = "), "{m}"),
        WARNING => {
            assert!(v[1] > 0.0 && m.contains("beyond 2 percent"), "{v:?} {m}");
            // Warned once: the next overloaded call is OK with the flag set.
            input.displacement[3] = 0.9;
            assert_eq!(fmu.set_input(&input), OK);
            let (s, v) = fmu.get(&[VR_OVERLOADED]);
            assert_eq!(s, OK);
            assert!(v[0] > 0.0);
        }
        _ => panic!("status {s}: {v:?}"),
    }
}

#[test]
fn bad_resources_type_and_guid_fail_instantiation_with_a_message() {
    let g = variables::guid();
    let empty = resources(&[]);
    let log = Fmu::try_new(&empty, g, MODEL_EXCHANGE).err().unwrap();
    assert!(
        log[0].0 == ERROR && log[0].1.contains("has none of case.toml"),
        "{log:?}"
    );
    let both = resources(&[
        ("case.toml", SEED),
        ("characterization.json", REPORT),
        ("trends.json", TRENDS),
    ]);
    let log = Fmu::try_new(&both, g, MODEL_EXCHANGE).err().unwrap();
    assert!(
        log[0]
            .1
            .contains("both characterization.json and trends.json"),
        "{log:?}"
    );
    let no_case = resources(&[("characterization.json", REPORT)]);
    let log = Fmu::try_new(&no_case, g, MODEL_EXCHANGE).err().unwrap();
    assert!(log[0].1.contains("no case.toml"), "{log:?}");
    let bad_case = resources(&[("case.toml", "[bearing]\nball_count = -3\n")]);
    let log = Fmu::try_new(&bad_case, g, MODEL_EXCHANGE).err().unwrap();
    assert!(log[0].1.contains("case.toml"), "{log:?}");
    let bad_json = resources(&[("case.toml", SEED), ("characterization.json", "{}")]);
    let log = Fmu::try_new(&bad_json, g, MODEL_EXCHANGE).err().unwrap();
    assert!(
        log[0].1.contains("not a characterization report"),
        "{log:?}"
    );
    let ok = resources(&[("case.toml", SEED)]);
    let log = Fmu::try_new(&ok, "{0}", MODEL_EXCHANGE).err().unwrap();
    assert!(
        log[0].1.contains("fmuGUID = Some(\"{0}\") does not match"),
        "{log:?}"
    );
    let log = Fmu::try_new(&ok, g, 1).err().unwrap();
    assert!(log[0].1.contains("model exchange only"), "{log:?}");
    // Null callbacks: null instance, no crash.
    let c = fmi2Instantiate(
        c"x".as_ptr(),
        MODEL_EXCHANGE,
        c"".as_ptr(),
        c"".as_ptr(),
        std::ptr::null(),
        0,
        0,
    );
    assert!(c.is_null());
    fmi2FreeInstance(std::ptr::null_mut());
    assert_eq!(
        unsafe { CStr::from_ptr(fmi2GetVersion()) }
            .to_str()
            .unwrap(),
        "2.0"
    );
}
