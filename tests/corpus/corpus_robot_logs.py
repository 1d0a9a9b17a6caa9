"""The robots' logs of the broken-input corpus and their valid seeds, built byte by byte for
make_corpus.py: BlueROV2 logs (MAVLink 2 telemetry .tlog, ArduPilot dataflash .BIN), ROS 1 bags (the ROS wiki's "Bags/Format/2.0", include/sonarmap/formats/ros_bag_reader.hpp),
ROS 2 MCAP files (mcap.dev/spec, version 0; CDR messages) and rosbag2's SQLite storage. Each *_files()
returns ({broken name: bytes}, {valid name: bytes}). Python 3 standard library only.
"""

import bz2
import pathlib
import sqlite3
import struct
import tempfile

HUGE = 1_000_000_000  # a count no tiny file can hold


# ---- ROS 1 bags (format 2.0, uncompressed chunks) -------------------------------------------------

SCAN_LINE_DEFINITION = (b"Header header\nfloat32 angle\nfloat32 bin_distance_step\nmicron_driver_ros/IntensityBin[] bins\n"
                        b"\n" + b"=" * 80 + b"\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
                        b"\n" + b"=" * 80 + b"\nMSG: micron_driver_ros/IntensityBin\nfloat32 distance\nuint8 intensity\n")


def bag_header(fields):
    """A record header: each field a uint32 length and NAME=VALUE."""
    return b"".join(struct.pack("<I", len(name) + 1 + len(value)) + name + b"=" + value for name, value in fields)


def bag_record(fields, data):
    header = bag_header(fields)
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def scan_line(seq, angle_deg, intensities, step=0.05, seconds=1000):
    out = struct.pack("<IIII", seq, seconds + seq, 0, 0) + struct.pack("<ffI", angle_deg, step, len(intensities))
    return out + b"".join(struct.pack("<fB", (i + 0.5) * step, v) for i, v in enumerate(intensities))


def ros_bag(messages, topic=b"/sonar", datatype=b"micron_driver_ros/ScanLine", definition=SCAN_LINE_DEFINITION,
            compression=b"none", index_shift=0, pack=lambda data: data, more=()):
    """A bag of one chunk holding `messages` (serialized) on one connection, one second apart, and
    the connections of `more` ((topic, datatype, definition, messages) each) after it; its index
    entries' offsets moved by `index_shift` bytes, its chunk's records stored as `pack` gives."""
    u32, u64 = (lambda v: struct.pack("<I", v)), (lambda v: struct.pack("<Q", v))
    connections, chunk_data, indexes = b"", b"", []
    all_connections = [(topic, datatype, definition, messages)] + list(more)
    for conn, (name, kind, text, payloads) in enumerate(all_connections):
        fields = [(b"topic", name), (b"type", kind), (b"md5sum", b"*")]
        if text is not None:
            fields.append((b"message_definition", text))
        connection = bag_record([(b"op", b"\x07"), (b"conn", u32(conn)), (b"topic", name)], bag_header(fields))
        connections += connection
        chunk_data += connection
        index = b""
        for i, message in enumerate(payloads):
            stamp = struct.pack("<II", 1000 + i, 0)
            index += stamp + u32(len(chunk_data) + index_shift)
            chunk_data += bag_record([(b"op", b"\x02"), (b"conn", u32(conn)), (b"time", stamp)], message)
        indexes.append(bag_record([(b"op", b"\x04"), (b"ver", u32(1)), (b"conn", u32(conn)),
                                   (b"count", u32(len(payloads)))], index))
    chunk = bag_record([(b"op", b"\x05"), (b"compression", compression), (b"size", u32(len(chunk_data)))], pack(chunk_data))
    chunk_pos = 13 + 4096
    index_pos = chunk_pos + len(chunk) + sum(len(i) for i in indexes)
    longest = max(len(c[3]) for c in all_connections)
    times = [struct.pack("<II", 1000, 0), struct.pack("<II", 1000 + max(longest - 1, 0), 0)]
    chunk_info = bag_record([(b"op", b"\x06"), (b"ver", u32(1)), (b"chunk_pos", u64(chunk_pos)),
                             (b"start_time", times[0]), (b"end_time", times[1]), (b"count", u32(len(all_connections)))],
                            b"".join(u32(conn) + u32(len(c[3])) for conn, c in enumerate(all_connections)))
    header_fields = bag_header([(b"op", b"\x03"), (b"index_pos", u64(index_pos)), (b"conn_count", u32(len(all_connections))),
                                (b"chunk_count", u32(1))])
    padding = 4096 - 4 - len(header_fields) - 4
    bag_header_record = struct.pack("<I", len(header_fields)) + header_fields + struct.pack("<I", padding) + b" " * padding
    return b"#ROSBAG V2.0\n" + bag_header_record + chunk + b"".join(indexes) + connections + chunk_info


