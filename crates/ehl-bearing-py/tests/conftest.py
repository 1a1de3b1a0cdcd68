"""Shared fixtures: the repository's example files."""

from __future__ import annotations

import pathlib

import pytest

import ehl_bearing as eb

REPO = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="session")
def case() -> eb.Case:
    """The seed case (7006, 5000 rpm, F_x = F_y = F_z = 1000 N)."""
    return eb.Case.from_file(str(EXAMPLES / "7006.toml"))


@pytest.fixture(scope="session")
def examples() -> pathlib.Path:
    return EXAMPLES
