"""FMPy side of scripts/test_fmi.sh: simulate an FMU with FMPy driving its 13 inputs from a table,
record the inputs the unit saw and its outputs, compare the outputs with the library's (the
reference written by `ehl-bearing-fmu reference` for the recorded inputs), and time calls through
FMPy's low-level API.

usage: python fmi_check.py simulate FMU INPUTS.csv HELPER OUT_DIR TOL [--cold]
       python fmi_check.py time FMU INPUTS.csv CALLS
       python fmi_check.py errors FMU
"""

import csv
import sys
import time

import numpy as np
from fmpy import read_model_description, simulate_fmu


def read_table(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    names = rows[0]
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    return names, data


def write_table(path, names, columns):
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for row in zip(*columns):
            f.write(",".join(repr(float(x)) for x in row) + "\n")


def simulate(fmu, inputs_csv, helper, out_dir, tol, cold):
    import subprocess

    from fmpy import extract

    # The reference reads the very files inside the FMU.
    resources = str(extract(fmu)) + "/resources"

    md = read_model_description(fmu)
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    names, data = read_table(inputs_csv)
    signals = np.array(
        [tuple(r) for r in data],
        dtype=[(n, np.float64) for n in names],
    )
    t = data[:, 0]
    dt = t[1] - t[0]
    start = time.perf_counter()
    result = simulate_fmu(
        fmu,
        start_time=t[0],
        stop_time=t[-1],
        solver="Euler",
        step_size=dt,
        output_interval=dt,
        input=signals,
        output=inputs + outputs,
        start_values={"warm_start": False} if cold else {},
        validate=True,
    )
    elapsed = time.perf_counter() - start
    tag = fmu.rsplit("/", 1)[-1].removesuffix(".fmu") + ("_cold" if cold else "")
    recorded = f"{out_dir}/{tag}_recorded_inputs.csv"
    write_table(recorded, ["time"] + inputs, [result["time"]] + [result[n] for n in inputs])
    expected = f"{out_dir}/{tag}_expected.csv"
    subprocess.run([helper, "reference", resources, recorded, expected], check=True)
    enames, edata = read_table(expected)
    assert enames[1:] == outputs, "output order of the reference and the FMU"
    worst = (0.0, "")
    exact = 0
    for k, name in enumerate(outputs):
        got = result[name]
        want = edata[:, k + 1]
        assert got.shape == want.shape, (name, got.shape, want.shape)
        # Relative to the column's largest magnitude (entries near zero of a column that is not
        # would otherwise inflate the figure).
        scale = max(np.max(np.abs(want)), 1e-300)
        err = float(np.max(np.abs(got - want)) / scale)
        exact += int(np.array_equal(got, want))
        if err > worst[0]:
            worst = (err, name)
    rows = len(result)
    print(
        f"  {tag}: {rows} time points x {len(outputs)} outputs; FMPy simulation {elapsed:.2f} s; "
        f"{exact}/{len(outputs)} output columns bit-identical to the library; "
        f"largest relative difference {worst[0]:.2e}{' (' + worst[1] + ')' if worst[1] else ''} "
        f"(tolerance {tol:g})"
    )
    if not worst[0] <= tol:
        sys.exit(f"FAILED: {tag} differs from the library by {worst[0]:.3e} > {tol:g}")
    for flag in ("overloaded_contacts",):
        if np.any(result[flag] > 0):
            sys.exit(f"FAILED: {tag}: {flag} > 0 on the test path")


def time_calls(fmu, inputs_csv, calls):
    """fmi2SetReal (13 inputs) + fmi2GetReal (reactions, K, C) through FMPy's ctypes API."""
    from fmpy import extract
    from fmpy.fmi2 import FMU2Model

    md = read_model_description(fmu)
    unzipdir = extract(fmu)
    m = FMU2Model(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.modelExchange.modelIdentifier,
        instanceName="timing",
    )
    m.instantiate()
    m.setupExperiment(startTime=0.0)
    m.enterInitializationMode()
    m.exitInitializationMode()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    names, data = read_table(inputs_csv)
    in_vr = [vr[n] for n in names[1:]]
    out_vr = [
        v.valueReference
        for v in md.modelVariables
        if v.name.startswith(("reaction_", "K_", "C_"))
    ]
    rows = [list(r[1:]) for r in data]
    # Warm up, then time: the inputs walk along the table (small steps, as a rotor integrator's).
    for r in rows[:50]:
        m.setReal(in_vr, r)
        m.getReal(out_vr)
    # CPU time of the process (not inflated by other load on a shared machine).
    start = time.process_time()
    for k in range(calls):
        m.setReal(in_vr, rows[k % len(rows)])
        m.getReal(out_vr)
    per_call = (time.process_time() - start) / calls
    # Python's share: the same calls with unchanged inputs (no evaluation: outputs cached).
    start = time.process_time()
    r = rows[0]
    m.setReal(in_vr, r)
    m.getReal(out_vr)
    for k in range(calls):
        m.setReal(in_vr, r)
        m.getReal(out_vr)
    cached = (time.process_time() - start) / calls
    m.terminate()
    m.freeInstance()
    print(
        f"  FMPy low-level API, {calls} calls of fmi2SetReal(13) + fmi2GetReal(55): "
        f"{per_call * 1e6:.1f} us CPU per call; {cached * 1e6:.1f} us of it Python and ctypes "
        f"(same calls, inputs unchanged, no evaluation)"
    )


def errors(fmu):
    """Errors reach FMPy's calls as fmi2Error with the unit's message in the importer's logger."""
    import math

    from fmpy import extract
    from fmpy.fmi1 import FMICallException
    from fmpy.fmi2 import FMU2Model, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE

    messages = []

    def log(env, name, status, category, message):
        messages.append((status, message.decode()))

    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(log)
    md = read_model_description(fmu)
    m = FMU2Model(
        guid=md.guid,
        unzipDirectory=extract(fmu),
        modelIdentifier=md.modelExchange.modelIdentifier,
        instanceName="errors",
    )
    m.instantiate(callbacks=callbacks)
    m.setupExperiment(startTime=0.0)
    m.enterInitializationMode()
    m.exitInitializationMode()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    try:
        m.setReal([vr["q_y_m"]], [math.nan])
        sys.exit("FAILED: fmi2SetReal accepted NaN")
    except FMICallException as e:
        assert e.status == 3, e
    status, text = messages[-1]
    assert status == 3 and "q_y_m = NaN: the input must be a finite number (m)" in text, messages
    print(f"  NaN input: fmi2Error, logged: {text}")
    # A tilt of 1 rad: contacts far beyond 2 % of the ball diameter → fmi2Warning, flagged.
    m.setReal([vr["q_thy_rad"], vr["inner_speed_rad_s"]], [1.0, 500.0])
    (n,) = m.getReal([vr["overloaded_contacts"]])
    status, text = messages[-1]
    assert n > 0 and status == 1 and "beyond 2 percent of the ball diameter" in text, (n, messages)
    print(f"  overloaded: overloaded_contacts = {n:g}, fmi2Warning, logged: {text[:90]}...")
    m.terminate()
    m.freeInstance()


if __name__ == "__main__":
    if sys.argv[1] == "simulate":
        fmu, inputs_csv, helper, out_dir, tol = sys.argv[2:7]
        simulate(fmu, inputs_csv, helper, out_dir, float(tol), "--cold" in sys.argv)
    elif sys.argv[1] == "errors":
        errors(sys.argv[2])
    elif sys.argv[1] == "time":
        time_calls(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        sys.exit(__doc__)
