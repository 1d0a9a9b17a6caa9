#!/usr/bin/env python3
"""Builds the broken-input corpus and the small valid seeds that test_corpus truncates and flips,
into a folder of the build tree: `python3 tests/corpus/make_corpus.py OUT` writes OUT/broken/ and
OUT/valid/. CMake runs it for test_corpus, and scripts/fuzz.sh for the fuzzers' hand-made seeds.

Python 3 standard library only. Every binary file is built here byte by byte (nothing is copied
from real data) and none is committed; the hand-written text files of the corpus (CSV, x y z,
scene, broken/MANIFEST.tsv) are kept in tests/corpus/broken and valid and copied beside them.

Layouts: ../shared/docs/formats.md and the readers' headers (MAT-file level 5: MathWorks'
"MAT-File Format" document; SeaNet V4LOG: include/sonarmap/formats/v4log_reader.hpp; SeaNet wire
packets: include/sonarmap/formats/seanet_capture.hpp; Ping360 ping-protocol messages and Ping Viewer
logs: include/sonarmap/formats/ping360_reader.hpp). The robots' logs (ROS 1 and 2, BlueROV2) are
corpus_robot_logs.py's.
"""

import gzip
import pathlib
import shutil
import struct
import sys
import zlib

from corpus_robot_logs import HUGE, dataflash_files, mcap_files, ros_bag_files, rosbag2_files

HERE = pathlib.Path(__file__).resolve().parent


# ---- MAT-file level 5 ----------------------------------------------------------------------------

MI_INT8, MI_UINT8, MI_INT32, MI_UINT32, MI_SINGLE, MI_DOUBLE, MI_MATRIX, MI_COMPRESSED = 1, 2, 5, 6, 7, 9, 14, 15
MX_STRUCT, MX_DOUBLE, MX_SINGLE, MX_INT16, MX_UINT8 = 2, 6, 7, 10, 9
FIELDS = ("time", "angle", "step_dist", "intensities")


def mat_header(version=0x0100, endian=b"IM"):
    text = b"MATLAB 5.0 MAT-file, Platform: sonarmap test corpus, Created on: 2024-01-01"
    return text.ljust(116, b" ") + b"\0" * 8 + struct.pack("<H", version) + endian


def element(mi_type, payload):
    """A data element: 8-byte tag, payload, zero padding to 8 bytes."""
    out = struct.pack("<II", mi_type, len(payload)) + payload
    return out + b"\0" * (-len(out) % 8)


def matrix(mx_class, dims, name, body):
    """An miMATRIX element: array flags, dimensions, name, then the class's own sub-elements."""
    content = element(MI_UINT32, struct.pack("<II", mx_class, 0))
    content += element(MI_INT32, struct.pack("<%di" % len(dims), *dims))
    content += element(MI_INT8, name.encode())
    content += body
    return struct.pack("<II", MI_MATRIX, len(content)) + content


def single(value, name=""):
    return matrix(MX_SINGLE, (1, 1), name, element(MI_SINGLE, struct.pack("<f", value)))


def uint8_vector(values, mx_class=MX_UINT8, dims=None):
    return matrix(mx_class, dims or (1, len(values)), "", element(MI_UINT8, bytes(values)))


def struct_array(name, fields, elements, dims=None):
    """A 1×N struct array; `elements` holds, per element, one miMATRIX per field."""
    names = b"".join(f.encode().ljust(32, b"\0") for f in fields)
    body = struct.pack("<HHi", MI_INT32, 4, 32) + element(MI_INT8, names)
    body += b"".join(b"".join(e) for e in elements)
    return matrix(MX_STRUCT, dims or (1, len(elements)), name, body)


def beam(time=10.0, angle=0.0, step=0.0125, bins=(0, 10, 200, 30)):
    return [single(time), single(angle), single(step), uint8_vector(bins)]


def cras_mat(beams, fields=FIELDS, dims=None, name="parsedData"):
    return mat_header() + struct_array(name, fields, beams, dims)


