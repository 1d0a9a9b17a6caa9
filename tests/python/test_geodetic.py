"""The map's zero on the Earth: the header line `sonarmap map` writes (from a bag's NavSatFix) is read
by OccupancyMap.read, set and written back by the module."""

import pytest

import sonarmap


def test_geodetic_origin_of_a_bag_with_navsatfix(cli, tmp_path):
    cli("simulate", "tank", "-o", tmp_path / "sim", "--speed", "0.1", "--turns", "1", "--bag", tmp_path / "run.bag",
        "--geo-origin", "-33.86,151.21", "-q")
    cli("map", tmp_path / "run.bag", "-o", tmp_path / "map.bt", "-q")
    m = sonarmap.OccupancyMap.read(str(tmp_path / "map.bt"))
    lat, lon, height = m.geodetic_origin
    assert lat == pytest.approx(-33.86, abs=1e-9)  # the NavSatFix fixes' origin, back through GeographicLib
    assert lon == pytest.approx(151.21, abs=1e-9)
    assert height == pytest.approx(0.0, abs=1e-3)


def test_geodetic_origin_set_written_and_read(tmp_path):
    m = sonarmap.OccupancyMap(0.1)
    assert m.geodetic_origin is None
    m.geodetic_origin = (43.2961, 5.37)
    m.write(str(tmp_path / "m.bt"))
    assert "# sonarmap geodetic origin: 43.2961 5.37 0 " in (tmp_path / "m.bt").read_bytes().decode("latin-1")
    assert sonarmap.OccupancyMap.read(str(tmp_path / "m.bt")).geodetic_origin == (43.2961, 5.37, 0.0)
    m.geodetic_origin = None
    assert m.geodetic_origin is None


@pytest.mark.parametrize("bad", [(91.0, 5.0), (43.0, -181.0), (float("nan"), 5.0), (1.0,)])
def test_bad_geodetic_origin_raises_value_error(bad):
    m = sonarmap.OccupancyMap(0.1)
    with pytest.raises(sonarmap.ValueError):
        m.geodetic_origin = bad
