//! Helper of the FMU route (scripts/build_fmu.sh, scripts/test_fmi.sh):
//!
//! - `ehl-bearing-fmu model-description OUT.xml`: modelDescription.xml from the variable table.
//! - `ehl-bearing-fmu inputs CASE.toml STEPS DT OUT.csv`: an input table (time and the 13 inputs)
//!   around the dry Hertz equilibrium of the case: displacements and rates oscillating, the inner
//!   speed ramping by 20 %, the cage turning at its speed.
//! - `ehl-bearing-fmu reference RESOURCES_DIR IN.csv OUT.csv`: the library's outputs at every row
//!   of IN.csv (columns named as the FMU's inputs), each evaluation from scratch, built from the
//!   resource files with the library's own calls (not through the FMU's code).
//! - `ehl-bearing-fmu bench RESOURCES_DIR [CALLS]`: time per call through the C functions
//!   (fmi2SetReal of the 13 inputs, fmi2GetReal of reactions, K and C) next to the library's
//!   `ForceElement::evaluate` on the same inputs, both warm; CPU time of the thread (robust to
//!   other load) and wall time (best and median of 5 rounds).

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws};
use ehl_bearing::characterize::CharacterizationReport;
use ehl_bearing::force_element::{
    ElementInput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::read_case;
use ehl_bearing_fmi::variables::{self, variables, Causality, N_INPUTS, N_REAL};
use ehl_bearing_fmi::{model, CallbackFunctions, MODEL_EXCHANGE, OK};
use std::ffi::CString;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

type Res<T> = Result<T, String>;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let r = match args.first().map(String::as_str) {
        Some("model-description") if args.len() == 2 => {
            std::fs::write(&args[1], variables::model_description()).map_err(|e| e.to_string())
        }
        Some("inputs") if args.len() == 5 => inputs(&args[1], &args[2], &args[3], &args[4]),
        Some("reference") if args.len() == 4 => reference(&args[1], &args[2], &args[3]),
        Some("bench") if (2..=3).contains(&args.len()) => bench(&args[1], args.get(2)),
        _ => Err("usage: ehl-bearing-fmu model-description OUT.xml | inputs CASE.toml STEPS DT OUT.csv | reference RESOURCES_DIR IN.csv OUT.csv | bench RESOURCES_DIR [CALLS]".into()),
    };
    if let Err(e) = r {
        eprintln!("ehl-bearing-fmu: {e}");
        std::process::exit(1);
    }
}

fn input_names() -> Vec<&'static str> {
    variables()
        .iter()
        .filter(|v| v.causality == Causality::Input)
        .map(|v| v.name.as_str())
        .collect()
}

fn output_names() -> Vec<&'static str> {
    (N_INPUTS..N_REAL)
        .map(|vr| variables::real_variable(vr).unwrap().name.as_str())
        .collect()
}

/// The dry Hertz equilibrium input of a case (rates zero, cage angle 0).
fn equilibrium_input(case_path: &str) -> Res<(ElementInput, f64)> {
    let case = read_case(Path::new(case_path)).map_err(|e| e.to_string())?;
    let laws = ContactLaws::hertz(&case.bearing).map_err(|e| e.to_string())?;
    let q = solve_equilibrium(&case.bearing, &laws, &case.operating, &case.settings)
        .map_err(|e| e.to_string())?
        .displacement;
    let e = LawElement::hertz_case(&case).map_err(|e| e.to_string())?;
    let input = ElementInput::at(q, case.operating.inner_speed, case.operating.outer_speed);
    // The cage turns at the operating cage speed of the bearing model.
    let cage = e
        .evaluate(&input, &mut ElementState::default())
        .map_err(|e| e.to_string())?
        .cage_speed;
    Ok((input, cage))
}

