"""The shipped examples draw what they say: the last whole sweep of a real log (every bearing the
head uses, not the few beams a log ends on), in the script and in the notebook."""

import importlib.util
import json
import os
import pathlib

import numpy as np
import pytest

import sonarmap

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"
LOGS = ["cras_micron_tank_static.mat", "micron_pool_ros1.bag"]


def head_bearings(log):
    """The distinct bearings the head uses over the whole log, degrees to 0.01°."""
    return np.unique(np.round(np.degrees(log.bearing_rad), 2) % 360.0)


def drawn_bearings(polar):
    return np.unique(np.round(np.degrees(polar.bearing_rad), 2) % 360.0)


@pytest.mark.parametrize("name", LOGS)
def test_the_whole_sweeps_of_a_full_turn_log_cover_every_bearing(shared_file, name):
    log = sonarmap.read_sonar_log(shared_file(name))
    whole = log.whole_sweeps()
    assert len(whole) > 0
    every = head_bearings(log)
    for first, last in whole:
        assert last - first == len(every)  # one beam per bearing of the turn
    last_whole = sonarmap.polar_image(log, sweep=-1)
    assert np.array_equal(drawn_bearings(last_whole), every)
    assert np.array_equal(last_whole.bearing_rad, log.bearing_rad[whole[-1][0]:whole[-1][1]])


def drawing(monkeypatch):
    """The polar images sonarmap.polar_image returns from now on, in a list: what an example drew."""
    drawn = []
    polar_image = sonarmap.polar_image

    def recorded(*args, **kwargs):
        drawn.append(polar_image(*args, **kwargs))
        return drawn[-1]

    monkeypatch.setattr(sonarmap, "polar_image", recorded)
    return drawn


@pytest.mark.parametrize("name", LOGS)
def test_the_example_script_draws_a_whole_sweep(shared_file, tmp_path, monkeypatch, name):
    pytest.importorskip("matplotlib")
    spec = importlib.util.spec_from_file_location("map_sonar_log_example", EXAMPLES / "map_sonar_log.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    log = sonarmap.read_sonar_log(shared_file(name))
    drawn = drawing(monkeypatch)
    example.plot_sonar_images(log, name, tmp_path)
    assert (tmp_path / "sonar_images.png").stat().st_size > 0
    assert len(drawn) == 1
    assert drawn[0].intensities.shape[0] == len(head_bearings(log))
    assert np.array_equal(drawn_bearings(drawn[0]), head_bearings(log))


def test_the_notebook_draws_a_whole_sweep(shared_file, monkeypatch):
    """The notebook's first cells (the log and its images), run as the notebook runs them."""
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cras = pathlib.Path(shared_file("cras_micron_tank_static.mat"))
    monkeypatch.setenv("SONARMAP_DATA", str(cras.parent))
    monkeypatch.setattr(plt, "show", lambda *args, **kwargs: None)
    cells = [c for c in json.loads((EXAMPLES / "sonarmap_tour.ipynb").read_text())["cells"] if c["cell_type"] == "code"]
    scope = {}
    exec("".join(cells[0]["source"]), scope)  # the log
    drawn = drawing(monkeypatch)
    exec("".join(cells[1]["source"]), scope)  # its images
    plt.close("all")
    log = scope["log"]
    assert len(drawn) == 1
    assert drawn[0].intensities.shape[0] == len(head_bearings(log))
    assert np.array_equal(drawn_bearings(drawn[0]), head_bearings(log))
