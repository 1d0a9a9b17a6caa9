"""The GIL is released during C++ work; help() shows shapes, dtypes, units and frames."""

import threading
import time

import numpy as np

import sonarmap


def _longest_pause_during(work):
    """The longest time a Python thread, stepping in a loop, did not step while `work()` ran in
    this thread, and how long `work()` took (seconds). A call that holds the GIL stops that thread
    for its whole length; one that releases it lets the thread step on."""
    longest = [0.0]
    running = threading.Event()
    stop = threading.Event()

    def spin():
        last = time.perf_counter()
        running.set()
        while not stop.is_set():
            now = time.perf_counter()
            longest[0] = max(longest[0], now - last)
            last = now

    thread = threading.Thread(target=spin)
    thread.start()
    running.wait()
    time.sleep(0.02)
    longest[0] = 0.0
    start = time.perf_counter()
    work()
    seconds = time.perf_counter() - start
    pause = longest[0]
    stop.set()
    thread.join()
    return pause, seconds


# A call that holds the GIL stops the other thread for all of its length but Python's switch
# interval (5 ms). The bound leaves room for the scheduler too: on a loaded two-core machine a
# thread that may run can still wait tens of milliseconds for a core.
PAUSE_SHARE = 0.8


def test_mapping_and_queries_release_the_gil(simulated_tank):
    pause, seconds = _longest_pause_during(lambda: sonarmap.map_sonar_log(simulated_tank.log, resolution=0.002))
    assert seconds > 0.1, "the mapping must take long enough to tell"
    assert pause < PAUSE_SHARE * seconds, f"a Python thread stood still {pause:.3f} s of {seconds:.3f} s of mapping"
    m = sonarmap.map_sonar_log(simulated_tank.log)
    points = np.random.default_rng(0).uniform(-2, 2, size=(4_000_000, 3))
    pause, seconds = _longest_pause_during(lambda: m.classify(points))
    assert seconds > 0.1, "the queries must take long enough to tell"
    assert pause < PAUSE_SHARE * seconds, f"a Python thread stood still {pause:.3f} s of {seconds:.3f} s of queries"


def test_help_shows_shapes_dtypes_units_and_frames():
    text = sonarmap.OccupancyMap.insert_point_cloud.__doc__
    for word in ("(N, 3)", "float64", "metres", "map frame"):
        assert word in text
    assert "(beams, bins)" in sonarmap.SonarLog.intensities.__doc__ and "uint8" in sonarmap.SonarLog.intensities.__doc__
    assert "radians" in sonarmap.SonarLog.bearing_rad.__doc__
    assert "map_frame" in sonarmap.map_sonar_log.__doc__ and "x east, y north, z up" in sonarmap.map_sonar_log.__doc__
    assert sonarmap.OccupancyMap.__module__ == "sonarmap"
