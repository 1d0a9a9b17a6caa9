#pragma once
/// @file ros_bag_check.hpp
/// Private to formats: a ROS 1 bag's records checked against its file before rosbag_storage reads
/// it. rosbag_storage trusts what the file says: it allocates what a record header declares (a
/// header length of 2³² − 1 bytes is a 4 GiB allocation), reads a header field's length without
/// checking it against its header, and reads a message at whatever offset of its chunk an index
/// entry gives. So a broken file would exhaust memory or read out of bounds instead of failing.
/// Layout: the ROS wiki's "Bags/Format/2.0" (a version line "#ROSBAG V2.0", then records of a
/// uint32 header length, the header's fields as a uint32 length and NAME=VALUE each, a uint32 data
/// length and the data).

#include <string>

namespace sonarmap::detail {

/// Largest uncompressed chunk accepted, bytes: rosbag writes chunks of 768 KiB by default
/// (`rosbag record --chunksize`), and a chunk is held in memory whole.
inline constexpr unsigned long long kMaxBagChunk = 256ull << 20;

/// Walks the bag at `path` record by record, and the records inside every chunk (decompressed,
/// bz2 or lz4, as rosbag_storage will): every header field, header and data must fit in what
/// holds it; the bag header's index position must be where a record starts, a chunk info's chunk
/// position where a chunk starts, and every index entry's offset where a record of its chunk
/// starts; every connection an index or chunk info names must be defined; a chunk's declared
/// uncompressed size must not exceed kMaxBagChunk. A compressed chunk is decompressed twice (here
/// and when read); an uncompressed bag is read twice.
/// @throws FileError naming the file, the record's byte offset and what does not fit; also for a
///   version other than 2.0 and an unknown compression.
void checkBagRecords(const std::string& path);

}  // namespace sonarmap::detail
