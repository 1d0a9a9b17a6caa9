"""Dead-reckoning simulations (simulate's mission and DVL/heading errors) and eval_trajectory."""
import numpy as np
import pytest

import sonarmap


def test_mission_with_dead_reckoning_errors(tmp_path):
    assert sonarmap.mission_plan_names() == ["harbour-loop", "harbour-lawnmower", "harbour-featureless", "hull-loop"]
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
    dead = sonarmap.eval_trajectory(run.dead_reckoning, run.nav)["ate_rmse_m"]
    corrected = sonarmap.eval_trajectory(slammed.trajectory, run.nav)["ate_rmse_m"]
    assert corrected < dead / 2.0
    plain = sonarmap.map_sonar_log(run.log, run.dead_reckoning)
    assert plain.trajectory is None and plain.slam is None
    assert slammed.copy().trajectory.shape == slammed.trajectory.shape
