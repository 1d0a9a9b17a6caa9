"""The GIL is released during C++ work; help() shows shapes, dtypes, units and frames."""

import threading
import time

import numpy as np

import sonarmap


def _increments_during(work):
    """How often a Python thread increments a counter while `work()` runs in this thread."""
    count = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            count[0] += 1

    thread = threading.Thread(target=spin)
    thread.start()
    time.sleep(0.02)
    before = count[0]
    start = time.perf_counter()
    work()
    seconds = time.perf_counter() - start
    during = count[0] - before
    stop.set()
    thread.join()
    return during, seconds


def test_mapping_and_queries_release_the_gil(simulated_tank):
    during, seconds = _increments_during(lambda: sonarmap.map_sonar_log(simulated_tank.log, resolution=0.01))
    assert seconds > 0.02
    assert during > 1000, f"a Python thread ran only {during} steps in {seconds:.3f} s of mapping"
    m = sonarmap.map_sonar_log(simulated_tank.log)
    points = np.random.default_rng(0).uniform(-2, 2, size=(2_000_000, 3))
    during, seconds = _increments_during(lambda: m.classify(points))
    assert during > 1000, f"a Python thread ran only {during} steps in {seconds:.3f} s of queries"


def test_help_shows_shapes_dtypes_units_and_frames():
    text = sonarmap.OccupancyMap.insert_point_cloud.__doc__
    for word in ("(N, 3)", "float64", "metres", "map frame"):
        assert word in text
    assert "(beams, bins)" in sonarmap.SonarLog.intensities.__doc__ and "uint8" in sonarmap.SonarLog.intensities.__doc__
    assert "radians" in sonarmap.SonarLog.bearing_rad.__doc__
    assert "NWU" in sonarmap.map_sonar_log.__doc__
    assert sonarmap.OccupancyMap.__module__ == "sonarmap"
