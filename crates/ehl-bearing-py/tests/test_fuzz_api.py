"""A fuzzer of the Python API: every public function and method, one or two arguments replaced by
a hostile value (NaN, ±inf, huge and tiny numbers, numpy scalars of every kind, wrong types,
arrays of wrong shapes and dtypes, huge arrays and lists, bad paths and texts), the others valid.

Every call must end in one of three ways: a result whose numbers are all finite (or, if not, that
came with a warning), or an exception of a documented kind (``ValueError``, including the
library's ``EhlBearingError``, ``TypeError``, ``OverflowError``) with a message. A panic of the
Rust code (pyo3's ``PanicException``), any other exception, a non-finite number returned without a
warning, or a call running longer than ``HANG_S`` (the process is then ended by ``faulthandler``,
printing where it hung) fails the test.

Fixed seed in the default run (``CASES`` calls, a few seconds). The many-case run:

    EHL_PY_FUZZ_CASES=20000 target/py-venv/bin/python -m pytest \
        crates/ehl-bearing-py/tests/test_fuzz_api.py -s

(``EHL_PY_FUZZ_SEED`` changes the seed; ``EHL_PY_FUZZ_ONE=i`` runs call ``i`` alone and prints it.)
"""

from __future__ import annotations

import collections
import faulthandler
import json
import math
import os
import pathlib
import random
import time
import warnings
from typing import Any, Callable

import numpy as np
import pytest

import ehl_bearing as eb
from ehl_bearing import plots

SEED = int(os.environ.get("EHL_PY_FUZZ_SEED", "11"))
CASES = int(os.environ.get("EHL_PY_FUZZ_CASES", "600"))
ONE = os.environ.get("EHL_PY_FUZZ_ONE")
MESSAGES = os.environ.get("EHL_PY_FUZZ_MESSAGES")  # a file to write every call's outcome to
HANG_S = 60.0
DATA = pathlib.Path(__file__).parent / "data"
REPO = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"


class UserStop(Exception):
    """Raised by the fuzzer's own progress callbacks: must come out of the call as it is."""


def stop(_event: Any) -> None:
    raise UserStop("the callback stops the run")


# Exceptions a caller may be handed for a bad value; each must carry a message.
CLEAR = (ValueError, TypeError, OverflowError, UserStop)

NAN = float("nan")
INF = float("inf")


class Opaque:
    """An object of no type the API knows."""

    def __repr__(self) -> str:
        return "<Opaque>"


WILD_SCALARS: list[Any] = [
    NAN,
    INF,
    -INF,
    0.0,
    -0.0,
    -1.0,
    1e300,
    -1e300,
    1e-300,
    5e-324,
    2**70,
    -(2**70),
    2**31,
    -1,
    0,
    np.float32("nan"),
    np.float64("inf"),
    np.float16(3.0),
    np.int64(-1),
    np.int64(2**62),
    np.uint64(2**64 - 1),
    np.int8(7),
    np.bool_(True),
    np.complex128(1j),
    1 + 2j,
    True,
    False,
    None,
    "",
    "abc",
    "nan",
    "1e300",
    "\x00",
    b"bytes",
    [],
    [1.0],
    {},
    {"a": 1},
    Opaque(),
]


def wild_array(rng: random.Random) -> Any:
    """Arrays and array-likes of wrong shape, dtype, contents or size."""
    k = rng.randrange(22)
    return [
        lambda: np.zeros(0),
        lambda: np.full(5, NAN),
        lambda: np.full(5, INF),
        lambda: np.full(5, 1e300),
        lambda: np.zeros(4),
        lambda: np.zeros(6),
        lambda: np.zeros((5, 1)),
        lambda: np.zeros((1, 5)),
        lambda: np.zeros((2, 5)),
        lambda: np.zeros((5, 5, 5)),
        lambda: np.zeros(5, dtype=complex),
        lambda: np.array(["a"] * 5),
        lambda: np.array([Opaque()] * 5, dtype=object),
        lambda: np.zeros(5, dtype=bool),
        lambda: np.zeros(5, dtype=np.int8),
        lambda: np.zeros(5, dtype=">f4"),
        lambda: np.zeros(2_000_000)[::2],  # huge and strided
        lambda: [NAN] * 5,
        lambda: (1, 2, 3, 4, "x"),
        lambda: [[0.0] * 5],
        lambda: np.ma.masked_array(np.zeros(5), mask=[1, 0, 0, 0, 0]),
        lambda: np.float64(0.0),  # a 0-d value where an array belongs
    ][k]()


