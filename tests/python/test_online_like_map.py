"""The online mapper fed a log's beams one at a time gives `sonarmap map`'s map (issue 66): it is
told the sonar (format= or log=), each beam carries what the head recorded of its settings
(intensity span, gain, pulse length: NaN or -1 where not recorded, as SonarLog's columns), and
given the log (log=) its automatic options are map_sonar_log's."""

import numpy as np
import pytest

import sonarmap


def _bytes_of(m, path):
    m.write(str(path))
    return path.read_bytes()


def _feed(online, log, settings=True):
    """The log's beams through add_beam in order, with every field (or without the head's settings)."""
    for i in range(len(log)):
        recorded = {}
        if settings:
            recorded = dict(intensity_span_db=log.intensity_span_db[i], gain_setting=log.gain_setting[i],
                            pulse_length_m=log.pulse_length_m[i])
        online.add_beam(log.time_s[i], log.bearing_rad[i], log.bin_length_m[i],
                        log.intensities[i, : log.valid_bins[i]], **recorded)
    online.finish()
    return online.map()


def _with_head_settings(csv_path, out_path, gain_from_beam):
    """The beam CSV at csv_path with a gain_setting column (0, then 2 from beam gain_from_beam on) and a
    pulse_length_m column of 2 cm, as a head recording its settings writes it."""
    lines = csv_path.read_text().splitlines()
    header = lines[0].split(",")
    at = header.index("bin_length_m") + 1
    rows = [header[:at] + ["gain_setting", "pulse_length_m"] + header[at:]]
    for i, line in enumerate(lines[1:]):
        fields = line.split(",")
        rows.append(fields[:at] + ["2" if i >= gain_from_beam else "0", "0.02"] + fields[at:])
    out_path.write_text("\n".join(",".join(row) for row in rows) + "\n")
    return sonarmap.read_sonar_log(str(out_path))


def test_the_sonar_must_be_named():
    with pytest.raises(sonarmap.ValueError, match="ping360: 2° × 25°") as raised:
        sonarmap.OnlineMapper()
    assert "log=" in str(raised.value) and "beam_width_deg" in str(raised.value)
    with pytest.raises(sonarmap.ValueError, match="format"):
        sonarmap.OnlineMapper(format="sonar9000")
    ping360 = sonarmap.OnlineMapper(format="ping360")
    assert (ping360.beam_width_deg, ping360.vertical_aperture_deg) == pytest.approx((2.0, 25.0))
    tritech = sonarmap.OnlineMapper(format="v4log")
    assert (tritech.beam_width_deg, tritech.vertical_aperture_deg) == pytest.approx((3.0, 35.0))
    stated = sonarmap.OnlineMapper(beam_width_deg=1.5, vertical_aperture_deg=20.0)
    assert (stated.beam_width_deg, stated.vertical_aperture_deg) == pytest.approx((1.5, 20.0))
    assert sonarmap.OnlineMapper(format="ping360", beam_width_deg=1.0).beam_width_deg == pytest.approx(1.0)


def test_a_log_gives_its_sonar_and_its_resolution(simulated_tank):
    log = simulated_tank.log
    online = sonarmap.OnlineMapper(log=log)
    assert (online.beam_width_deg, online.vertical_aperture_deg) == pytest.approx(log.nominal_beam_deg)
    assert online.resolution == sonarmap.map_sonar_log(log).resolution  # known before the first beam
    assert sonarmap.OnlineMapper(log=log, format="ping360").beam_width_deg == pytest.approx(2.0)
    assert sonarmap.OnlineMapper(format="ping360").resolution is None  # a stream: chosen at its first sweep
    with pytest.raises(TypeError):
        sonarmap.OnlineMapper(log="beams.csv")


