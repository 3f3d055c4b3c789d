"""Paths for the Python tests, from the environment ctest sets (tests/CMakeLists.txt):
LUB_SOURCE_DIR, LUB_BUILD_DIR, LUB_PAPER_STUDY (the paper grid's study, written by the
nightly_paper test, a ctest fixture)."""
import os
import pathlib

import pytest


def _env(name):
    v = os.environ.get(name)
    if not v:
        pytest.skip(f"{name} not set (run through ctest)")
    return pathlib.Path(v)


@pytest.fixture(scope="session")
def source_dir():
    return _env("LUB_SOURCE_DIR")


@pytest.fixture(scope="session")
def build_dir():
    return _env("LUB_BUILD_DIR")


@pytest.fixture(scope="session")
def paper_study():
    p = _env("LUB_PAPER_STUDY")
    if not p.exists():
        pytest.fail(f"{p} does not exist: the nightly_paper test writes it")
    return p
