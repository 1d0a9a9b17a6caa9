"""Dead-reckoning simulations (simulate's mission and DVL/heading errors) and eval_trajectory."""
import numpy as np
import pytest

import sonarmap


def test_mission_with_dead_reckoning_errors(tmp_path):
    assert sonarmap.mission_plan_names() == ["harbour-loop", "harbour-lawnmower", "harbour-featureless", "hull-loop",
                                             "lawnmower-3d", "tilted-loop"]
    plain = sonarmap.simulate("harbour", mission="harbour-featureless", nav_rate=2)
    run = sonarmap.simulate("harbour", mission="harbour-featureless", nav_rate=2, dvl_scale_error=0.02,
                            heading_bias_deg=1.0, dvl_noise=0.002, gyro_walk=0.002)
    assert plain.dead_reckoning.shape == (0, 7)
    assert np.array_equal(run.nav, plain.nav)  # nav stays the truth
    assert np.array_equal(run.truth_nav, run.nav)
    assert run.dead_reckoning.shape == run.nav.shape
    assert np.array_equal(run.dead_reckoning[:, 0], run.nav[:, 0])
    assert np.array_equal(run.log.intensities, plain.log.intensities)  # the beams do not change
    # 40 m east: 2 % along track and 1 degree (0.7 m) across it, plus a little noise.
    drift = run.dead_reckoning[-1, 1:3] - run.nav[-1, 1:3]
    assert drift[1] == pytest.approx(0.8, abs=0.1)
    assert drift[0] == pytest.approx(-0.7, abs=0.1)

    e = sonarmap.eval_trajectory(run.dead_reckoning, run.nav)
    assert e["poses"] == len(run.nav)
    assert e["distance_m"] == pytest.approx(40.0, abs=0.01)
    assert e["final_drift_pct"] == pytest.approx(100.0 * np.hypot(*drift) / 40.0, rel=1e-6)
    assert e["ate_rmse_m"] > 0.0
    assert e["ate_start_rmse_m"] >= e["ate_rmse_m"]  # the fit is the least error; the start is not fitted
    same = sonarmap.eval_trajectory(run.nav, run.nav, se3=True, segment_m=5.0)
    assert same["ate_rmse_m"] == pytest.approx(0.0, abs=1e-9)

    path = tmp_path / "nav.csv"
    sonarmap.write_nav_csv(path, run.dead_reckoning)
    assert sonarmap.eval_trajectory(path, run.nav) == e  # a path reads the CSV (or a TUM file)


def test_mission_errors():
    with pytest.raises(sonarmap.ValueError, match="harbour"):
        sonarmap.simulate("hull", mission="harbour-loop")
    with pytest.raises(sonarmap.ValueError):
        sonarmap.simulate("harbour", mission="lake-loop")
    with pytest.raises(sonarmap.ValueError):
        sonarmap.simulate("harbour", dvl_noise=-1.0)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.eval_trajectory(np.zeros((2, 7)), np.zeros((2, 7)))


def test_map_sonar_log_with_slam():
    run = sonarmap.simulate("harbour", mission="harbour-loop", dvl_scale_error=0.03, heading_bias_deg=2.0,
                            gyro_walk=0.02)
    slammed = sonarmap.map_sonar_log(run.log, run.dead_reckoning, slam=True)
    assert slammed.trajectory.shape == run.dead_reckoning.shape
    assert slammed.slam["scans"] == 17
    assert any(loop["accepted"] for loop in slammed.slam["loop_closures"])
    # The quay and piles measure the 3 % scale error (distances 3 % long: a scale under 1).
    assert slammed.slam["odometry_scale_observed"]
    assert 0.0 < slammed.slam["odometry_scale_sigma"] < 0.03 and slammed.slam["odometry_scale"] < 0.995
    dead = sonarmap.eval_trajectory(run.dead_reckoning, run.nav)["ate_rmse_m"]
    corrected = sonarmap.eval_trajectory(slammed.trajectory, run.nav)["ate_rmse_m"]
    assert corrected < dead / 2.0
    plain = sonarmap.map_sonar_log(run.log, run.dead_reckoning)
    assert plain.trajectory is None and plain.slam is None
    assert slammed.copy().trajectory.shape == slammed.trajectory.shape
    # The true track given and stated as good navigation is left within a centimetre.
    kept = sonarmap.map_sonar_log(run.log, run.nav, slam=True, nav_class="absolute")
    assert sonarmap.eval_trajectory(kept.trajectory, run.nav)["ate_rmse_m"] < 0.01
    with pytest.raises(sonarmap.ValueError, match="dvl-ins"):
        sonarmap.map_sonar_log(run.log, run.nav, slam=True, nav_class="submarine")
    assert not slammed.slam["heading_only"]


