"""The hand-labelled Ping360 basin log (../shared/data/labels/ping360_basin.labels.json), scored by
the labels' own scorer (../shared/tools/score_labels.py): precision and recall of the occupied cells
at the sonar's level, with the default detector and with the local reverberation level
(docs/accuracy.md, "Local reverberation level"). Skips without the shared data or the scorer's
packages (numpy, scipy, matplotlib)."""

import os
import re
import subprocess
import sys

import pytest

import sonarmap

SCORER = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "tools", "score_labels.py")


def _score(shared_file, tmp_path, **options):
    pytest.importorskip("scipy")
    pytest.importorskip("matplotlib")
    if not os.path.exists(SCORER):
        pytest.skip("the labels' scorer is absent")
    labels = shared_file("labels/ping360_basin.labels.json")
    log = sonarmap.read_sonar_log(shared_file("ping360_basin.bin"))
    path = str(tmp_path / "basin.bt")
    sonarmap.map_sonar_log(log, **options).write(path)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    out = subprocess.run([sys.executable, SCORER, path, labels], capture_output=True, text=True, env=env, check=True).stdout
    found = re.search(r"precision=([0-9.]+) recall=([0-9.]+)", out)
    assert found, out
    return float(found.group(1)), float(found.group(2))


def test_local_reverberation_keeps_the_structure_and_drops_the_seabed(shared_file, tmp_path):
    precision, recall = _score(shared_file, tmp_path, local_reverberation=True)
    # Measured 0.697 / 0.714 (the default: 0.174 / 0.714).
    assert precision >= 0.65
    assert recall >= 0.68


def test_default_map_holds_the_structure(shared_file, tmp_path):
    precision, recall = _score(shared_file, tmp_path)
    assert recall >= 0.68
    assert precision >= 0.15
