"""The module and the command-line tool give the same files: the same library behind both."""

import numpy as np
import pytest

import sonarmap


def test_cloud_same_bt_as_cli(cli, tmp_path):
    rng = np.random.default_rng(11)
    points = rng.uniform(-2.0, 2.0, size=(300, 3))
    cloud = tmp_path / "cloud.xyz"
    np.savetxt(cloud, points, fmt="%.17g")
    cli("cloud", cloud, "-o", tmp_path / "cli.bt", "--resolution", "0.1", "--max-range", "2.5", "-q")
    m = sonarmap.OccupancyMap(0.1)
    m.insert_point_cloud(np.loadtxt(cloud), np.zeros(3), max_range=2.5)
    m.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()


def test_cli_simulation_reads_as_python_simulation(cli, tmp_path):
    cli("simulate", "tank", "-o", tmp_path / "sim", "--turns", "2", "--seed", "5")
    run = sonarmap.simulate("tank", turns=2, seed=5)
    run.log.write_csv(str(tmp_path / "py_beams.csv"))
    assert (tmp_path / "py_beams.csv").read_bytes() == (tmp_path / "sim" / "beams.csv").read_bytes()
    log = sonarmap.read_sonar_log(str(tmp_path / "sim" / "beams.csv"))
    assert np.array_equal(log.intensities, run.log.intensities)
    assert np.allclose(log.bearing_rad, run.log.bearing_rad, rtol=0, atol=1e-6)  # the CSV rounds
    assert np.array_equal(sonarmap.read_nav_csv(str(tmp_path / "sim" / "nav.csv")), run.nav)


def test_tilted_loop_with_a_mounting_simulates_as_the_cli_and_maps_as_its_printed_command(cli, tmp_path):
    out = cli("simulate", "quay3d", "--sonar", "ping360-5m", "--mission", "tilted-loop", "--mounting",
              "0.3,0,0.2,0,-45,30", "-o", tmp_path / "sim")
    run = sonarmap.simulate("quay3d", sonar="ping360-5m", mission="tilted-loop", mounting=[0.3, 0, 0.2, 0, -45, 30])
    assert run.mounting == [0.3, 0, 0.2, 0, -45, 30]
    assert sonarmap.simulate("quay3d", sonar="ping360-5m", mission="tilted-loop").mounting == [0, 0, 0, 0, -25, 0]
    run.log.write_csv(str(tmp_path / "py_beams.csv"))
    assert (tmp_path / "py_beams.csv").read_bytes() == (tmp_path / "sim" / "beams.csv").read_bytes()
    assert "--mounting 0.3,0,0.2,0,-45,30" in out.stdout


@pytest.mark.parametrize(
    "options, flags",
    [
        ({}, []),
        ({"resolution": 0.05, "detector": "cfar-ca", "beam_width_deg": 0}, ["--resolution", "0.05", "--detector", "cfar-ca", "--beam-width", "0"]),
        ({"volume": True, "resolution": 0.1, "vertical_aperture_deg": 30, "smoothing": "gaussian"},
         ["--3d", "--resolution", "0.1", "--vertical-aperture", "30", "--smoothing", "gaussian"]),
    ],
)
def test_map_same_bt_as_cli(cli, tmp_path, tank_csv, options, flags):
    cli("map", tank_csv, "-o", tmp_path / "cli.bt", "-q", *flags)
    m = sonarmap.map_sonar_log(sonarmap.read_sonar_log(str(tank_csv)), **options)
    m.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()
    assert m.stats is not None and m.stats.sweeps >= 4 and m.stats.obstacles > 0