def wild(rng: random.Random, valid: Any = None) -> Any:
    """A hostile value; sometimes a valid one scaled (near-valid), when one is given."""
    r = rng.random()
    if valid is not None and isinstance(valid, float) and r < 0.2:
        return valid * 10.0 ** rng.uniform(-12, 12) * rng.choice([1.0, -1.0])
    if r < 0.45:
        return wild_array(rng)
    return rng.choice(WILD_SCALARS)


def wild_text(rng: random.Random, valid: str) -> Any:
    """A TOML or JSON text mutated: random bytes, a cut, a value replaced, or a wild value."""
    k = rng.randrange(6)
    if k == 0:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(300))).decode("latin-1")
    if k == 1:
        return valid[: rng.randrange(len(valid) + 1)]
    if k == 2:
        # Replace one number by a wild number's text.
        words = valid.split("= ")
        if len(words) > 1:
            i = rng.randrange(1, len(words))
            rest = words[i].split("\n", 1)
            value = rng.choice(["nan", "inf", "-inf", "1e300", "-1", "0", "1e-300", '"x"', "[]"])
            words[i] = value + ("\n" + rest[1] if len(rest) > 1 else "")
            return "= ".join(words)
        return valid
    if k == 3:
        i = rng.randrange(len(valid) + 1)
        return valid[:i] + rng.choice(["[", "]", "=", '"', "\n[x]\n", "{", "}", ","]) + valid[i:]
    if k == 4:
        return valid * rng.choice([2, 3])  # duplicated keys and tables
    return wild(rng)


def wild_path(rng: random.Random, tmp: pathlib.Path) -> Any:
    return rng.choice(
        [
            "/dev/zero",
            "/dev/null",
            "/",
            "/nonexistent/case.toml",
            str(tmp / "binary.bin"),
            str(tmp / "huge.toml"),
            str(tmp),
            "",
            "\x00",
            pathlib.Path("/proc/self/mem"),
            wild(rng),
        ]
    )


def nonfinite(value: Any, path: str = "") -> str | None:
    """The path of the first non-finite number in a result, or None."""
    if isinstance(value, (bool, np.bool_)):
        return None
    if isinstance(value, (float, np.floating, complex, np.complexfloating)):
        return None if np.isfinite(value) else path or "."
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc" and not np.all(np.isfinite(value)):
            return path or "."
        return None
    if isinstance(value, dict):
        for k, v in value.items():
            p = nonfinite(v, f"{path}.{k}")
            if p:
                return p
    if isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            p = nonfinite(v, f"{path}[{i}]")
            if p:
                return p
    return None


class Env:
    """The valid values each call starts from (made once per session)."""

    def __init__(self, tmp: pathlib.Path) -> None:
        self.tmp = tmp
        self.case_toml = (EXAMPLES / "7006.toml").read_text()
        self.contact_toml = (EXAMPLES / "contact_7006_inner.toml").read_text()
        self.case = eb.Case.from_file(str(EXAMPLES / "7006.toml"))
        self.case_dict = {
            "bearing": {
                "ball_count": 11,
                "ball_diameter_mm": 7.0,
                "pitch_diameter_mm": 42.5,
                "inner_conformity": 0.51,
                "outer_conformity": 0.54,
                "contact_angle_deg": 15.0,
            },
            "operating": {"inner_speed_rpm": 5000.0, "force_axial_n": 1000.0},
        }
        self.hertz = eb.LawElement.hertz(self.case)
        self.case3000 = self.case.with_inner_speed_rpm(3000.0)
        self.report = json.loads((DATA / "fitted_7006_3000rpm_harmonic.json").read_text())
        self.fitted = eb.LawElement.from_report(self.case3000, self.report)
        self.q, _, _ = self.hertz.equilibrium(self.case)
        self.w = self.case.inner_speed_rad_s
        self.characterization = eb.characterize(self.case, method="hertz")
        self.coefficients = eb.coefficients(self.case, [3000.0, 5000.0], method="hertz")
        out = tmp / "study"
        summary = eb.study(str(EXAMPLES / "study_7006.toml"), str(out), method="hertz")
        self.trends_path = summary["trends_json"]
        assert self.trends_path, summary
        self.trends_text = pathlib.Path(self.trends_path).read_text()
        self.trend = eb.TrendForceElement.from_json(self.trends_text)
        (tmp / "binary.bin").write_bytes(bytes(range(256)) * 64)
        with open(tmp / "huge.toml", "wb") as f:  # sparse: 64 MiB, no disk used
            f.truncate(64 << 20)
        self.n = 4
        self.elements = [self.hertz, self.fitted, self.trend]

    def rotor(self) -> eb.RotorModel:
        """A 4-DOF rotor (two bearing planes y, z) on one dry element, softly held."""
        n = self.n
        m = np.eye(n) * 2.0
        k = np.eye(n) * 1e5
        model = eb.RotorModel(m, np.eye(n) * 10.0, np.zeros((n, n)), k)
        model.add_bearing(self.hertz, [None, 0, 1, None, None])
        return model