ODOMETRY_DEFINITION = (b"Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
                       b"\n" + b"=" * 80 + b"\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
                       b"\n" + b"=" * 80 + b"\nMSG: geometry_msgs/PoseWithCovariance\ngeometry_msgs/Pose pose\nfloat64[36] covariance\n"
                       b"\n" + b"=" * 80 + b"\nMSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"
                       b"\n" + b"=" * 80 + b"\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n"
                       b"\n" + b"=" * 80 + b"\nMSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n")


# miniking_ros/AcousticBeam (the srv/miniking_ros driver's msg/AcousticBeam.msg, with its comments)
MINIKING_DEFINITION = (b"Header header\nfloat32 range_max   # Maximum range value [m]\n"
                       b"int32 bins          # Number of bins of the returned echoes\n"
                       b"float32 angle       # Angle of the current scan\nuint8[] intensities # Intensities of the returned echoes\n"
                       b"\n" + b"=" * 80 + b"\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n")


def acoustic_beam(seq, angle_deg, intensities, range_m=10.0):
    header = struct.pack("<IIII", seq, 1000 + seq, 0, 5) + b"sonar"
    return header + struct.pack("<fif", range_m, len(intensities), angle_deg) + struct.pack("<I", len(intensities)) + bytes(intensities)


def odometry(seq, position, quaternion, frame=b"odom"):
    """A nav_msgs/Odometry as ODOMETRY_DEFINITION lays it out (its pose only, no twist)."""
    header = struct.pack("<III", seq, 1000 + seq, 0) + struct.pack("<I", len(frame)) + frame
    child = struct.pack("<I", 9) + b"base_link"
    return header + child + struct.pack("<3d", *position) + struct.pack("<4d", *quaternion) + struct.pack("<36d", *([0.0] * 36))


def huge_chunk(beams):
    bag = ros_bag(beams)
    at = bag.index(b"compression=none") + len(b"compression=none") + 4 + len(b"size=")
    return bag[:at] + struct.pack("<I", 4_000_000_000) + bag[at + 4:]


def bag_records(data, start):
    """(start, end, op) of each whole record of `data` from byte `start`."""
    out = []
    while start + 4 <= len(data):
        header_length = struct.unpack_from("<I", data, start)[0]
        header_end = start + 4 + header_length
        if header_end + 4 > len(data):
            break
        end = header_end + 4 + struct.unpack_from("<I", data, header_end)[0]
        if end > len(data):
            break
        op = data[data.index(b"op=", start + 4, header_end) + 3]
        out.append((start, end, op))
        start = end
    return out


def stopped_recording(bag, keep):
    """`bag` as a stopped `rosbag record` leaves it: its header's index position 0, nothing after its
    chunk, whose sizes were never written (0), and its records cut `keep` bytes after the chunk's
    header (the ROS wiki's "Bags/Format/2.0"; rosbag writes the chunk's sizes when it closes it)."""
    out = bytearray(bag)
    at = out.index(b"index_pos=") + len(b"index_pos=")
    out[at:at + 8] = bytes(8)
    chunk_at, chunk_end, _ = next(r for r in bag_records(bag, 13) if r[2] == 0x05)
    size_at = out.index(b"size=", chunk_at) + len(b"size=")
    out[size_at:size_at + 4] = bytes(4)
    header_end = chunk_at + 4 + struct.unpack_from("<I", bag, chunk_at)[0]
    out[header_end:header_end + 4] = bytes(4)
    return bytes(out[:header_end + 4 + keep])


