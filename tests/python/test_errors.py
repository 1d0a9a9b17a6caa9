"""The exception hierarchy: C++ exceptions arrive as Python exceptions of the same names."""

import builtins

import numpy as np
import pytest

import sonarmap


def test_hierarchy():
    assert issubclass(sonarmap.Error, RuntimeError)
    for name in ("FileError", "ValueError", "OutOfMapError"):
        cls = getattr(sonarmap, name)
        assert issubclass(cls, sonarmap.Error)
        assert cls.__name__ == name and cls.__module__ == "sonarmap"
    assert issubclass(sonarmap.FileError, OSError)
    assert issubclass(sonarmap.ValueError, builtins.ValueError)
    assert issubclass(sonarmap.OutOfMapError, builtins.ValueError)


def test_star_import_keeps_builtin_value_error():
    namespace = {}
    exec("from sonarmap import *", namespace)
    assert "ValueError" not in namespace


def test_value_error_from_cpp():
    with pytest.raises(sonarmap.ValueError, match="resolution"):
        sonarmap.OccupancyMap(-1.0)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.OccupancyMap(0.1, prob_hit=0.3)


def test_file_error_from_cpp(tmp_path):
    with pytest.raises(sonarmap.FileError):
        sonarmap.OccupancyMap.read(str(tmp_path / "missing.bt"))
    with pytest.raises(sonarmap.FileError, match="extension|unknown"):
        sonarmap.OccupancyMap(0.1).write(str(tmp_path / "map.xyz"))
    with pytest.raises(sonarmap.FileError):
        sonarmap.read_sonar_log(str(tmp_path / "log.unknown"))
    with pytest.raises(OSError):  # a FileError is an OSError too
        sonarmap.read_sonar_log(str(tmp_path / "missing.csv"))


def test_out_of_map_error_from_cpp():
    m = sonarmap.OccupancyMap(0.001)  # depth 16 at 1 mm spans about ±32 m
    with pytest.raises(sonarmap.OutOfMapError):
        m.insert_point_cloud(np.zeros((1, 3)), np.array([100.0, 0.0, 0.0]))
    with pytest.raises(sonarmap.OutOfMapError):
        m.cast_ray([100.0, 0.0, 0.0], [1.0, 0.0, 0.0])


def test_unknown_keyword_is_a_type_error(simulated_tank):
    with pytest.raises(TypeError, match="resolutoin"):
        sonarmap.map_sonar_log(simulated_tank.log, resolutoin=0.05)
