# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Fixtures for the Python module's tests (ctest runs them with PYTHONPATH at
the built module and STRATA_CLI at the strata executable)."""

import os
import pathlib
import re
import subprocess
import threading
import time

import pytest

import strata

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli():
    path = os.environ.get("STRATA_CLI")
    if not path or not os.path.exists(path):
        pytest.fail("STRATA_CLI must name the strata executable (ctest sets it)")
    return path


def run_cli(*args):
    """Runs the strata executable; fails the test with its output when it fails."""
    result = subprocess.run([cli(), *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, f"strata {' '.join(map(str, args))}: exit {result.returncode}\n{result.stderr}"
    return result


@pytest.fixture(scope="session")
def small_scene_text():
    """The C++ tests' small scene (tests/SmallScene.h): hills minus worm
    tunnels over 24 m at 0.5 m voxels. Read from that header, so both
    languages test the same scene."""
    header = (REPO / "tests" / "SmallScene.h").read_text()
    match = re.search(r'R"\((.*?)\)"', header, re.S)
    assert match, "tests/SmallScene.h no longer holds a raw string scene"
    return match.group(1)


@pytest.fixture(scope="session")
def small_scene(small_scene_text):
    return strata.parse_scene(small_scene_text, "small.toml")


@pytest.fixture(scope="session")
def small_grid(small_scene):
    return strata.sample(small_scene)


@pytest.fixture(scope="session")
def small_mesh(small_grid):
    return strata.mesh(small_grid)


def ticks_during(call):
    """Runs call() while a second Python thread counts, sleeping 1 ms between
    counts; returns (ticks, seconds). A call that holds the GIL leaves the
    counter where it was when it started."""
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    thread = threading.Thread(target=count)
    thread.start()
    try:
        start = time.perf_counter()
        call()
        seconds = time.perf_counter() - start
    finally:
        done.set()
        thread.join()
    return ticks, seconds