def ros_bag_files():
    beams = [scan_line(i, 1.8 * i, [0, 2, 9, 180, 120, 40]) for i in range(3)]
    small = ros_bag(beams)
    # a message whose bins array declares far more elements than its bytes hold
    lying = scan_line(0, 0.0, [1, 2])[:-10] + struct.pack("<I", HUGE)
    return {
        "bag_text.bag": b"this is not a ROS bag\n",
        "bag_truncated.bag": small[:len(small) // 2],
        "bag_unknown_compression.bag": ros_bag(beams, compression=b"zip"),
        "bag_no_definition.bag": ros_bag(beams, definition=None),
        "bag_bad_definition.bag": ros_bag(beams, definition=b"float32\n"),
        "bag_no_sonar.bag": ros_bag([struct.pack("<I", 2) + b"hi"], topic=b"/chatter", datatype=b"std_msgs/String",
                                    definition=b"string data\n"),
        "bag_messages_cut.bag": ros_bag([scan_line(0, 0.0, [1, 2])[:-3], lying]),
        # lengths rosbag_storage would allocate as they stand (a 4 GiB record header, a chunk of 4 GB)
        "bag_huge_header.bag": small[:13] + struct.pack("<I", 0xFFFFFFF0) + small[17:],
        "bag_huge_chunk.bag": huge_chunk(beams),
        # an index entry pointing into a message, not at its start (rosbag_storage would read its
        # header length from the middle of the message)
        "bag_index_mid_message.bag": ros_bag(beams, index_shift=6),
        "bag_bz2_not_bz2.bag": ros_bag(beams, compression=b"bz2"),
        "bag_version_1_2.bag": b"#ROSBAG V1.2\n" + small[13:],
        # cut short inside its chunk's last message (a full disk): the messages before are read
        "bag_cut_in_chunk.bag": small[:bag_records(small, 13)[1][1] - 30],
        # a stopped `rosbag record`: unindexed, its last chunk unterminated and cut inside a message
        "bag_stopped_recording.bag": stopped_recording(small, 800),
        # the same, its chunk bz2-compressed: nothing of its stream decompresses, nothing is usable
        "bag_stopped_recording_bz2.bag": stopped_recording(ros_bag(beams, compression=b"bz2", pack=bz2.compress), 40),
        # navigation whose every orientation is no rotation (a pose left at zero)
        "bag_odometry_zero_quaternion.bag": ros_bag(beams, more=[(b"/odom", b"nav_msgs/Odometry", ODOMETRY_DEFINITION,
                                                                  [odometry(i, (i, 0, 0), (0, 0, 0, 0)) for i in range(3)])]),
    }, {"bag_small.bag": small, "bag_small_bz2.bag": ros_bag(beams, compression=b"bz2", pack=bz2.compress),
        "bag_miniking.bag": ros_bag([acoustic_beam(i, 90.0 + 0.9 * i, [0, 1, 5, 200, 80, 9, 4, 2]) for i in range(3)],
                                    topic=b"/miniking_node/sonar", datatype=b"miniking_ros/AcousticBeam",
                                    definition=MINIKING_DEFINITION),
        "bag_with_odometry.bag": ros_bag(beams, more=[(b"/odom", b"nav_msgs/Odometry", ODOMETRY_DEFINITION,
                                                       [odometry(i, (0.1 * i, 0, 0), (0, 0, 0, 1)) for i in range(3)])])}


# ---- ROS 2 logs in MCAP (mcap.dev/spec, version 0; CDR messages, ros2msg schemas) ------------------

MCAP_MAGIC = b"\x89MCAP0\r\n"
SCAN_LINE_2 = (b"std_msgs/Header header\nfloat32 angle\nfloat32 bin_distance_step\nmicron_driver_ros/IntensityBin[] bins\n"
               + b"=" * 80 + b"\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n"
               + b"=" * 80 + b"\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"
               + b"=" * 80 + b"\nMSG: micron_driver_ros/IntensityBin\nfloat32 distance\nuint8 intensity\n")


def mcap_record(opcode, content):
    return struct.pack("<BQ", opcode, len(content)) + content


def mcap_text(value):
    return struct.pack("<I", len(value)) + value


def cdr_scan_line(seq, angle_deg, intensities, step=0.05, encapsulation=b"\x00\x01\x00\x00"):
    """A micron_driver_ros/msg/ScanLine in plain little-endian CDR (each number aligned to its size)."""
    out = struct.pack("<iI", 1000 + seq, 0) + struct.pack("<I", 6) + b"sonar\x00"
    out += b"\x00" * (-len(out) % 4) + struct.pack("<ffI", angle_deg, step, len(intensities))
    for i, value in enumerate(intensities):
        out += b"\x00" * (-len(out) % 4) + struct.pack("<fB", (i + 0.5) * step, value)
    return encapsulation + out


def mcap_file(messages, definition=SCAN_LINE_2, compression=b"", pack=lambda data: data, size=None):
    """An MCAP file of one schema, one channel and one chunk holding `messages` (CDR bytes)."""
    schema = mcap_record(0x03, struct.pack("<H", 1) + mcap_text(b"micron_driver_ros/msg/ScanLine") + mcap_text(b"ros2msg")
                         + mcap_text(definition))
    channel = mcap_record(0x04, struct.pack("<HH", 1, 1) + mcap_text(b"/sonar") + mcap_text(b"cdr") + struct.pack("<I", 0))
    records = b"".join(mcap_record(0x05, struct.pack("<HIQQ", 1, i, (1000 + i) * 10**9, (1000 + i) * 10**9) + m)
                       for i, m in enumerate(messages))
    packed = pack(records)
    chunk = mcap_record(0x06, struct.pack("<QQQI", 1000 * 10**9, (1000 + len(messages)) * 10**9,
                                          len(records) if size is None else size, 0)
                        + mcap_text(compression) + struct.pack("<Q", len(packed)) + packed)
    end = mcap_record(0x0F, struct.pack("<I", 0)) + mcap_record(0x02, struct.pack("<QQI", 0, 0, 0))
    return MCAP_MAGIC + mcap_record(0x01, mcap_text(b"ros2") + mcap_text(b"corpus")) + schema + channel + chunk + end + MCAP_MAGIC


def mcap_files():
    beams = [cdr_scan_line(i, 1.8 * i, [0, 2, 9, 180, 120, 40]) for i in range(3)]
    small = mcap_file(beams)
    past_end = bytearray(small)
    past_end[len(MCAP_MAGIC) + 1:len(MCAP_MAGIC) + 9] = struct.pack("<Q", 2**40)  # the header record's length
    return {
        "mcap_text.mcap": b"\x89MCAP but not really\n",
        "mcap_truncated.mcap": small[:len(small) // 2],
        "mcap_record_past_end.mcap": bytes(past_end),
        "mcap_unknown_compression.mcap": mcap_file(beams, compression=b"zip"),
        "mcap_huge_chunk.mcap": mcap_file(beams, size=4_000_000_000),
        "mcap_bad_definition.mcap": mcap_file(beams, definition=b"float32\n"),
        "mcap_big_endian.mcap": mcap_file([cdr_scan_line(0, 0.0, [1, 2], encapsulation=b"\x00\x00\x00\x00")]),
    }, {"scan_small.mcap": small}


# ---- ROS 2 logs in rosbag2's SQLite storage (Humble: type names only) -------------------------------

def sonar_echo(seq, angle_rad, samples):
    """A ping360_sonar_msgs/msg/SonarEcho in plain little-endian CDR (range 2 m)."""
    out = struct.pack("<iI", 1000 + seq, 0) + struct.pack("<I", 6) + b"sonar\x00"
    out += b"\x00" * (-len(out) % 4) + struct.pack("<fBxHHHB", angle_rad, 1, len(samples), 750, 1500, 2)
    out += b"\x00" * (-len(out) % 4) + struct.pack("<I", len(samples)) + bytes(samples)
    return b"\x00\x01\x00\x00" + out


def rosbag2_db3(messages, type_name="ping360_sonar_msgs/msg/SonarEcho", tables=True):
    """The bytes of a rosbag2 SQLite database holding `messages` on one topic."""
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "bag_0.db3"
        db = sqlite3.connect(path)
        if tables:
            db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
                       "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)")
            db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
                       "timestamp INTEGER NOT NULL, data BLOB NOT NULL)")
            db.execute("INSERT INTO topics VALUES(1, '/sonar', ?, 'cdr', '')", (type_name,))
            db.executemany("INSERT INTO messages(topic_id, timestamp, data) VALUES(1, ?, ?)",
                           [((1000 + i) * 10**9, m) for i, m in enumerate(messages)])
        else:
            db.execute("CREATE TABLE notes(text TEXT)")
        db.commit()
        db.close()
        return path.read_bytes()