def test_map_sonar_log_with_slam_on_the_heading_only():
    # A BlueROV2 without a DVL logs its attitude and leaves north and east 0: the position comes
    # from the scans (nav_class "auto" takes it for "ahrs"), the vehicle believed still otherwise.
    run = sonarmap.simulate("hull", mission="hull-loop", sonar="seaking-30")
    heading = run.nav.copy()
    heading[:, 1:3] = 0.0
    found = sonarmap.map_sonar_log(run.log, heading, slam=True)
    assert found.slam["heading_only"]
    assert found.slam["matches_beyond_limits"] == 0
    with pytest.raises(sonarmap.ValueError, match="max_speed"):
        sonarmap.map_sonar_log(run.log, heading, slam=True, max_speed=0.0)
    believed = sonarmap.map_sonar_log(run.log, heading, slam=True, nav_class="dvl-ahrs")
    assert not believed.slam["heading_only"]
    still = sonarmap.eval_trajectory(heading, run.nav)["ate_rmse_m"]
    assert still > 20.0
    assert sonarmap.eval_trajectory(found.trajectory, run.nav)["ate_rmse_m"] < 0.3 * still
    assert sonarmap.eval_trajectory(believed.trajectory, run.nav)["ate_rmse_m"] > 0.8 * still


def rectangle_scans(count=6, forward_m=0.0):
    """Point scans of a 6 x 4 m rectangle of walls every 2 degrees, seen from a vehicle still or
    moving forward_m along x between two scans (10 s apart)."""
    rows = []
    for scan in range(count):
        ahead = forward_m * scan
        for k in range(180):
            a = np.radians(2.0 * k)
            c, s = np.cos(a), np.sin(a)
            r = min((4.0 - ahead if c > 0 else 2.0 + ahead) / abs(c) if abs(c) > 1e-9 else 1e9,
                    (1.5 if s > 0 else 2.5) / abs(s) if abs(s) > 1e-9 else 1e9)
            rows.append((scan, 10.0 * scan + 0.05 * k, r * c, r * s))
    return np.array(rows, dtype=np.float64)


def test_localize_point_scans(tmp_path):
    scans = rectangle_scans()
    alone = sonarmap.localize_point_scans(scans)
    assert alone["scans"] == 6 and alone["matches_accepted"] >= 4
    assert np.abs(alone["trajectory"][:, 1:3]).max() < 0.03  # still
    assert alone["points_behind_echoes"] == 0
    # Each echo listed as two bins, the second 5 cm behind along the line of sight: left out.
    behind = scans.copy()
    behind[:, 2:4] *= (1.0 + 0.05 / np.hypot(scans[:, 2], scans[:, 3]))[:, None]
    both = np.empty((2 * len(scans), 4))
    both[0::2], both[1::2] = scans, behind  # each point followed by its second bin, at its time
    thick = sonarmap.localize_point_scans(both)
    assert thick["points_behind_echoes"] == len(scans)
    np.testing.assert_array_equal(thick["trajectory"], alone["trajectory"])
    nav = np.zeros((71, 7))
    nav[:, 0] = np.arange(71.0)
    nav[:, 3] = 1.0
    path = tmp_path / "scans.csv"
    with open(path, "w") as f:
        f.write("scan,time_s,x_m,y_m\n")
        for row in scans:
            f.write(f"{int(row[0])},{row[1]!r},{row[2]!r},{row[3]!r}\n")
    corrected = sonarmap.localize_point_scans(path, nav=nav, range_sigma=0.05, bearing_sigma=1.5)
    assert corrected["trajectory"].shape == nav.shape
    e = sonarmap.eval_trajectory(corrected["trajectory"], nav)
    assert e["ate_start_rmse_m"] < 0.03 and e["ate_rmse_m"] <= e["ate_start_rmse_m"] + 1e-9
    trusted = sonarmap.localize_point_scans(path, nav=nav, nav_class="absolute")
    assert trusted["trajectory"].shape == nav.shape
    with pytest.raises(sonarmap.ValueError, match="dvl-ahrs, dvl-ins, absolute"):
        sonarmap.localize_point_scans(path, nav=nav, nav_class="submarine")
    with pytest.raises(sonarmap.ValueError, match="shape"):
        sonarmap.localize_point_scans(scans[:, :3])
    with pytest.raises(sonarmap.ValueError, match="integer"):
        sonarmap.localize_point_scans(scans + np.array([0.5, 0.0, 0.0, 0.0]))
    with pytest.raises(sonarmap.ValueError, match="point 1: .* must not decrease"):
        sonarmap.localize_point_scans(scans[::-1].copy())
    broken = tmp_path / "broken.csv"
    broken.write_text("scan,time_s,x_m,y_m\n0,2,1,1\n0,1,1,1\n")
    with pytest.raises(sonarmap.FileError, match="line 3"):
        sonarmap.localize_point_scans(broken)


