#pragma once
/// @file dataflash_log.hpp
/// Private to src/formats: the records of an ArduPilot dataflash log (`.BIN`), each read by the FMT
/// record that defines its type (ArduPilot's libraries/AP_Logger/LogStructure.h, pymavlink's
/// DFReader.py). Every record is 0xA3 0x95, a type byte, then the fields its format string lists,
/// packed, little-endian; FMT (type 128, 89 bytes) defines a type: Type (B), Length (B, the whole
/// record's bytes), Name (n), Format (N), Columns (Z, comma-separated).

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sonarmap::detail {

/// A message type as its FMT record defines it, with each column's byte offset in the record.
struct DataflashFormat {
  std::uint8_t type = 0;
  std::size_t length = 0;  ///< bytes of a record, its 3-byte header included
  std::string name;
  std::string format;  ///< one format character per column
  std::vector<std::string> columns;
  std::vector<std::size_t> offsets;  ///< of each column, from the record's first byte
};

/// One record, read through its format.
class DataflashRecord {
 public:
  DataflashRecord(const DataflashFormat& format, const std::uint8_t* record) : format_(format), record_(record) {}
  const DataflashFormat& format() const { return format_; }
  /// The column `name`'s number, scaled as its format character says (c, C, e, E: ÷ 100; L:
  /// ÷ 1e7 degrees); nullopt when the type has no such column or it holds text or an array.
  std::optional<double> value(std::string_view name) const;

 private:
  const DataflashFormat& format_;
  const std::uint8_t* record_;
};

/// What scanning a log found besides its records.
struct DataflashScan {
  std::size_t records = 0;        ///< records visited, FMT records included
  std::size_t skipped_bytes = 0;  ///< bytes between records (skipped to the next header)
  std::size_t refused_formats = 0;  ///< FMT records whose format string is unknown or disagrees with its length
  std::string stop_note;          ///< where a record cut short ended the log; empty if none
};

/// Calls `visit` with each record of a known type, in file order. Bytes that do not start a record
/// of a defined type are skipped one at a time to the next that does, and counted. A record cut
/// short by the end of the bytes ends the scan with `stop_note` naming the record and its byte.
/// @throws FileError naming `source` when the bytes do not start with a FMT record.
DataflashScan scanDataflash(std::span<const std::uint8_t> bytes, const std::string& source,
                            const std::function<void(const DataflashRecord&)>& visit);

}  // namespace sonarmap::detail