def test_map_with_nav_same_bt_as_cli(cli, tmp_path):
    cli("simulate", "harbour", "-o", tmp_path / "sim", "--turns", "2", "--speed", "0.1", "--heading", "30")
    beams, nav = tmp_path / "sim" / "beams.csv", tmp_path / "sim" / "nav.csv"
    mounting = "0.1,0,0.2,0,0,5"
    cli("map", beams, "-o", tmp_path / "cli.bt", "-q", "--nav", nav, "--mounting", mounting, "--resolution", "0.05")
    log = sonarmap.read_sonar_log(str(beams))
    m = sonarmap.map_sonar_log(log, nav=sonarmap.read_nav_csv(str(nav)), mounting=[0.1, 0, 0.2, 0, 0, 5],
                               resolution=0.05)
    m.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()
    from_path = sonarmap.map_sonar_log(log, nav=str(nav), mounting=(0.1, 0, 0.2, 0, 0, 5), resolution=0.05)
    from_path.write(str(tmp_path / "py2.bt"))
    assert (tmp_path / "py2.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()


def test_python_reads_cli_map_and_writes_it_back(cli, tmp_path, tank_csv):
    cli("map", tank_csv, "-o", tmp_path / "cli.bt", "-q")
    m = sonarmap.OccupancyMap.read(str(tmp_path / "cli.bt"))
    m.write(str(tmp_path / "again.bt"))
    assert (tmp_path / "again.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()


def test_cras_log_same_bt_as_cli(cli, shared_file, tmp_path):
    cras = shared_file("cras_micron_tank_static.mat")
    cli("map", cras, "-o", tmp_path / "cli.bt", "-q")
    log = sonarmap.read_sonar_log(cras)
    assert log.format == "mat" and log.intensities.shape[0] == len(log)
    m = sonarmap.map_sonar_log(log)
    m.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()


def test_demo_3d_mission_same_bt_from_python(cli, tmp_path):
    """The demo's 3D run (tilted loop over quay3d, sonar 25 degrees down, --3d at 5 cm) made from
    Python with the log its beams.csv holds (which the demo maps: a bearing written in degrees may
    read back an ulp from the simulated one) and the mission's navigation, mounting and beam: the
    same bytes as the demo's map.bt."""
    cli("demo", "-o", tmp_path / "demo", "-q")
    mission = sonarmap.simulate_mission("tilted-loop", sonar="micron", scene="quay3d")
    assert mission.mounting == [0.0, 0.0, 0.0, 0.0, -25.0, 0.0]
    written = sonarmap.read_sonar_log(str(tmp_path / "demo" / "3d-mission" / "beams.csv"))
    assert len(written) == len(mission.log)
    m = sonarmap.map_sonar_log(written, nav=mission.nav, mounting=mission.mounting, volume=True,
                               resolution=0.05, beam_width_deg=mission.beam_width_deg,
                               vertical_aperture_deg=mission.vertical_aperture_deg)
    m.write(tmp_path / "map.bt")
    assert (tmp_path / "map.bt").read_bytes() == (tmp_path / "demo" / "3d-mission" / "map.bt").read_bytes()


def test_simulated_bag_maps_with_its_own_navigation_as_the_cli_does(cli, tmp_path):
    bag = tmp_path / "run.bag"
    cli("simulate", "harbour", "-o", tmp_path / "sim", "--turns", "2", "--speed", "0.1", "--heading", "30", "--bag", bag, "-q")
    nav_csv = sonarmap.read_nav_csv(str(tmp_path / "sim" / "nav.csv"))
    nav_bag = sonarmap.read_navigation(bag)
    assert nav_bag.shape == nav_csv.shape
    assert np.allclose(nav_bag[:, 0], nav_csv[:, 0], rtol=0, atol=1e-6)  # stamps hold nanoseconds
    assert np.allclose(nav_bag[:, 1:], nav_csv[:, 1:], rtol=0, atol=1e-9)
    cli("map", bag, "-o", tmp_path / "cli.bt", "-q", "--resolution", "0.05")
    m = sonarmap.map_sonar_log(sonarmap.read_sonar_log(str(bag)), nav=bag, resolution=0.05)
    m.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()
    with pytest.raises(sonarmap.FileError, match="no topic /odom"):
        sonarmap.read_navigation(bag, nav_topic="/odom")
    topics = {t["topic"]: t for t in sonarmap.read_bag_topics(bag)}
    assert topics["/odometry"]["type"] == "nav_msgs/Odometry"
    assert topics["/odometry"]["messages"] == len(nav_csv)
    assert topics["/sonar/scan_line"]["messages"] == sonarmap.read_sonar_log(str(bag)).time_s.shape[0]
    assert topics["/tf_static"]["type"] == "tf2_msgs/TFMessage"
    assert topics["/odometry"]["first_s"] == pytest.approx(nav_csv[0, 0], abs=1e-6)


def test_simulated_mcap_reads_as_its_csv(cli, tmp_path):
    mcap = tmp_path / "run.mcap"
    cli("simulate", "tank", "-o", tmp_path / "sim", "--turns", "1", "--mcap", mcap, "-q")
    from_mcap = sonarmap.read_sonar_log(mcap)
    from_csv = sonarmap.read_sonar_log(str(tmp_path / "sim" / "beams.csv"))
    assert from_mcap.format == "mcap"
    assert np.array_equal(from_mcap.intensities, from_csv.intensities)
    mirrored = sonarmap.read_sonar_log(mcap, bearing_direction="ccw")
    total = mirrored.bearing_rad + from_mcap.bearing_rad  # counter-clockwise: the mirror image
    assert np.allclose(np.sin(total), 0, atol=1e-6) and np.allclose(np.cos(total), 1, atol=1e-6)
    with pytest.raises(sonarmap.ValueError):
        sonarmap.read_sonar_log(mcap, bearing_unit="degrees")


def _mavlink2_frame(msgid, crc_extra, payload, seq):
    """A MAVLink 2 frame (mavlink.io/en/guide/serialization.html): trailing zeros truncated,
    CRC-16/MCRF4XX over the bytes after the magic, then CRC_EXTRA."""
    import struct

    def crc(data, c=0xFFFF):
        for b in data:
            t = (b ^ (c & 0xFF)) & 0xFF
            t = (t ^ (t << 4)) & 0xFF
            c = ((c >> 8) ^ (t << 8) ^ (t << 3) ^ (t >> 4)) & 0xFFFF
        return c

    payload = payload.rstrip(b"\0") or b"\0"
    body = bytes([len(payload), 0, 0, seq & 255, 1, 1]) + struct.pack("<I", msgid)[:3] + payload
    return b"\xfd" + body + struct.pack("<H", crc(bytes([crc_extra]), crc(body)))


def test_a_telemetry_log_joined_by_its_offset_maps_as_the_csv_does(cli, tmp_path):
    """A BlueROV2's .tlog (ATTITUDE + LOCAL_POSITION_NED, UTC receive stamps) as map_sonar_log's nav:
    its times are UTC; nav_time_offset_s puts them on the log's clock, as --nav-time-offset does."""
    import struct

    cli("simulate", "tank", "-o", tmp_path / "sim", "--turns", "2", "--seed", "3", "-q")
    nav = sonarmap.read_nav_csv(str(tmp_path / "sim" / "nav.csv"))
    boot_utc_us = 1723630500_000000
    tlog = bytearray()
    for i, (t, x, y, z, roll, pitch, yaw) in enumerate(nav):
        boot_ms = int(round(t * 1000)) + 5000
        stamp = struct.pack(">Q", boot_utc_us + boot_ms * 1000)
        tlog += stamp + _mavlink2_frame(30, 39, struct.pack("<I6f", boot_ms, roll, pitch, yaw, 0, 0, 0), i)
        tlog += stamp + _mavlink2_frame(32, 185, struct.pack("<I6f", boot_ms, x, y, z, 0, 0, 0), i)
    (tmp_path / "flight.tlog").write_bytes(bytes(tlog))
    fixes = sonarmap.read_navigation(tmp_path / "flight.tlog")
    assert fixes.shape == nav.shape
    assert np.allclose(fixes[:, 0] - 1723630505.0, nav[:, 0], atol=1e-3)
    assert np.allclose(fixes[:, 1:], nav[:, 1:], atol=1e-5)

    log = sonarmap.read_sonar_log(tmp_path / "sim" / "beams.csv")
    assert log.clock_utc_s is None
    joined = sonarmap.map_sonar_log(log, nav=tmp_path / "flight.tlog", nav_time_offset_s=-1723630505.0)
    from_csv = sonarmap.map_sonar_log(log, nav=tmp_path / "sim" / "nav.csv")
    assert joined.stats.beams_used == from_csv.stats.beams_used
    assert abs(joined.stats.obstacles - from_csv.stats.obstacles) <= 0.02 * from_csv.stats.obstacles
    cli("map", tmp_path / "sim" / "beams.csv", "--nav", tmp_path / "flight.tlog", "--nav-time-offset=-1723630505",
        "-o", tmp_path / "cli.bt", "-q")
    joined.write(str(tmp_path / "py.bt"))
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()


def test_map_frame_enu_by_default_ned_on_request(cli, tmp_path):
    """map_sonar_log's map is ENU unless map_frame="ned": the same voxels with (x, y, z) of ENU
    being (y, x, -z) of NED, the frame named by ``frame`` and in the written file's header, as the
    CLI's --map-frame writes it."""
    cli("simulate", "harbour", "-o", tmp_path / "sim", "--turns", "1", "--speed", "0.1", "--heading", "30")
    beams, nav = tmp_path / "sim" / "beams.csv", tmp_path / "sim" / "nav.csv"
    log = sonarmap.read_sonar_log(str(beams))
    enu = sonarmap.map_sonar_log(log, nav=str(nav), resolution=0.1)
    ned = sonarmap.map_sonar_log(log, nav=str(nav), resolution=0.1, map_frame="ned")
    assert enu.frame == "ENU" and ned.frame == "NED"
    e, _ = enu.occupied_voxels()
    n, _ = ned.occupied_voxels()
    assert len(e) > 10 and len(e) == len(n)
    swapped = np.column_stack([n[:, 1], n[:, 0], -n[:, 2]])
    def as_set(points):
        return {tuple(np.round(row, 6)) for row in points}
    assert as_set(e) == as_set(swapped)
    ned.write(tmp_path / "py.bt")
    cli("map", beams, "-o", tmp_path / "cli.bt", "-q", "--nav", nav, "--resolution", "0.1", "--map-frame", "ned")
    assert (tmp_path / "py.bt").read_bytes() == (tmp_path / "cli.bt").read_bytes()
    assert b"# sonarmap map frame: NED (x north, y east, z down)\n" in (tmp_path / "cli.bt").read_bytes()[:200]
    assert sonarmap.OccupancyMap.read(tmp_path / "cli.bt").frame == "NED"
    with pytest.raises(sonarmap.ValueError, match="map frame"):
        sonarmap.map_sonar_log(log, map_frame="nwu")
