"""What the module says by name: angles in degrees say so in their keyword (the module's other
angles are radians), errors and warnings name the keywords a Python user gave (not the CLI's
flags), and no message starts with the name of a library function."""

import pathlib
import re
import warnings

import numpy as np
import pytest

import sonarmap

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"
FUNCTION_PREFIX = re.compile(r"^[a-z]+[A-Z][A-Za-z0-9]*(::[A-Za-z]+)?: ")


def test_angles_in_degrees_say_so(simulated_tank):
    degrees = [o for o in sonarmap.mapping_options() if o["unit"] == "degrees"]
    assert {o["keyword"] for o in degrees} >= {"beam_width_deg", "vertical_aperture_deg", "smoothing_bearing_deg"}
    assert all(o["keyword"].endswith("_deg") for o in degrees)
    # The old names, which gave no unit, are refused with the new one: beam_width=0.05 (meant as
    # radians, the unit of nav's attitude) used to map a 0.05-degree beam.
    for old in ("beam_width", "vertical_aperture", "smoothing_bearing"):
        with pytest.raises(TypeError, match=f"{old}_deg"):
            sonarmap.map_sonar_log(simulated_tank.log, **{old: 0.05})
        with pytest.raises(TypeError, match=f"{old}_deg"):
            sonarmap.OnlineMapper(**{old: 3.0})
    mission = sonarmap.simulate_mission("tilted-loop")
    assert mission.beam_width_deg == pytest.approx(mission.log.nominal_beam_deg[0])
    assert mission.vertical_aperture_deg == pytest.approx(mission.log.nominal_beam_deg[1])


def test_errors_name_the_python_keyword(simulated_tank):
    log = simulated_tank.log
    bad = {"resolution": -1.0, "beam_width_deg": -1.0, "false_alarm": 2.0, "detector": "bogus",
           "min_range": -1.0, "vertical_aperture_deg": 0.0}
    for keyword, value in bad.items():
        with pytest.raises(sonarmap.ValueError) as raised:
            sonarmap.map_sonar_log(log, **{keyword: value})
        message = str(raised.value)
        assert message.startswith(f"{keyword} expects"), message
        assert "--" not in message, message
    polar = sonarmap.polar_image(log)
    with pytest.raises(sonarmap.ValueError, match=r"^false_alarm expects"):
        sonarmap.detect_obstacles(polar, false_alarm=3.0)


def test_warnings_name_the_python_keyword(simulated_tank):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sonarmap.map_sonar_log(simulated_tank.log, max_range=0.01)
    texts = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert texts and any("max_range" in text for text in texts), texts
    assert not any("--" in text for text in texts), texts


def test_messages_name_no_library_function(tmp_path, simulated_tank):
    bad_mat = tmp_path / "x.mat"
    bad_mat.write_text("not a MATLAB file\n")
    with pytest.raises(sonarmap.FileError) as raised:
        sonarmap.read_sonar_log(str(bad_mat))
    assert "x.mat" in str(raised.value) and not FUNCTION_PREFIX.search(str(raised.value)), str(raised.value)
    with pytest.raises(sonarmap.ValueError) as raised:
        sonarmap.polar_image(simulated_tank.log, first=10, last=10)
    assert not FUNCTION_PREFIX.search(str(raised.value)), str(raised.value)
    with pytest.raises(sonarmap.ValueError) as raised:
        sonarmap.cartesian_image(sonarmap.polar_image(simulated_tank.log), pixel_size_m=-1.0)
    assert not FUNCTION_PREFIX.search(str(raised.value)), str(raised.value)


def test_no_library_message_starts_with_a_function_name():
    """Every error the library throws, as written in its sources: a message for a user says what
    is wrong, not which function found it ("readCrasMat: ...")."""
    thrown = re.compile(r'(?:Error|throw\w*)\(\s*(?:std::string\()?"([a-z]+[A-Z][A-Za-z0-9]*(?:::[A-Za-z]+)?): ')
    found = []
    for path in sorted(SRC.rglob("*.cpp")):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if not line.lstrip().startswith("//") and thrown.search(line):
                found.append(f"{path.relative_to(SRC)}:{number}: {line.strip()}")
    assert not found, "messages starting with a function name:\n" + "\n".join(found)