def test_a_span_not_recorded_is_nan_or_none(simulated_tank, tmp_path):
    """SonarLog's NaN span (the format states none: a Ping360's) is accepted as not recorded: the
    mapper assumes 45 dB, as for None and as `sonarmap map` does."""
    log = simulated_tank.log
    expected = _bytes_of(sonarmap.map_sonar_log(log, resolution=0.05), tmp_path / "batch.bt")
    online = sonarmap.OnlineMapper(format="csv", resolution=0.05)
    for i in range(len(log)):
        online.add_beam(log.time_s[i], log.bearing_rad[i], log.bin_length_m[i], log.intensities[i, : log.valid_bins[i]],
                        np.nan)
    online.finish()
    assert _bytes_of(online.map(), tmp_path / "online.bt") == expected
    for bad in (0.0, -3.0, np.inf):
        with pytest.raises(sonarmap.ValueError, match="span"):
            sonarmap.OnlineMapper(format="csv").add_beam(0.0, 0.0, 0.01, np.zeros(10, np.uint8), intensity_span_db=bad)


def test_settings_not_recorded_are_marked_as_sonar_log_marks_them(simulated_tank, tmp_path):
    log = simulated_tank.log
    assert np.all(log.gain_setting == -1) and np.all(np.isnan(log.pulse_length_m))  # the simulator records none
    online = _feed(sonarmap.OnlineMapper(log=log), log)
    assert _bytes_of(online, tmp_path / "online.bt") == _bytes_of(sonarmap.map_sonar_log(log), tmp_path / "batch.bt")
    for bad in (0.0, -3.0, np.inf):
        with pytest.raises(sonarmap.ValueError, match="pulse"):
            sonarmap.OnlineMapper(format="csv").add_beam(0.0, 0.0, 0.01, np.zeros(10, np.uint8), pulse_length_m=bad)


def test_the_heads_settings_pass_with_each_beam(tank_csv, tmp_path):
    log = _with_head_settings(tank_csv, tmp_path / "settings.csv", gain_from_beam=300)
    assert log.gain_setting.dtype == np.int32 and log.gain_setting[299] == 0 and log.gain_setting[300] == 2
    assert np.all(log.pulse_length_m == 0.02)
    batch = sonarmap.map_sonar_log(log)
    online = _feed(sonarmap.OnlineMapper(log=log), log)
    assert online.stats.sweeps == batch.stats.sweeps
    assert _bytes_of(online, tmp_path / "online.bt") == _bytes_of(batch, tmp_path / "batch.bt")
    # Without them the gain change joins two settings in one sweep, calibrated together.
    blind = _feed(sonarmap.OnlineMapper(log=log), log, settings=False)
    assert blind.stats.sweeps == batch.stats.sweeps - 1


def test_basin_beam_by_beam_gives_map_sonar_logs_map(shared_file, tmp_path):
    """The shared Ping360 log: 2 m power-on pings, 10 m turns (gain 0, then 2), 20 m sectors."""
    log = sonarmap.read_sonar_log(shared_file("ping360_basin.bin"))
    assert np.all(np.isnan(log.intensity_span_db))  # a Ping360 states no span in dB
    assert set(np.unique(log.gain_setting)) == {0, 2} and np.all(log.pulse_length_m > 0.0)
    batch = sonarmap.map_sonar_log(log)
    assert batch.resolution == 0.05  # the 10 m scale most beams use
    online = sonarmap.OnlineMapper(log=log)
    assert online.resolution == 0.05
    assert _bytes_of(_feed(online, log), tmp_path / "online.bt") == _bytes_of(batch, tmp_path / "batch.bt")
    # At a given resolution a stream needs no whole-log information: the beams' fields suffice.
    fixed = _feed(sonarmap.OnlineMapper(format="ping360", resolution=0.05), log)
    assert _bytes_of(fixed, tmp_path / "fixed.bt") == _bytes_of(batch, tmp_path / "batch.bt")
    # Without the log a stream's automatic resolution grows with the range: the 20 m sectors' 0.1 m.
    assert _feed(sonarmap.OnlineMapper(format="ping360"), log).resolution == 0.1


def test_basin_beam_by_beam_gives_the_clis_map(shared_file, cli, tmp_path):
    path = shared_file("ping360_basin.bin")
    cli("map", path, "-q", "-o", tmp_path / "cli.bt")
    log = sonarmap.read_sonar_log(path)
    online = _feed(sonarmap.OnlineMapper(log=log), log)
    assert _bytes_of(online, tmp_path / "online.bt") == (tmp_path / "cli.bt").read_bytes()