def rosbag2_files():
    beams = [sonar_echo(i, 0.05 * i, [0, 2, 9, 180, 120, 40]) for i in range(3)]
    small = rosbag2_db3(beams)
    return {
        "rosbag2_text.db3": b"this is not an SQLite database\n",
        "rosbag2_truncated.db3": small[:len(small) // 2],
        "rosbag2_no_tables.db3": rosbag2_db3([], tables=False),
        "rosbag2_unknown_type.db3": rosbag2_db3(beams, type_name="vendor_msgs/msg/Echo"),
        "rosbag2_messages_cut.db3": rosbag2_db3([b[:-3] for b in beams]),
    }, {"rosbag2_small.db3": small}


# ---- BlueROV2 logs: MAVLink telemetry (.tlog) and ArduPilot dataflash (.BIN) --------------------------

def mcrf4xx(data, crc=0xFFFF):
    """CRC-16/MCRF4XX, MAVLink's checksum (mavlink.io/en/guide/serialization.html)."""
    for byte in data:
        tmp = (byte ^ (crc & 0xFF)) & 0xFF
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def mavlink2(msgid, crc_extra, payload, seq=0, crc_delta=0, incompat_flags=0):
    payload = payload.rstrip(b"\0") or b"\0"
    body = bytes([len(payload), incompat_flags, 0, seq & 255, 1, 1]) + struct.pack("<I", msgid)[:3] + payload
    return b"\xfd" + body + struct.pack("<H", mcrf4xx(bytes([crc_extra]), mcrf4xx(body)) ^ crc_delta)


def tlog_fixes(count, crc_delta=0, incompat_flags=0):
    out = b""
    for i in range(count):
        stamp = struct.pack(">Q", 1723630500_000000 + 100000 * i)
        out += stamp + mavlink2(30, 39, struct.pack("<I6f", 100 * i, 0.01 * i, 0.0, 0.5, 0, 0, 0), i, crc_delta, incompat_flags)
        out += stamp + mavlink2(32, 185, struct.pack("<I6f", 100 * i, 0.1 * i, 0.0, 2.0, 0, 0, 0), i, crc_delta, incompat_flags)
    return out


def tlog_attitude_before_positions():
    """ATTITUDEs for 0.3 s, then LOCAL_POSITION_NED from 1 s: no attitude within the positions' span."""
    out = b""
    for i in range(4):
        out += struct.pack(">Q", 1723630500_000000 + 100000 * i)
        out += mavlink2(30, 39, struct.pack("<I6f", 100 * i, 0.0, 0.0, 0.5, 0, 0, 0), i)
    for i in range(2):
        out += struct.pack(">Q", 1723630501_000000 + 100000 * i)
        out += mavlink2(32, 185, struct.pack("<I6f", 1000 + 100 * i, 1.0, 0.0, 2.0, 0, 0, 0), 4 + i)
    return out


def dataflash_fmt(type_id, name, fmt, columns):
    sizes = {"B": 1, "b": 1, "h": 2, "H": 2, "c": 2, "C": 2, "i": 4, "I": 4, "f": 4, "Q": 8, "X": 1}
    length = 3 + sum(sizes[c] for c in fmt)
    return (b"\xa3\x95\x80" + bytes([type_id, length]) + name.ljust(4, b"\0") + fmt.encode().ljust(16, b"\0")
            + columns.ljust(64, b"\0"))


def dataflash_files():
    att = dataflash_fmt(129, b"ATT", "QccccCCCC", b"TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw,ErrRP,ErrYaw")
    ekf = dataflash_fmt(130, b"XKF1", "QBccCfffffff", b"TimeUS,C,Roll,Pitch,Yaw,VN,VE,VD,dPD,PN,PE,PD")
    records = b""
    for i in range(4):
        records += b"\xa3\x95\x81" + struct.pack("<Q4h4H", 1000000 + 100000 * i, 0, 100 * i, 0, -50, 0, 9000, 0, 0)
        records += b"\xa3\x95\x82" + struct.pack("<QB2hH7f", 1000000 + 100000 * i, 0, 0, 0, 0, 0, 0, 0, 0, 0.2 * i, 0.0, 3.0)
    small = att + ekf + records
    return {
        "tlog_text.tlog": b"this is not a MAVLink telemetry log\n",
        "tlog_no_attitude.tlog": struct.pack(">Q", 1723630500_000000) + mavlink2(0, 50, b"\0\0\0\0\x0c\x03\x51\x04\x03"),
        "tlog_cut_first_frame.tlog": tlog_fixes(1)[:20],
        "tlog_bad_checksums.tlog": tlog_fixes(3, crc_delta=0x5A5A),
        "tlog_unknown_incompat_flag.tlog": tlog_fixes(3, incompat_flags=0x02),
        "tlog_attitude_before_positions.tlog": tlog_attitude_before_positions(),
        "dataflash_text.BIN": b"this is not a dataflash log\n",
        "dataflash_no_att.BIN": att + ekf,
        "dataflash_cut_att.BIN": small[:len(att) + len(ekf) + 10],
        "dataflash_unknown_format.BIN": dataflash_fmt(129, b"ATT", "QccccCCCX", b"TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw,ErrRP,ErrYaw") + records[:24],
    }, {"tlog_small.tlog": tlog_fixes(4), "dataflash_small.BIN": small}
