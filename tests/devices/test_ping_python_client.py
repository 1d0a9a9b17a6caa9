"""Blue Robotics' own Ping360 client (ping-python's brping) against `sonarmap emulate`, over a
pseudo-terminal and over UDP: what the client reads is what a Ping360 would give it.

Runs when SONARMAP_PING_PYTHON names a folder holding a generated `brping` package (ping-python's
generate/generate-python.py writes it; pyserial is needed); skipped otherwise. This file does not
generate brping. SONARMAP_CLI names the `sonarmap` tool (ctest sets it).

The scene is the built-in tank at the 5 m scale (`--sonar ping360-5m --scene tank`): its north
wall is 2.1 m ahead of the head (angle 0), so at 5 m in 1200 samples (222 ticks) its echo is near
sample 504, with dark water before it.
"""

import os
import re
import subprocess
import sys
import time

import pytest

PING_PYTHON = os.environ.get("SONARMAP_PING_PYTHON", "")
if not PING_PYTHON or not os.path.isdir(os.path.join(PING_PYTHON, "brping")):
    pytest.skip("SONARMAP_PING_PYTHON is not set to a folder holding a generated brping package",
                allow_module_level=True)
CLI = os.environ.get("SONARMAP_CLI", "")
if not CLI or not os.path.exists(CLI):
    pytest.skip("SONARMAP_CLI is not set to the sonarmap command-line tool", allow_module_level=True)

sys.path.insert(0, PING_PYTHON)
from brping import Ping360, definitions  # noqa: E402

SAMPLES = 1200
SAMPLE_PERIOD = 222  # 25 ns ticks: 1200 samples over 4.995 m at 1500 m/s
WALL = slice(480, 540)
WATER = slice(150, 450)


@pytest.fixture(scope="module")
def emulator(tmp_path_factory):
    """`sonarmap emulate` serving one head on a pty and another on UDP: (pty path, UDP port)."""
    folder = tmp_path_factory.mktemp("emulate")
    pty = str(folder / "ping360")
    err_path = folder / "emulate.err"
    with open(err_path, "w") as err:
        process = subprocess.Popen(
            [CLI, "emulate", "--sonar", "ping360-5m", "--scene", "tank", "--serial", "pty:" + pty,
             "--udp", "udp://:0", "--baud", "115200", "--duration", "240"],
            stdout=subprocess.DEVNULL, stderr=err)
    port = None
    for _ in range(2000):
        text = err_path.read_text()
        found = re.search(r"on udp://:([0-9]+)", text)
        if found and os.path.exists(pty):
            port = int(found.group(1))
            break
        if process.poll() is not None:
            break
        time.sleep(0.005)
    assert port is not None, err_path.read_text()
    yield pty, port
    process.terminate()
    process.wait(timeout=20)
    text = err_path.read_text()
    print(text)
    assert process.returncode == 0, text
    assert "pings sent" in text, text


def configure(ping):
    """initialize() and the settings of this test, each set_* answered by a device_data."""
    assert ping.initialize()  # protocol_version, then general_request(device_data)
    info = ping.get_device_information()
    assert info is not None and info["device_type"] == 2
    assert info["firmware_version_major"] == 3
    for reply in (ping.set_gain_setting(2), ping.set_sample_period(SAMPLE_PERIOD),
                  ping.set_number_of_samples(SAMPLES), ping.set_transmit_frequency(750),
                  ping.set_transmit_duration(27)):
        assert reply is not None and reply.message_id == definitions.PING360_DEVICE_DATA
        assert len(reply.data) == 0  # transmit = 0: no samples


def sweep(ping):
    """transmitAngle over 0..9 gradians: the device_data messages it returns."""
    replies = []
    for angle in range(10):
        reply = ping.transmitAngle(angle)
        assert reply is not None, f"no device_data for angle {angle}"
        assert reply.message_id == definitions.PING360_DEVICE_DATA
        replies.append(reply)
    return replies


def check_pings(replies):
    for angle, reply in enumerate(replies):
        assert reply.angle == angle
        assert reply.number_of_samples == SAMPLES
        assert len(reply.data) == reply.number_of_samples == reply.data_length
        assert reply.gain_setting == 2
        assert reply.sample_period == SAMPLE_PERIOD
        assert reply.transmit_frequency == 750
        assert reply.transmit_duration == 27
        assert reply.verify_checksum()
    ahead = replies[0].data
    assert max(ahead[WALL]) > 150, "no echo from the wall 2.1 m ahead"
    assert sum(ahead[WATER]) / len(ahead[WATER]) < 30, "the water before the wall is not dark"


def check_state(ping):
    state = ping.get_device_data()  # general_request(device_data): the head's settings
    assert state is not None
    assert state["angle"] == 9
    assert state["gain_setting"] == 2
    assert state["number_of_samples"] == SAMPLES


def check_auto_transmit(ping):
    """auto_transmit over 0..399 by 1 gradian: auto_device_data pings by themselves, until motor_off."""
    ping.control_auto_transmit(1, 1, 27, SAMPLE_PERIOD, 750, SAMPLES, 0, 399, 1, 0)
    angles = []
    for _ in range(5):
        message = ping.wait_message([definitions.PING360_AUTO_DEVICE_DATA], 4.0)
        assert message is not None
        assert len(message.data) == SAMPLES
        angles.append(message.angle)
    assert angles == [0, 1, 2, 3, 4]
    ping.control_motor_off()
    assert ping.wait_message([definitions.COMMON_ACK], 4.0) is not None


def test_serial_client(emulator):
    pty, _ = emulator
    ping = Ping360()
    ping.connect_serial(pty, 115200)  # a break and 'U' first, as to a real head
    configure(ping)
    check_pings(sweep(ping))
    check_state(ping)
    check_auto_transmit(ping)
    ping.iodev.close()


def test_udp_client(emulator):
    _, port = emulator
    ping = Ping360()
    ping.connect_udp("127.0.0.1", port)
    configure(ping)
    check_pings(sweep(ping))
    check_state(ping)
    check_auto_transmit(ping)
    ping.iodev.close()
