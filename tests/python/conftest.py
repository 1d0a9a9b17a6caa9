"""Fixtures of the Python module's tests (run by ctest as python.pytest).

Environment (set by tests/CMakeLists via python/CMakeLists.txt):
  PYTHONPATH            <build>/python, where the package is assembled
  SONARMAP_CLI          the `sonarmap` command-line tool (tests comparing with it skip without it)
  SONARMAP_SHARED_DATA  ../shared/data (tests on real logs skip without it)
"""

import os
import subprocess

import numpy as np
import pytest

import sonarmap


def _shared_data():
    return os.environ.get("SONARMAP_SHARED_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data"))


@pytest.fixture(scope="session")
def cli():
    """Runs the sonarmap CLI with the given arguments; skips when it is not available."""
    path = os.environ.get("SONARMAP_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("SONARMAP_CLI is not set to the sonarmap command-line tool")

    def run(*args):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True, timeout=120)
        assert result.returncode == 0, f"sonarmap {' '.join(map(str, args))} failed:\n{result.stderr}"
        return result

    return run


@pytest.fixture(scope="session")
def shared_file():
    """Path of a file in ../shared/data; skips when it is absent."""

    def path_of(name):
        path = os.path.join(_shared_data(), name)
        if not os.path.exists(path):
            pytest.skip(f"shared data {name} is absent")
        return path

    return path_of


@pytest.fixture(scope="session")
def simulated_tank():
    """A short simulated run of the Micron in the built-in tank (4 turns, 800 beams)."""
    return sonarmap.simulate("tank", turns=4, seed=3)


@pytest.fixture(scope="session")
def tank_csv(tmp_path_factory, simulated_tank):
    """The simulated run written as a beam CSV (what `sonarmap simulate` writes as beams.csv)."""
    path = tmp_path_factory.mktemp("tank") / "beams.csv"
    simulated_tank.log.write_csv(str(path))
    return path


@pytest.fixture()
def small_map():
    """A 0.1 m map with one scan of a wall at x = 2 m seen from the origin."""
    m = sonarmap.OccupancyMap(0.1)
    ys, zs = np.meshgrid(np.linspace(-0.5, 0.5, 11), np.linspace(-0.3, 0.3, 7))
    wall = np.column_stack([np.full(ys.size, 2.05), ys.ravel(), zs.ravel()])
    m.insert_point_cloud(wall, np.zeros(3))
    return m
