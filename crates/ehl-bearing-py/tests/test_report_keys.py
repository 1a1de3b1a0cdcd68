"""One key set for every result: the Python functions and the command line's `--json` give the
same keys, recursively (both are made from the library's typed reports, docs/results.md).

The command line is the workspace's `ehl-bearing` binary: $EHL_BEARING_CLI if set, else the debug
build in $CARGO_TARGET_DIR (or the repository's target/), built with cargo if it is missing.
"""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
from typing import Any

import pytest

import ehl_bearing as eb

REPO = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def cli() -> str:
    given = os.environ.get("EHL_BEARING_CLI")
    if given:
        return given
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    exe = target / "debug" / "ehl-bearing"
    if not exe.exists():
        subprocess.run(
            ["cargo", "build", "--quiet", "-p", "ehl-bearing-cli"],
            cwd=REPO,
            check=True,
        )
    assert exe.exists(), f"{exe}: not built"
    return str(exe)


def run_json(cli: str, *args: str) -> Any:
    out = subprocess.run([cli, *args, "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def key_tree(v: Any) -> Any:
    """The keys of `v`, recursively: dicts as {key: subtree}, lists as the list of their items'
    trees, anything else as None."""
    if isinstance(v, dict):
        return {k: key_tree(x) for k, x in v.items()}
    if isinstance(v, list):
        return [key_tree(x) for x in v]
    return None


def test_key_tree_tells_a_renamed_or_missing_key():
    assert key_tree({"a": [{"b": 1}], "c": 2.0}) == {"a": [{"b": None}], "c": None}
    assert key_tree({"K": 1.0}) != key_tree({"k": 1.0})
    assert key_tree({"a": {"b": 1}}) != key_tree({"a": {"b": 1, "c": 2}})


def test_contact_has_the_keys_of_contact_json(cli, examples):
    path = examples / "contact_7006_inner.toml"
    from_cli = run_json(cli, "contact", str(path), "--grid", "33")
    from_py = eb.contact(path.read_text(), grid=33)
    assert key_tree(from_py) == key_tree(from_cli)
    # The same computation: the same law.
    assert from_py["k"] == pytest.approx(from_cli["k"], rel=1e-9)
    assert from_py["moes_m"] == from_cli["moes_m"]


def test_ehl_has_the_keys_of_ehl_json(cli, examples):
    path = examples / "contact_7006_inner.toml"
    from_cli = run_json(cli, "ehl", str(path), "--grid", "65")
    from_py = eb.ehl(path.read_text(), grid=65)
    assert key_tree(from_py) == key_tree(from_cli)
    assert from_py["h_central"] == from_cli["h_central"]
    assert "fields" in eb.ehl(path.read_text(), grid=33, fields=True)


def test_equilibrium_has_the_keys_of_equilibrium_json(cli, examples):
    path = examples / "7006.toml"
    from_cli = run_json(cli, "equilibrium", str(path))
    from_py = eb.equilibrium(eb.Case.from_file(str(path)))
    assert key_tree(from_py) == key_tree(from_cli)
    assert from_py["stiffness"] == from_cli["stiffness"]


def test_characterization_report_has_the_keys_of_characterize_json(cli, examples):
    path = examples / "7006.toml"
    from_cli = run_json(cli, "characterize", str(path), "--method", "hertz")
    report = eb.characterize(eb.Case.from_file(str(path)), method="hertz").report(timing=True)
    assert key_tree(report) == key_tree(from_cli)
    assert report["contacts"] == from_cli["contacts"]


def test_law_maps_are_the_cli_info(cli: str) -> None:
    """`law_maps()` gives the summaries `ehl-bearing law-map info --json` prints, key for key and
    value for value: the embedded maps in query order, the first the seed oil's (M 120–4000)."""
    maps = eb.law_maps()
    assert maps == run_json(cli, "law-map", "info")
    assert maps[0]["law"] == "quasi-static" and maps[-1]["law"] == "harmonic"
    assert maps[0]["name"] == "seed_oil" and len({x["name"] for x in maps}) == len(maps)
    m = maps[0]["spec"]["axis"][0]
    assert (m["group"], m["min"], m["max"], m["nodes"], m["log"]) == ("m", 120.0, 4000.0, 17, True)
    assert all(x["nodes"] > 0 and x["worst_node_r_squared"] <= 1.0 for x in maps)