Call = Callable[[], Any]


def targets(env: Env) -> dict[str, Callable[[random.Random], Call]]:
    """For each public entry point, a maker of one hostile call."""
    case, w, q = env.case, env.w, env.q

    def pick_element(rng: random.Random) -> Any:
        return rng.choice(env.elements)

    def evaluate(rng: random.Random) -> Call:
        element = pick_element(rng)
        w_el = 3000.0 * math.pi / 30.0 if element is env.fitted else w
        args: dict[str, Any] = {
            "displacement": np.array(q),
            "velocity": np.zeros(5),
            "inner_speed_rad_s": w_el,
            "outer_speed_rad_s": 0.0,
            "cage_angle_rad": 0.1,
            "full": rng.random() < 0.5,
        }
        for key in rng.sample(sorted(args), rng.choice([1, 1, 2])):
            args[key] = wild(rng, args[key] if isinstance(args[key], float) else None)
        return lambda: element.evaluate(**args)

    def cage_speed(rng: random.Random) -> Call:
        element = pick_element(rng)
        a, b = (wild(rng, w), 0.0) if rng.random() < 0.7 else (w, wild(rng, 1.0))
        return lambda: element.cage_speed(a, b)

    def element_equilibrium(rng: random.Random) -> Call:
        return lambda: pick_element(rng).equilibrium(wild(rng))

    def case_from_file(rng: random.Random) -> Call:
        p = wild_path(rng, env.tmp)
        return lambda: eb.Case.from_file(p)

    def case_from_toml(rng: random.Random) -> Call:
        text = wild_text(rng, env.case_toml)
        origin = wild(rng) if rng.random() < 0.2 else "<fuzz>"
        return lambda: eb.Case.from_toml(text, origin)

    def case_from_dict(rng: random.Random) -> Call:
        d = {k: dict(v) for k, v in env.case_dict.items()}
        k = rng.randrange(4)
        if k == 0:
            table = rng.choice(sorted(d))
            key = rng.choice(sorted(d[table]))
            valid = d[table][key]
            d[table][key] = wild(rng, float(valid) if isinstance(valid, float) else None)
        elif k == 1:
            d[rng.choice(sorted(d))] = wild(rng)
        elif k == 2:
            d[rng.choice(["lubricant", "operating", "bearing", "unknown"])] = {
                rng.choice(["viscosity_pa_s", "temperature_c", "grade", 3, None]): wild(rng)
            }
        else:
            return lambda: eb.Case.from_dict(wild(rng))
        return lambda: eb.Case.from_dict(d)

    def with_speed(rng: random.Random) -> Call:
        v = wild(rng, 5000.0)
        return lambda: case.with_inner_speed_rpm(v)

    def equilibrium(rng: random.Random) -> Call:
        v = wild(rng)
        return lambda: eb.equilibrium(v)

    def ehl(rng: random.Random) -> Call:
        text: Any = env.contact_toml
        grid: Any = 17
        fields: Any = False
        k = rng.randrange(3)
        if k == 0:
            text = wild_text(rng, text)
        elif k == 1:
            grid = rng.choice([0, 1, 2, 16, 18, 2049, 1 << 40, -17, 17.0, 1e300, NAN, "17", None])
            if grid is None:
                grid = 33
        else:
            fields = wild(rng)
        return lambda: eb.ehl(text, grid=grid, fields=fields)

    def contact(rng: random.Random) -> Call:
        text: Any = env.contact_toml
        method: Any = "hertz"
        extrapolation: Any = True
        k = rng.randrange(3)
        if k == 0:
            text = wild_text(rng, text)
        elif k == 1:
            method = (
                rng.choice(["", "magic", "HERTZ", "synthetic", None])
                if rng.random() < 0.6
                else wild(rng)
            )
            if method is None:
                method = "nope"
        else:
            extrapolation = wild(rng)
        return lambda: eb.contact(text, method=method, film_extrapolation=extrapolation)

    def characterize(rng: random.Random) -> Call:
        c: Any = case
        method: Any = "hertz"
        progress: Any = None
        k = rng.randrange(3)
        if k == 0:
            c = wild(rng)
        elif k == 1:
            method = (
                rng.choice(["", "magic", "quasi_static", None]) if rng.random() < 0.6 else wild(rng)
            )
            if method is None:
                method = "HERTZ"
        else:
            progress = rng.choice([wild(rng), stop, lambda e: None, lambda: None, print])
            if progress is print:
                progress = lambda e: json.dumps(e)  # noqa: E731
        return lambda: eb.characterize(c, method=method, progress=progress)

    def characterization(rng: random.Random) -> Call:
        ch = env.characterization
        v = wild(rng)
        k = rng.randrange(3)
        if k == 0:
            return lambda: ch.report(timing=v)
        if k == 1:
            return lambda: (ch.displacement, ch.stiffness, ch.dry_stiffness, ch.converged)
        return lambda: ch.law_element().evaluate(v, inner_speed_rad_s=w)

    def coefficients(rng: random.Random) -> Call:
        args: dict[str, Any] = {"case": case, "speeds_rpm": [3000.0, 5000.0], "method": "hertz"}
        k = rng.randrange(5)
        if k == 0:
            args["speeds_rpm"] = rng.choice(
                [
                    [NAN],
                    [INF],
                    [-3000.0],
                    [0.0],
                    [],
                    [1e300],
                    [3000.0] * 200_000,
                    np.linspace(1000.0, 5000.0, 3).astype(np.float32),
                    np.array([[3000.0]]),
                    "3000",
                    wild(rng),
                ]
            )
        elif k == 1:
            args["method"] = rng.choice(["", "magic", wild(rng)])
        elif k == 2:
            args["element"] = rng.choice([wild(rng), env.trend, env.fitted, env.hertz])
        elif k == 3:
            args["progress"] = rng.choice([wild(rng), stop])
        else:
            args["case"] = wild(rng)
        return lambda: eb.coefficients(**args)

    def ross_table(rng: random.Random) -> Call:
        rows = json.loads(json.dumps(env.coefficients))
        k = rng.randrange(4)
        if k == 0:
            return lambda: eb.ross_table_csv(wild(rng))
        if k == 1:
            rows[0][rng.choice(sorted(rows[0]))] = wild(rng)
        elif k == 2:
            rows = rows * rng.choice([0, 1000])
        else:
            rows[0] = wild(rng)
        return lambda: eb.ross_table_csv(rows)

    def law_element(rng: random.Random) -> Call:
        k = rng.randrange(3)
        if k == 0:
            v = wild(rng)
            return lambda: eb.LawElement.hertz(v)
        report = json.loads(json.dumps(env.report))
        if k == 1:
            return lambda: eb.LawElement.from_report(env.case3000, wild(rng))
        # A value deep inside the report replaced.
        node: Any = report
        for _ in range(rng.randrange(1, 6)):
            if isinstance(node, dict) and node:
                key = rng.choice(sorted(node))
                if rng.random() < 0.4 or not isinstance(node[key], (dict, list)):
                    node[key] = wild(rng)
                    break
                node = node[key]
            elif isinstance(node, list) and node:
                i = rng.randrange(len(node))
                if not isinstance(node[i], (dict, list)):
                    node[i] = wild(rng)
                    break
                node = node[i]
        return lambda: eb.LawElement.from_report(env.case3000, report)

    def trend_element(rng: random.Random) -> Call:
        if rng.random() < 0.3:
            p = wild_path(rng, env.tmp)
            return lambda: eb.TrendForceElement.from_file(p)
        text = wild_text(rng, env.trends_text)
        return lambda: eb.TrendForceElement.from_json(text)

    def rotor_new(rng: random.Random) -> Call:
        n = env.n
        mats = [np.eye(n) * 2.0, np.eye(n) * 10.0, np.zeros((n, n)), np.eye(n) * 1e5, None]
        i = rng.randrange(5)
        mats[i] = rng.choice(
            [
                wild(rng),
                -np.eye(n),
                np.full((n, n), NAN),
                np.eye(n + 1),
                np.zeros((n, n)),
                np.eye(n)[:, :3],
                np.eye(2000),
            ]
        )
        return lambda: eb.RotorModel(*mats[:4], constant_force=mats[4])

    def rotor_add(rng: random.Random) -> Call:
        model = env.rotor()
        k = rng.randrange(5)
        element: Any = env.hertz
        dofs: Any = [None, 2, 3, None, None]
        signs: Any = None
        offset: Any = None
        if k == 0:
            element = wild(rng)
        elif k == 1:
            dofs = rng.choice(
                [
                    [None] * 5,
                    [0, 1, 2, 3, 99],
                    [-1] * 5,
                    [2, 2, 3, None, None],
                    [0.5] * 5,
                    wild(rng),
                ]
            )
        elif k == 2:
            signs = rng.choice([[NAN] * 5, [0.0] * 5, [2.0] * 5, wild(rng)])
        elif k == 3:
            offset = rng.choice([[NAN] * 5, [1.0] * 5, [1e300] * 5, wild(rng)])
        else:
            return lambda: model.add_unbalance(
                rng.choice([(0, 1), (0, 99), (1, 1), wild(rng)]), wild(rng, 1e-4), wild(rng, 0.0)
            )
        return lambda: model.add_bearing(element, dofs, signs=signs, offset=offset)

    def rotor_static(rng: random.Random) -> Call:
        model = env.rotor()
        v = wild(rng, w)
        if rng.random() < 0.5:
            return lambda: model.static_equilibrium(v)
        return lambda: model.linearized(v)

    def rotor_simulate(rng: random.Random) -> Call:
        model = env.rotor()
        args: dict[str, Any] = {
            "step_s": 1e-4,
            "duration_s": 2e-3,
            "speed_rad_s": w,
            "record_every": 1,
            "time_limit_s": 10.0,
        }
        key = rng.choice(
            [
                "step_s",
                "duration_s",
                "speed_rad_s",
                "ramp",
                "record_every",
                "record_dofs",
                "coupling",
                "cage_angle_rad",
                "start_displacement",
                "start_velocity",
                "progress",
                "time_limit_s",
            ]
        )
        valid = args.get(key)
        args[key] = wild(rng, valid if isinstance(valid, float) else None)
        if key == "ramp" and rng.random() < 0.5:
            args[key] = rng.choice(
                [(0.0, w, NAN), (0.0, -1.0, 1.0), (w, w, 0.0), (0.0, 1e300, 1e-3)]
            )
        if key in ("step_s", "duration_s") and args["time_limit_s"] is not None:
            args["record_every"] = 1000  # huge runs then stop at the time limit, not on memory
        return lambda: model.simulate(**args)

    def plots_api(rng: random.Random) -> Call:
        k = rng.randrange(3)
        if k == 0:
            signal, step = rng.choice(
                [(wild(rng), 1e-3), (np.sin(np.arange(64.0)), wild(rng, 1e-3))]
            )
            return lambda: plots.amplitude_spectrum(signal, step)
        if k == 1:
            a, b, c = 1000, 1e-3, 50.0
            which = rng.randrange(3)
            a, b, c = [wild(rng) if i == which else v for i, v in enumerate((a, b, c))]
            return lambda: plots.whole_periods(a, b, c)
        response = {"record_dofs": [0, 1], "displacement": np.zeros((8, 2))}
        v = wild(rng)
        return lambda: plots.column(response if rng.random() < 0.5 else v, v)

    return {
        "LawElement/TrendForceElement.evaluate": evaluate,
        "element.cage_speed": cage_speed,
        "element.equilibrium": element_equilibrium,
        "Case.from_file": case_from_file,
        "Case.from_toml": case_from_toml,
        "Case.from_dict": case_from_dict,
        "Case.with_inner_speed_rpm": with_speed,
        "equilibrium": equilibrium,
        "ehl": ehl,
        "contact": contact,
        "characterize": characterize,
        "Characterization": characterization,
        "coefficients": coefficients,
        "ross_table_csv": ross_table,
        "LawElement.hertz/from_report": law_element,
        "TrendForceElement.from_json/from_file": trend_element,
        "RotorModel()": rotor_new,
        "RotorModel.add_bearing/add_unbalance": rotor_add,
        "RotorModel.static_equilibrium/linearized": rotor_static,
        "RotorModel.simulate": rotor_simulate,
        "plots": plots_api,
    }