fn inputs(case_path: &str, steps: &str, dt: &str, out: &str) -> Res<()> {
    let steps: usize = steps.parse().map_err(|_| format!("STEPS = {steps:?}"))?;
    let dt: f64 = dt.parse().map_err(|_| format!("DT = {dt:?}"))?;
    let (q0, cage) = equilibrium_input(case_path)?;
    let mut csv = String::from("time");
    for n in input_names() {
        let _ = write!(csv, ",{n}");
    }
    csv.push('\n');
    let t_end = steps as f64 * dt;
    let w = 2.0 * std::f64::consts::PI / t_end.max(f64::MIN_POSITIVE);
    // Amplitudes: 2 µm, 1 µm, 1 µm, 1e-4 rad, 1e-4 rad about the equilibrium.
    let amp = [2e-6, 1e-6, 1e-6, 1e-4, 1e-4];
    for k in 0..=steps {
        let t = k as f64 * dt;
        let mut row = vec![t];
        for (j, a) in amp.iter().enumerate() {
            let phase = j as f64;
            row.push(q0.displacement[j] + a * (w * t + phase).sin());
        }
        for (j, a) in amp.iter().enumerate() {
            let phase = j as f64;
            row.push(a * w * (w * t + phase).cos());
        }
        let inner = q0.inner_speed * (1.0 + 0.2 * t / t_end);
        row.push(inner);
        row.push(q0.outer_speed);
        row.push(cage * t);
        let line: Vec<String> = row.iter().map(|x| format!("{x:e}")).collect();
        csv.push_str(&line.join(","));
        csv.push('\n');
    }
    std::fs::write(out, csv).map_err(|e| format!("{out}: {e}"))
}

/// The element of a resources folder, built with the library's calls.
fn element(dir: &Path) -> Res<Box<dyn ForceElement>> {
    let trends = dir.join(model::TRENDS_FILE);
    let ch = dir.join(model::CHARACTERIZATION_FILE);
    let read =
        |p: &PathBuf| std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()));
    if trends.is_file() {
        return Ok(Box::new(
            TrendForceElement::from_json(&read(&trends)?).map_err(|e| e.to_string())?,
        ));
    }
    let case = read_case(&dir.join(model::CASE_FILE)).map_err(|e| e.to_string())?;
    if ch.is_file() {
        let report: CharacterizationReport =
            serde_json::from_str(&read(&ch)?).map_err(|e| e.to_string())?;
        let e = LawElement::from_report(&case.bearing, case.operating.race_control, &report)
            .map_err(|e| e.to_string())?
            .with_kinematics(case.settings.kinematics);
        return Ok(Box::new(e));
    }
    Ok(Box::new(
        LawElement::hertz_case(&case).map_err(|e| e.to_string())?,
    ))
}

fn reference(dir: &str, input: &str, out: &str) -> Res<()> {
    let element = element(Path::new(dir))?;
    let text = std::fs::read_to_string(input).map_err(|e| format!("{input}: {e}"))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .ok_or("empty input table")?
        .split(',')
        .map(|s| s.trim().trim_matches('"'))
        .collect();
    let cols: Vec<usize> = input_names()
        .iter()
        .map(|n| {
            header
                .iter()
                .position(|h| h == n)
                .ok_or_else(|| format!("{input}: no column {n}"))
        })
        .collect::<Res<_>>()?;
    let time = header.iter().position(|h| *h == "time");
    let mut csv = String::from("time");
    for n in output_names() {
        let _ = write!(csv, ",{n}");
    }
    csv.push('\n');
    let mut real = vec![0.0; N_REAL as usize];
    for (row, line) in lines.enumerate() {
        let v: Vec<f64> = line
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("{input} row {}: {e}", row + 2))?;
        let x = |k: usize| v[cols[k]];
        let i = ElementInput {
            displacement: [x(0), x(1), x(2), x(3), x(4)],
            velocity: [x(5), x(6), x(7), x(8), x(9)],
            inner_speed: x(10),
            outer_speed: x(11),
            cage_angle: x(12),
        };
        let o = element
            .evaluate(&i, &mut ElementState::default())
            .map_err(|e| format!("row {}: {e}", row + 2))?;
        model::write_outputs(&mut real, &o);
        let _ = write!(csv, "{:e}", time.map(|t| v[t]).unwrap_or(row as f64));
        for r in &real[N_INPUTS as usize..] {
            // Shortest round-trip representation: the comparison sees every bit.
            let _ = write!(csv, ",{r:e}");
        }
        csv.push('\n');
    }
    std::fs::write(out, csv).map_err(|e| format!("{out}: {e}"))
}

/// CPU time of this thread, s (Linux: /proc/thread-self/schedstat; NaN elsewhere): unlike wall
/// time, not inflated by other load on a shared machine.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

