"""Sonar logs as arrays, polar and Cartesian images, detectors."""

import numpy as np
import pytest

import sonarmap


def test_log_arrays(simulated_tank):
    log = simulated_tank.log
    n = len(log)
    assert n == 800 and log.format == "simulated"
    assert log.intensities.dtype == np.uint8 and log.intensities.shape == (n, 399)
    for name in ("time_s", "bearing_rad", "bin_length_m", "intensity_span_db"):
        values = getattr(log, name)
        assert values.dtype == np.float64 and values.shape == (n,), name
    assert log.valid_bins.dtype == np.int32 and np.all(log.valid_bins == 399)
    assert np.all((log.bearing_rad >= 0) & (log.bearing_rad < 2 * np.pi))
    assert np.all(np.diff(log.time_s) > 0) and np.all(log.bin_length_m > 0)
    assert log.nominal_beam_deg == pytest.approx((3.0, 35.0))
    sweeps = log.sweeps()
    assert sweeps.dtype == np.int64 and sweeps.shape == (4, 2) and sweeps[0, 0] == 0 and sweeps[-1, 1] == n


def test_log_arrays_are_views_not_copies(simulated_tank):
    log = simulated_tank.log
    first, second = log.intensities, log.intensities
    assert np.shares_memory(first, second)  # one contiguous buffer, built once
    assert not first.flags.writeable and first.flags.c_contiguous
    del log  # the arrays keep their owner alive
    assert int(first.sum()) == int(second.sum())


def test_log_from_arrays_round_trip(simulated_tank, tmp_path):
    log = simulated_tank.log
    copy = sonarmap.SonarLog.from_arrays(log.intensities, log.time_s, log.bearing_rad, log.bin_length_m)
    assert np.array_equal(copy.intensities, log.intensities)
    path = tmp_path / "beams.csv"
    copy.write_csv(str(path))
    again = sonarmap.read_sonar_log(str(path))
    assert np.array_equal(again.intensities, log.intensities) and np.array_equal(again.time_s, log.time_s)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.SonarLog.from_arrays(log.intensities.astype(np.int16), log.time_s, log.bearing_rad, 0.01)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.SonarLog.from_arrays(log.intensities, log.time_s[:-1], log.bearing_rad, 0.01)


def test_bad_log_files(tmp_path):
    bad = tmp_path / "beams.csv"
    bad.write_text("this is not a beam csv\n1,2,3\n")
    with pytest.raises(sonarmap.FileError, match="beams.csv"):
        sonarmap.read_sonar_log(str(bad))
    with pytest.raises(sonarmap.ValueError):
        sonarmap.read_sonar_log(str(bad), format="nonsense")
    truncated = tmp_path / "log.mat"
    truncated.write_bytes(b"MATLAB 5.0 MAT-file" + b"\0" * 20)
    with pytest.raises(sonarmap.FileError):
        sonarmap.read_sonar_log(str(truncated))


def test_polar_and_cartesian_images(simulated_tank):
    log = simulated_tank.log
    polar = sonarmap.polar_image(log)  # the largest sweep, as --polar-png
    assert polar.intensities.shape == (200, 399) and polar.intensities.dtype == np.uint8
    assert polar.range_m.shape == (399,) and polar.bearing_rad.shape == (200,)
    assert np.array_equal(polar.intensities, log.intensities[600:800])
    second = sonarmap.polar_image(log, sweep=1)
    assert np.array_equal(second.intensities, log.intensities[200:400])
    assert np.array_equal(sonarmap.polar_image(log, first=10, last=20).intensities, log.intensities[10:20])
    with pytest.raises(sonarmap.ValueError):
        sonarmap.polar_image(log, sweep=99)
    image = sonarmap.cartesian_image(polar, pixel_size_m=0.05)
    side = 2 * int(np.ceil(399 * polar.bin_length_m / 0.05)) + 1
    assert image.shape == (side, side) and image.dtype == np.uint8 and image.max() > 0
    assert sonarmap.cartesian_extent(image, 0.05)[1] == pytest.approx(side / 2 * 0.05)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.cartesian_image(polar, pixel_size_m=-1.0)


def test_polar_view_is_zero_copy_and_writable(simulated_tank):
    polar = sonarmap.polar_image(simulated_tank.log, sweep=0)
    view = polar.intensities
    view[:, :] = 0
    assert polar.intensities.max() == 0  # the view writes into the C++ image
    assert sonarmap.cartesian_image(polar).max() == 0


def test_detectors(simulated_tank):
    polar = sonarmap.polar_image(simulated_tank.log)
    before = polar.intensities.copy()
    result = sonarmap.detect_obstacles(polar)
    assert np.array_equal(polar.intensities, before)  # the input is not modified
    bins, ranges = result["obstacle_bin"], result["range_m"]
    assert bins.dtype == np.int32 and bins.shape == (200,) and ranges.dtype == np.float64
    found = bins >= 0
    assert found.mean() > 0.8  # the tank's walls surround the sonar
    assert np.all(np.isnan(ranges[~found])) and np.all(ranges[found] > 0)
    ends = result["echo_end_m"]  # the loud echo falls back behind its leading edge
    assert np.all(np.isnan(ends[~found])) and np.all(ends[found] >= ranges[found])
    assert isinstance(result["cleaned"], sonarmap.PolarImage)
    for detector in ("threshold", "canny", "cfar-os"):
        other = sonarmap.detect_obstacles(polar, detector=detector)
        assert other["obstacle_bin"].shape == (200,)
    with pytest.raises(sonarmap.ValueError, match="detector"):
        sonarmap.detect_obstacles(polar, detector="magic")
    with pytest.raises(sonarmap.ValueError, match="^false_alarm expects"):
        sonarmap.detect_obstacles(polar, false_alarm=0.9)


def test_polar_image_from_arrays():
    rng = np.random.default_rng(1)
    image = rng.integers(0, 40, size=(100, 200), dtype=np.uint8)
    image[:, 150] = 250
    bearings = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    polar = sonarmap.PolarImage(image, bearings, 0.02)
    assert np.array_equal(polar.intensities, image)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.PolarImage(image, bearings[:50], 0.02)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.PolarImage(image.astype(np.float64), bearings, 0.02)


def test_a_step_into_reverberation_is_a_weak_return():
    # Water clipped at the receiver's floor (one-look speckle 6 dB under it, 45 dB over 0..255) and
    # one beam stepping into a reverberation tail of 30..90 counts at 5 m: never the 16.9 dB a
    # loud echo needs over the background, the default (evidence) detector's weak return.
    rng = np.random.default_rng(7)
    level_db = -6.0 + 10.0 * np.log10(rng.exponential(size=(100, 300)))
    image = np.clip(np.rint(level_db * 255.0 / 45.0), 0, 255).astype(np.uint8)
    image[10, 100:] = rng.integers(30, 91, size=200)
    polar = sonarmap.PolarImage(image, np.linspace(0, 2 * np.pi, 100, endpoint=False), 0.05)
    result = sonarmap.detect_obstacles(polar)
    assert result["weak"].dtype == np.bool_ and result["weak"].shape == (100,)
    assert result["weak"][10] and abs(result["range_m"][10] - 5.025) < 0.03
    assert np.count_nonzero(result["obstacle_bin"] >= 0) == 1
    loud_only = sonarmap.detect_obstacles(polar, detector="background")
    assert loud_only["obstacle_bin"][10] == -1 and not loud_only["weak"].any()