def compressed(mat_bytes):
    """The same file with its one variable stored as an miCOMPRESSED (zlib) element."""
    packed = zlib.compress(mat_bytes[128:])
    return mat_bytes[:128] + struct.pack("<II", MI_COMPRESSED, len(packed)) + packed  # not padded


def valid_beams():
    return [beam(10.0 + 0.05 * i, 1.8 * i, bins=(i, 10, 200, 30)) for i in range(3)]


def mat_files():
    good = cras_mat(valid_beams())
    flipped_class = bytearray(good)
    flipped_class[128 + 16] = 0x01  # parsedData's array flags: struct (2) → cell (1)
    huge_intensities = beam()
    huge_intensities[3] = matrix(MX_UINT8, (1, HUGE), "", element(MI_UINT8, bytes(4)))
    return {
        "mat_empty.mat": b"",
        "mat_text.mat": b"time,angle,step_dist\n10,0,0.0125\n" * 8,
        "mat_wrong_endian.mat": mat_header(endian=b"XY") + good[128:],
        "mat_header_only.mat": mat_header(),
        "mat_truncated.mat": good[: len(good) // 2],
        "mat_huge_struct.mat": cras_mat(valid_beams()[:1], dims=(1, HUGE)),
        "mat_huge_intensities.mat": cras_mat([huge_intensities]),
        "mat_wrong_variable.mat": cras_mat(valid_beams(), name="otherData"),
        "mat_not_struct.mat": mat_header() + single(1.0, "parsedData"),
        "mat_class_flipped.mat": bytes(flipped_class),
        "mat_missing_field.mat": cras_mat([b[:2] + b[3:] for b in valid_beams()], fields=("time", "angle", "intensities")),
        "mat_empty_struct.mat": cras_mat([], dims=(1, 0)),
        "mat_nan_angle.mat": cras_mat([beam(angle=float("nan")), beam(11.0, angle=float("nan"))]),
        "mat_inf_time.mat": cras_mat([beam(time=float("inf"))]),
        "mat_zero_step.mat": cras_mat([beam(step=0.0), beam(11.0, step=0.0)]),
        "mat_negative_step.mat": cras_mat([beam(step=-0.0125)]),
        "mat_wrong_type.mat": cras_mat([beam()[:3] + [matrix(MX_INT16, (1, 2), "", element(MI_UINT8, bytes(4)))]]),
        "mat_time_backwards.mat": cras_mat([beam(10.0), beam(10.1), beam(9.0)]),
        # cut short in the last element (a full disk): the elements before it are read
        "mat_cut_in_last_element.mat": good[:-20],
        "mat_compressed_cut_in_stream.mat": compressed(good)[:-15],
    }, {"cras_small.mat": good, "cras_small_compressed.mat": compressed(good)}


# ---- SeaNet V4LOG --------------------------------------------------------------------------------

V4_MAGIC = b"SeaNetV4 Log File V1"
OLE_DATE = 38494.620369097225  # days since 1899-12-30


def v4_header(record_count, data_offset=80, magic=V4_MAGIC):
    head = magic.ljust(32, b"\0") + struct.pack("<IIII", 16, 0, data_offset, record_count)
    return head + b"\0" * 16 + struct.pack("<dd", OLE_DATE, OLE_DATE)


def head_data(date=OLE_DATE, ad_interval=33, bearing=3200, data=b"\x0a\x14\x1e\x28", data_count=None, length=None):
    message = struct.pack("<BBBBBHBBBHHIBHBBHHHHBHH", 2, 255, 2, 0x80, 2, 0, 11, 0x11, 0, 0x230D, 100, 0, 60, 125,
                          80, 0, 0, ad_interval, 2400, 4000, 16, bearing,
                          len(data) if data_count is None else data_count)
    body = struct.pack("<d", date) + message + data
    return struct.pack("<H", length if length is not None else 2 + len(body)) + body


def other_record(date=OLE_DATE, message_type=4):
    body = struct.pack("<dBBB", date, 2, 255, message_type)
    return struct.pack("<H", 2 + len(body)) + body


def v4log(records, **header):
    return v4_header(len(records), **header) + b"".join(records)


def v4_files():
    step = 0.5 / 86400.0
    good = v4log([head_data(OLE_DATE + i * step, bearing=3200 + 16 * i) for i in range(3)])
    return {
        "v4_empty.V4LOG": b"",
        "v4_wrong_magic.V4LOG": v4log([head_data()], magic=b"SeaNetV3 Log File V1"),
        "v4_truncated_header.V4LOG": good[:50],
        "v4_huge_record_count.V4LOG": v4_header(HUGE) + head_data(),
        "v4_data_offset_outside.V4LOG": v4log([head_data()], data_offset=100_000),
        "v4_zero_adinterval.V4LOG": v4log([head_data(ad_interval=0)]),
        "v4_nan_date.V4LOG": v4log([head_data(date=float("nan"))]),
        "v4_bearing_out_of_range.V4LOG": v4log([head_data(bearing=6400)]),
        "v4_record_past_end.V4LOG": v4log([head_data(), head_data(length=60000)]),
        "v4_record_too_short.V4LOG": v4log([head_data(length=4)]),
        "v4_data_count_too_big.V4LOG": v4log([head_data(data_count=5000)]),
        "v4_time_backwards.V4LOG": v4log([head_data(OLE_DATE), head_data(OLE_DATE - step)]),
        "v4_no_beams.V4LOG": v4log([other_record(), head_data(data=b"")]),
        "v4_zero_records.V4LOG": v4log([]),
        # a log cut short (a full disk): read up to the cut, or refused when no record is whole
        "v4_cut_in_last_record.V4LOG": good[:-20],
        "v4_cut_in_first_record.V4LOG": good[:100],
    }, {"seanet_small.V4LOG": good}


# ---- SeaNet wire capture -------------------------------------------------------------------------


def seanet_frame(message):
    """'@', the length as 4 hex digits and as uint16 (it counts itself and the message), message, LF."""
    length = len(message) + 2
    return b"@" + b"%04X" % length + struct.pack("<H", length) + message + b"\n"


def seanet_head(ad_interval=33, bearing=3200, data=b"\x0a\x14\x1e\x28", head_control=0x230D):
    """An imaging head's mtHeadData packet: source, destination, byte count, type 2, sequence, node, fields, data."""
    message = struct.pack("<BBBBBBHBBBHHIBHBBHHHHBHH", 2, 255, 0, 2, 0x80, 2, len(data) + 31, 11, 0x10, 0,
                          head_control, 100, 0, 60, 125, 80, 0, 0, ad_interval, 2400, 4000, 16, bearing, len(data))
    return seanet_frame(message + data)


def seanet_alive():
    return seanet_frame(struct.pack("<BBBBBB", 2, 255, 11, 4, 0x80, 2) + b"\x07" * 8)


def seanet_files():
    good = b"\r\n" + seanet_head() + seanet_alive() + seanet_head(bearing=3216, head_control=0x230C) + b"noise"
    no_lf = bytearray(seanet_head())
    no_lf[-1] = 0x0D
    lengths_differ = bytearray(seanet_head())
    lengths_differ[5] += 1
    return {
        "seanet_empty.seanet": b"",
        "seanet_text.seanet": b"time,angle\n1,2\n",
        "seanet_only_alive.seanet": seanet_alive() * 3,
        "seanet_zero_adinterval.seanet": seanet_head(ad_interval=0),
        "seanet_bearing_out_of_range.seanet": seanet_head(bearing=6400),
        "seanet_cut_short.seanet": seanet_head()[:30],
        "seanet_no_lf.seanet": bytes(no_lf),
        "seanet_lengths_differ.seanet": bytes(lengths_differ),
        # The host's side of a conversation (mtReBoot, mtSendVersion, mtSendData as the drivers send
        # them: seanet_protocol.hpp), no beam in it.
        "seanet_host_commands.seanet": seanet_frame(struct.pack("<BBBBBB", 255, 2, 3, 16, 0x80, 2))
        + seanet_frame(struct.pack("<BBBBBB", 255, 2, 3, 23, 0x80, 2))
        + seanet_frame(struct.pack("<BBBBBBI", 255, 2, 7, 25, 0x80, 2, 45296000)),
        # Consistent lengths, but 7: shorter than the smallest packet (header and LF, 14 bytes).
        "seanet_length_too_small.seanet": b"@0007\x07\x00\xff\x02\x03\x10\x80\n",
    }, {"seanet_small.seanet": good}


# ---- Ping360 ping-protocol and Ping Viewer logs ---------------------------------------------------


def ping_message(message_id, payload, checksum_delta=0):
    """'B' 'R', payload length, id, source 2, destination 0, payload, checksum (byte sum mod 65536)."""
    out = b"BR" + struct.pack("<HHBB", len(payload), message_id, 2, 0) + payload
    return out + struct.pack("<H", (sum(out) + checksum_delta) & 0xFFFF)


def ping360_data(angle=0, sample_period=80, data=b"\x01\x02\xfa", auto=False, gain=0):
    """device_data (2300) or auto_device_data (2301, with its sector fields)."""
    payload = struct.pack("<BBHHHH", 1, gain, angle, 32, sample_period, 750)
    if auto:
        payload += struct.pack("<HHBB", 0, 399, 1, 0)
    payload += struct.pack("<HH", len(data), len(data)) + data
    return ping_message(2301 if auto else 2300, payload)


def qt_string(text, utf16=False):
    """A QDataStream QString as Ping Viewer logs hold it: big-endian byte length, UTF-8 or UTF-16BE."""
    data = text.encode("utf-16-be" if utf16 else "utf-8")
    return struct.pack(">I", len(data)) + data


def viewer_header(version=1, utf16=False):
    out = qt_string("PingViewer sensor log file", utf16) + struct.pack(">i", version)
    out += b"".join(qt_string(t, utf16) for t in ("1ed4508", "2025-08-07", "v2.4.1", "Debian GNU/Linux 12", "12"))
    return out + struct.pack(">ii", 1, 2)


def viewer_log(records, utf16=False, **header):
    return viewer_header(utf16=utf16, **header) + b"".join(
        qt_string(time, utf16) + struct.pack(">I", len(data)) + data for time, data in records)


# What real Ping Viewer logs do (../shared/data/README.md), each in a small file of its own, made
# here from the protocol, never copied from a shared log.

def locale_digits(text, zero="\u06f0"):
    """`text` with its ASCII digits written in another locale's digits (default: Persian, U+06F0...)."""
    return "".join(chr(ord(zero) + ord(c) - ord("0")) if c.isdigit() else c for c in text)


def device_information():
    """device_information (common message 4): a Ping360 (type 2), revision 1, firmware 3.1.1."""
    return ping_message(4, bytes([2, 1, 3, 1, 1, 0]))


def chunks(stream, sizes):
    """`stream` cut into pieces of `sizes` bytes (the rest in a last piece), as serial reads cut it."""
    out, at = [], 0
    for size in sizes:
        out.append(stream[at:at + size])
        at += size
    return out + ([stream[at:]] if at < len(stream) else [])


def viewer_records(pieces, start_ms=100, step_ms=50, zero="0"):
    """One record a piece, the time stamps `step_ms` apart in `zero`'s digits."""
    return [(locale_digits("00:00:%02d.%03d" % divmod(start_ms + i * step_ms, 1000), zero), piece)
            for i, piece in enumerate(pieces)]


def real_viewer_files():
    """The real files' behaviours: (broken, valid) as every maker here returns."""
    pings = b"".join(ping360_data(angle=a) for a in range(4))
    # power-on pings at the 2 m default (sample period 88 ticks: 1.65 mm samples), then the user's
    # range (sample period 440: 8.25 mm), then the gain changed from low (0) to normal (1)
    power_on = b"".join(ping360_data(angle=a, sample_period=88) for a in range(3))
    user_range = b"".join(ping360_data(angle=a, sample_period=440) for a in range(3, 6))
    new_gain = b"".join(ping360_data(angle=a, sample_period=440, gain=1) for a in range(6, 9))
    settings = device_information() + power_on + user_range + new_gain
    one = ping360_data()
    return {
        # Persian-digit times around records that hold no ping at all
        "viewer_locale_digits_no_ping.bin": viewer_log(viewer_records([device_information()] * 2, zero="\u06f0"), utf16=True),
        # a message split over records whose last piece never came
        "viewer_chunked_cut_short.bin": viewer_log(viewer_records(chunks(one, [9, 9])[:2])),
        # a log cut short in its last record's data (a pulled cable): the messages before it are read
        "viewer_cut_in_record.bin": viewer_log(viewer_records([pings[:40], pings[40:]]))[:-10],
        # the power-on 2 m pings in Persian digits, all with a sample period of 0 (no range at all)
        "viewer_power_on_zero_period.bin": viewer_log(viewer_records(
            [device_information(), b"".join(ping360_data(angle=a, sample_period=0) for a in range(3))],
            zero="\u06f0"), utf16=True),
    }, {
        # Windows' UTF-16 time stamps in Persian digits
        "viewer_locale_digits.bin": viewer_log(viewer_records([pings[:40], pings[40:]], zero="\u06f0"), utf16=True),
        # serial chunks: one message over three records, then three messages and a half in one record
        "viewer_chunked.bin": viewer_log(viewer_records(chunks(pings, [7, 11, 9, 3 * len(one) + 4]))),
        # device_information, power-on 2 m pings, a range change and a gain change
        "viewer_range_changes.bin": viewer_log(viewer_records(chunks(settings, [len(settings) // 3] * 2))),
    }


def ping360_files():
    stream = ping360_data() + ping_message(1, b"\xb0\x04") + ping360_data(angle=17, auto=True)
    return {
        "ping_empty.bin": b"",
        "ping_text.bin": b"time,angle\n1,2\n",
        "ping_bad_checksum.bin": ping360_data()[:-2] + b"\x00\x00",
        "ping_only_ack.bin": ping_message(1, b"\xb0\x04") * 2,
        "ping_angle_out_of_range.bin": ping360_data(angle=400),
        "ping_zero_sample_period.bin": ping360_data(sample_period=0),
        "ping_cut_short.bin": ping360_data()[:20],
        # the host's side of the link recorded: general_request and transducer commands, no pings
        "ping_host_commands.bin": ping_message(6, struct.pack("<H", 4)) + ping_message(
            2601, struct.pack("<BBHHHHHBB", 1, 1, 0, 107, 888, 750, 1200, 1, 0)),
        "ping_data_length_short.bin": ping_message(
            2300, struct.pack("<BBHHHHHH", 1, 0, 0, 32, 80, 750, 3, 3) + b"\x01\x02"),
        "ping_auto_payload_short.bin": ping_message(2301, struct.pack("<BBHHHH", 1, 0, 0, 32, 80, 750)),
        "ping_declares_too_long.bin": b"BR\xff\xff\xfc\x08\x02\x00" + bytes(40),
        "ping_device_information_short.bin": ping_message(4, bytes([2, 1, 3, 1, 1])),
        "viewer_wrong_version.bin": viewer_log([("00:00:00.100", stream)], version=2),
        "viewer_truncated_header.bin": viewer_header()[:40],
        "viewer_no_messages.bin": viewer_log([("00:00:00.100", b"")]),
        "viewer_time_too_long.bin": viewer_log([("0" * 65, stream)]),
    }, {"ping_small.bin": b"xx" + stream,
        "viewer_small.bin": viewer_log([("00:00:00.100", stream[:20]), ("00:00:00.150", stream[20:])]),
        "viewer_small_utf16.bin": viewer_log([("00:00:00.100", stream)], utf16=True)}


# ---- OctoMap scan graph --------------------------------------------------------------------------


def vec(x, y, z, marker=3):
    return struct.pack("<iddd", marker, x, y, z)


def pose(t=(1.0, 0.0, -0.5), q=(1.0, 0.0, 0.0, 0.0)):
    return vec(*t) + struct.pack("<idddd", 4, *q)


def node(points, node_id=0, node_pose=None):
    return struct.pack("<I", len(points)) + b"".join(points) + (node_pose or pose()) + struct.pack("<I", node_id)


def graph(nodes, edges=b"", edge_count=0):
    return struct.pack("<I", len(nodes)) + b"".join(nodes) + struct.pack("<I", edge_count) + edges


def graph_files():
    points = [vec(1.0, 0.0, 0.0), vec(0.0, 1.0, 0.5), vec(-1.0, -0.5, 0.25)]
    good = graph([node(points, 0), node(points[:2], 1, pose((2.0, 0.0, 0.0)))],
                 struct.pack("<II", 0, 1) + pose() + struct.pack("<d", 1.0), 1)
    return {
        "graph_empty.graph": b"",
        "graph_text.graph": b"1.0 2.0 3.0\n4.0 5.0 6.0\n",
        "graph_huge_node_count.graph": struct.pack("<I", HUGE) + node(points),
        "graph_huge_point_count.graph": struct.pack("<II", 1, HUGE) + b"".join(points),
        "graph_nan_point.graph": graph([node([vec(1.0, float("nan"), 0.0)])]),
        "graph_bad_marker.graph": graph([node([vec(1.0, 2.0, 3.0, marker=7)])]),
        "graph_zero_quaternion.graph": graph([node(points, node_pose=pose(q=(0.0, 0.0, 0.0, 0.0)))]),
        "graph_inf_translation.graph": graph([node(points, node_pose=pose(t=(float("inf"), 0.0, 0.0)))]),
        "graph_bad_edge.graph": graph([node(points)], struct.pack("<II", 0, 7) + pose() + struct.pack("<d", 1.0), 1),
        "graph_trailing_bytes.graph": graph([node(points)]) + b"junk",
        "graph_truncated.graph": good[: len(good) - 40],
    }, {"scan_small.graph": good}


# ---- OctoMap .bt and .ot -------------------------------------------------------------------------


def octomap_header(first_line, size, res="0.1", tree_id="OcTree", extra=""):
    return (f"{first_line}\n# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
            f"id {tree_id}\nsize {size}\nres {res}\n{extra}data\n").encode()


BT = "# Octomap OcTree binary file"
OT = "# Octomap OcTree file"
# Root: child 0 inner (its 8 children occupied leaves), child 1 occupied, child 2 free: 12 nodes.
BT_DATA = bytes([0x1B, 0x00, 0xAA, 0xAA])


def ot_records(records):
    return b"".join(struct.pack("<fB", log_odds, bits) for log_odds, bits in records)


OT_TREE = [(3.5, 0x07), (3.5, 0xFF)] + [(3.5, 0)] * 8 + [(3.5, 0), (-2.0, 0)]


def bt_files():
    deep = bytes([0x03, 0x00]) * 17  # child 0 inner at every level, below the finest one
    return {
        "bt_empty.bt": b"",
        "bt_wrong_magic.bt": octomap_header("# Octomap OcTree file", 12) + BT_DATA,
        "bt_no_data_line.bt": octomap_header(BT, 12)[:-5],
        "bt_unknown_line.bt": octomap_header(BT, 12, extra="colour red\n") + BT_DATA,
        "bt_wrong_id.bt": octomap_header(BT, 12, tree_id="ColorOcTree") + BT_DATA,
        "bt_zero_res.bt": octomap_header(BT, 12, res="0") + BT_DATA,
        "bt_negative_res.bt": octomap_header(BT, 12, res="-0.1") + BT_DATA,
        "bt_nan_res.bt": octomap_header(BT, 12, res="nan") + BT_DATA,
        "bt_res_not_number.bt": octomap_header(BT, 12, res="fine") + BT_DATA,
        "bt_negative_size.bt": octomap_header(BT, -12) + BT_DATA,
        "bt_huge_size.bt": octomap_header(BT, HUGE) + BT_DATA,
        "bt_size_mismatch.bt": octomap_header(BT, 14) + BT_DATA,
        "bt_truncated_data.bt": octomap_header(BT, 12) + BT_DATA[:3],
        "bt_too_deep.bt": octomap_header(BT, 18) + deep,
    }, {"tree_small.bt": octomap_header(BT, 12) + BT_DATA}


def ot_files():
    return {
        "ot_empty.ot": b"",
        "ot_wrong_magic.ot": octomap_header(BT, 12) + ot_records(OT_TREE),
        "ot_zero_res.ot": octomap_header(OT, 12, res="0") + ot_records(OT_TREE),
        "ot_inf_res.ot": octomap_header(OT, 12, res="1e999") + ot_records(OT_TREE),
        "ot_huge_size.ot": octomap_header(OT, HUGE) + ot_records(OT_TREE),
        "ot_nan_log_odds.ot": octomap_header(OT, 12) + ot_records([(float("nan"), 0x07)] + OT_TREE[1:]),
        "ot_tree_ends_early.ot": octomap_header(OT, 13) + ot_records(OT_TREE + [(0.0, 0)]),
        "ot_tree_continues.ot": octomap_header(OT, 11) + ot_records(OT_TREE),
        "ot_truncated.ot": octomap_header(OT, 12) + ot_records(OT_TREE)[:33],
        "ot_too_deep.ot": octomap_header(OT, 18) + ot_records([(0.0, 0x01)] * 17 + [(0.0, 0)]),
    }, {"tree_small.ot": octomap_header(OT, 12) + ot_records(OT_TREE)}


# ---- gzip-compressed CSV (`.csv.gz`: include/sonarmap/io/text_input.hpp) ---------------------------

def gzip_files():
    scans = (HERE / "valid" / "scans_small.csv").read_bytes()
    nav = (HERE / "valid" / "nav_small.csv").read_bytes()
    beams = (HERE / "valid" / "beams_small.csv").read_bytes()
    packed = gzip.compress(scans, mtime=0)
    corrupt = bytearray(packed)
    corrupt[12] ^= 0xFF  # inside the deflate data, past the 10-byte gzip header
    corrupt[13] ^= 0xFF
    return {
        "scans_truncated.csv.gz": packed[:len(packed) // 2],
        "scans_not_gzip.csv.gz": scans,
        "scans_corrupt.csv.gz": bytes(corrupt),
        "scans_wrong_header.csv.gz": gzip.compress(scans.replace(b"time_s", b"t", 1), mtime=0),
        "nav_truncated.csv.gz": gzip.compress(nav, mtime=0)[:-12],
        "beams_truncated.csv.gz": gzip.compress(beams, mtime=0)[:-6],
    }, {
        "scans_small.csv.gz": packed,
        # two gzip members one after the other read as one text, as gzip(1) reads them
        "scans_two_members.csv.gz": gzip.compress(scans[:60], mtime=0) + gzip.compress(scans[60:], mtime=0),
        "nav_small.csv.gz": gzip.compress(nav, mtime=0),
        "beams_small.csv.gz": gzip.compress(beams, mtime=0),
    }


# ---- text readers fed bytes that are not text ------------------------------------------------------

def binary_text_files():
    return {
        "beams_binary.csv": b"\x00\x01\x02\xff\xfe,\x80\x81\n\x10\x11,\x12\n",
        "points_binary.xyz": b"\x00\x01\x02\xff\xfe \x80\x81 \x7f\n",
        "scene_binary.txt": b"\x00\x01plane\xff 1 2\n",
    }, {}


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_corpus.py OUT  (writes OUT/broken and OUT/valid)")
    out = pathlib.Path(sys.argv[1])
    for kind in ("broken", "valid"):
        folder = out / kind
        folder.mkdir(parents=True, exist_ok=True)
        for text in (HERE / kind).iterdir():  # the hand-written files, copied as they are
            shutil.copyfile(text, folder / text.name)
    for make in (mat_files, v4_files, seanet_files, ping360_files, real_viewer_files, graph_files, bt_files,
                 ot_files, ros_bag_files, mcap_files, rosbag2_files, dataflash_files, gzip_files, binary_text_files):
        for kind, files in zip(("broken", "valid"), make()):
            for name, data in files.items():
                (out / kind / name).write_bytes(data)


if __name__ == "__main__":
    main()