fn bench(dir: &str, calls: Option<&String>) -> Res<()> {
    let calls: usize = match calls {
        Some(c) => c.parse().map_err(|_| format!("CALLS = {c:?}"))?,
        None => 20_000,
    };
    let dir = Path::new(dir)
        .canonicalize()
        .map_err(|e| format!("{dir}: {e}"))?;
    let case = dir.join(model::CASE_FILE);
    let (q0, cage) = equilibrium_input(case.to_str().ok_or("non-UTF-8 path")?)?;
    let mut base = q0;
    base.velocity = [1e-4, -2e-4, 1e-4, 1e-3, -1e-3];
    let dt = 1e-5;
    // The rotor step of `cargo bench --bench force_element`: the position moves by ≤ 10 nm, the
    // cage turns.
    let input_at = |step: usize| {
        let mut i = base;
        let t = step as f64 * dt;
        i.displacement[1] += 1e-8 * (1e3 * t).sin();
        i.cage_angle = cage * t;
        i
    };
    // Through the C functions (called in-process: the same code the FMU's .so exports).
    let functions = CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: std::ptr::null_mut(),
    };
    let uri = CString::new(format!("file://{}", dir.display())).unwrap();
    let guid = CString::new(variables::guid()).unwrap();
    let c = ehl_bearing_fmi::fmi2Instantiate(
        c"bench".as_ptr(),
        MODEL_EXCHANGE,
        guid.as_ptr(),
        uri.as_ptr(),
        &functions,
        0,
        0,
    );
    if c.is_null() {
        return Err(format!("fmi2Instantiate failed for {}", dir.display()));
    }
    ehl_bearing_fmi::fmi2EnterInitializationMode(c);
    ehl_bearing_fmi::fmi2ExitInitializationMode(c);
    let in_vr: Vec<u32> = (0..N_INPUTS).collect();
    let out_vr: Vec<u32> = (variables::VR_REACTION..variables::VR_C + 25).collect();
    let mut out = vec![0.0; out_vr.len()];
    let mut fmi_call = |step: usize| -> Res<()> {
        let i = input_at(step);
        let mut v = [0.0; 13];
        v[..5].copy_from_slice(&i.displacement);
        v[5..10].copy_from_slice(&i.velocity);
        v[10..].copy_from_slice(&[i.inner_speed, i.outer_speed, i.cage_angle]);
        let s1 = ehl_bearing_fmi::fmi2SetReal(c, in_vr.as_ptr(), 13, v.as_ptr());
        let s2 = ehl_bearing_fmi::fmi2GetReal(c, out_vr.as_ptr(), out_vr.len(), out.as_mut_ptr());
        if s1 != OK || s2 != OK {
            return Err(format!("step {step}: status {s1}, {s2}"));
        }
        Ok(())
    };
    let element = element(&dir)?;
    let mut state = ElementState::default();
    let mut lib_call = |step: usize| -> Res<()> {
        std::hint::black_box(
            element
                .evaluate(&input_at(step), &mut state)
                .map_err(|e| e.to_string())?,
        );
        Ok(())
    };
    // Warm up both, then alternate rounds so that load changes hit both alike.
    for s in 0..calls / 10 {
        fmi_call(s)?;
        lib_call(s)?;
    }
    let rounds = 5;
    let (mut t_fmi, mut t_lib) = (Vec::new(), Vec::new());
    let (mut c_fmi, mut c_lib) = (0.0, 0.0);
    let mut step = calls / 10;
    for _ in 0..rounds {
        let n = calls / rounds;
        let (t, c) = (Instant::now(), cpu_seconds());
        for s in step..step + n {
            fmi_call(s)?;
        }
        t_fmi.push(t.elapsed().as_secs_f64() / n as f64);
        c_fmi += (cpu_seconds() - c) / calls as f64;
        let (t, c) = (Instant::now(), cpu_seconds());
        for s in step..step + n {
            lib_call(s)?;
        }
        t_lib.push(t.elapsed().as_secs_f64() / n as f64);
        c_lib += (cpu_seconds() - c) / calls as f64;
        step += n;
    }
    ehl_bearing_fmi::fmi2Terminate(c);
    ehl_bearing_fmi::fmi2FreeInstance(c);
    // Best and median of the rounds, µs per call (the best is the least disturbed by other load
    // on the machine).
    let stats = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[0] * 1e6, v[v.len() / 2] * 1e6)
    };
    let ((f, fm), (l, lm)) = (stats(&mut t_fmi), stats(&mut t_lib));
    println!(
        "{{\"calls\": {calls}, \"rounds\": {rounds}, \"fmi_us_per_call_cpu\": {:.2}, \"library_us_per_call_cpu\": {:.2}, \"fmi_us_per_call_wall_best\": {f:.2}, \"library_us_per_call_wall_best\": {l:.2}, \"fmi_us_per_call_wall_median\": {fm:.2}, \"library_us_per_call_wall_median\": {lm:.2}}}",
        c_fmi * 1e6,
        c_lib * 1e6
    );
    Ok(())
}