def test_localize_point_scans_within_the_vehicle_limits():
    # 0.4 m forward every 10 s (0.04 m/s), no navigation: found within the default limits; under
    # max_speed 0.02 m/s the matches that need more are refused and the track never goes faster.
    scans = rectangle_scans(forward_m=0.4)
    found = sonarmap.localize_point_scans(scans)
    assert found["matches_beyond_limits"] == 0
    assert abs(found["trajectory"][-1, 1] - 2.0) < 0.05
    held = sonarmap.localize_point_scans(scans, max_speed=0.02)
    assert held["matches_beyond_limits"] >= 1
    reference = held["trajectory"][1::3]  # each scan's reference time
    steps = np.linalg.norm(np.diff(reference[:, 1:3], axis=0), axis=1)
    assert np.all(steps <= 0.02 * np.diff(reference[:, 0]) + 1e-6)
    with pytest.raises(sonarmap.ValueError, match="max_turn_rate"):
        sonarmap.localize_point_scans(scans, max_turn_rate=-1.0)


def test_localize_the_st_pere_survey(shared_file):
    # The real marina survey (its point scans gzipped as shared): the dead reckoning's compass drifts
    # with the heading; localize finds the deviation and comes within 3 m of the DGPS from the start.
    scans = shared_file("stpere_marina/scans.csv.gz")
    nav = shared_file("stpere_marina/dr_nav.csv")
    truth = sonarmap.read_navigation(shared_file("stpere_marina/dgps_truth_nav.csv"))
    result = sonarmap.localize_point_scans(scans, nav=nav)
    before = sonarmap.eval_trajectory(sonarmap.read_navigation(nav), truth)
    after = sonarmap.eval_trajectory(result["trajectory"], truth)
    assert before["ate_start_rmse_m"] > 11.0
    assert after["ate_start_rmse_m"] < 3.0 and after["ate_rmse_m"] < 2.0
    a_deg, b_deg = result["compass_deviation_deg"]
    assert 3.0 < b_deg < 7.0 and abs(a_deg) < 3.0  # the DGPS's course gives -2.2 cos + 5.2 sin
    assert result["loop_closures_accepted"] >= 8


def test_map_sonar_log_about_a_local_origin(tmp_path):
    """A navigation in UTM maps about a local origin as the same navigation does near zero."""
    run = sonarmap.simulate("harbour", mission="harbour-loop")
    utm = run.nav.copy()
    utm[:, 1] += 4_600_000.0
    utm[:, 2] += 500_000.0
    near = sonarmap.map_sonar_log(run.log, run.nav, resolution=0.1)
    given = sonarmap.map_sonar_log(run.log, utm, resolution=0.1, origin=(4_600_000.0, 500_000.0))
    assert near.origin is None
    assert given.origin == (4_600_000.0, 500_000.0, 0.0)
    near.write(tmp_path / "near.bt")
    given.write(tmp_path / "given.bt")
    # The same voxels; the file names its origin in a header line, read back with it.
    origin_line = b"# sonarmap map origin: 4600000 500000 0 m"
    given_bytes = (tmp_path / "given.bt").read_bytes()
    assert origin_line in given_bytes
    line_end = given_bytes.index(b"\n", given_bytes.index(origin_line)) + 1
    without_origin = given_bytes[: given_bytes.index(origin_line)] + given_bytes[line_end:]
    assert (tmp_path / "near.bt").read_bytes() == without_origin
    assert sonarmap.OccupancyMap.read(tmp_path / "given.bt").origin == (4_600_000.0, 500_000.0, 0.0)
    # By default the first fix; the trajectory is given back in the navigation's own coordinates.
    automatic = sonarmap.map_sonar_log(run.log, utm, resolution=0.1, slam=True, nav_class="absolute")
    assert automatic.origin == (utm[0, 1], utm[0, 2], 0.0)
    assert np.abs(automatic.trajectory[:, 1:3] - utm[:, 1:3]).max() < 0.05
    # 10 km north: no origin fits it at 5 cm; the error names the fix and the resolution that does.
    spread = utm.copy()
    spread[:, 1] += np.linspace(0.0, 10_000.0, len(spread))
    with pytest.raises(sonarmap.ValueError, match=r"navigation fix at .*no origin=\(north_m, east_m\[, down_m\]\) fits it.*resolution="):
        sonarmap.map_sonar_log(run.log, spread, resolution=0.05)