def outcome_of(thunk: Call) -> tuple[str, str]:
    """(outcome, detail) of one call."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = thunk()
        except CLEAR as e:
            msg = str(e).strip()
            return (
                "clear error" if msg else "error without a message"
            ), f"{type(e).__name__}: {msg}"
        except (KeyboardInterrupt, SystemExit):
            raise
        except BaseException as e:  # a pyo3 panic is a BaseException
            kind = "panic" if type(e).__name__ == "PanicException" else "unexpected exception"
            return kind, f"{type(e).__name__}: {e}"
    bad = nonfinite(result)
    warned = f"; warning: {caught[0].message}" if caught else ""
    if bad:
        return ("flagged" if caught else "non-finite result"), f"non-finite at {bad}{warned}"
    return ("flagged" if caught else "result"), warned


def run_one(thunk: Call) -> tuple[str, str, float]:
    """(outcome, detail, seconds) of one call; a call running longer than HANG_S ends the process
    (faulthandler prints where it hung)."""
    t0 = time.perf_counter()
    faulthandler.dump_traceback_later(HANG_S, exit=True)
    try:
        outcome, detail = outcome_of(thunk)
    finally:
        faulthandler.cancel_dump_traceback_later()
    return outcome, detail, time.perf_counter() - t0


FAILURES = {"panic", "unexpected exception", "non-finite result", "error without a message"}


@pytest.fixture(scope="module")
def env(tmp_path_factory: pytest.TempPathFactory) -> Env:
    return Env(tmp_path_factory.mktemp("fuzz"))


def test_fuzz_the_python_api(env: Env) -> None:
    makers = targets(env)
    names = sorted(makers)
    counts: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
    slowest: dict[str, float] = collections.defaultdict(float)
    findings = []
    indices = [int(ONE)] if ONE is not None else range(CASES)
    log: list[str] = []
    for i in indices:
        rng = random.Random(SEED * 1_000_003 + i)
        name = names[i % len(names)]
        try:
            thunk = makers[name](rng)
        except CLEAR:  # a hostile value refused while the call itself was being set up
            continue
        if MESSAGES:  # the call about to run, in case it never returns
            with open(MESSAGES + ".last", "w") as f:
                f.write(f"{i}\t{name}\n")
        outcome, detail, seconds = run_one(thunk)
        counts[name][outcome] += 1
        slowest[name] = max(slowest[name], seconds)
        if ONE is not None:
            print(f"call {i} ({name}): {outcome} in {seconds:.3f} s: {detail}")
        if MESSAGES:
            log.append(f"{i}\t{name}\t{outcome}\t{seconds:.3f}\t{detail[:400]!r}")
        if outcome in FAILURES:
            findings.append(f"call {i} ({name}): {outcome}: {detail[:300]}")
    # The warm state of the shared elements survived every hostile call.
    ref = eb.LawElement.hertz(env.case).evaluate(env.q, inner_speed_rad_s=env.w)[0]
    now = env.hertz.evaluate(env.q, inner_speed_rad_s=env.w)[0]
    assert np.allclose(now, ref, rtol=1e-9, atol=1e-9), (now, ref)

    outcomes = ["result", "flagged", "clear error", *sorted(FAILURES)]
    lines = [
        f"Python API fuzz: seed {SEED}, {sum(map(sum, map(dict.values, counts.values())))} calls",
        "| entry point | " + " | ".join(outcomes) + " | slowest call, s |",
        "|---|" + "---|" * (len(outcomes) + 1),
    ]
    for name in names:
        c = counts[name]
        lines.append(
            f"| `{name}` | " + " | ".join(str(c[o]) for o in outcomes) + f" | {slowest[name]:.2f} |"
        )
    total = collections.Counter()
    for c in counts.values():
        total.update(c)
    lines.append(
        "| all | "
        + " | ".join(str(total[o]) for o in outcomes)
        + f" | {max(slowest.values(), default=0):.2f} |"
    )
    print("\n".join(lines))
    if MESSAGES:
        pathlib.Path(MESSAGES).write_text("\n".join(log) + "\n")
    assert not findings, "\n".join(findings[:20])
