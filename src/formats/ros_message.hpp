#pragma once
/// @file ros_message.hpp
/// Private to formats: ROS messages read from the definitions a log stores with each topic (a ROS 1
/// bag's connection `message_definition`, an MCAP file's `ros2msg` schema), so that a driver's own
/// message needs no compiled package. Sources: the ROS msg format (wiki.ros.org/msg: field and
/// constant lines, `Header` as std_msgs/Header, a type without a package taken from the message's
/// own package; ROS 2's adds `pkg/msg/Name`, bounded strings and sequences and default values:
/// design.ros2.org/articles/legacy_interface_definition.html); the ROS 1 serialization
/// (wiki.ros.org/roscpp/Overview/MessagesSerializationAndAdaptingTypes: little-endian, no padding,
/// a string or a variable-length array as a uint32 count and its elements, a fixed-length array as
/// its elements alone, time and duration as two 32-bit integers); ROS 2's CDR (OMG CDR as DDS-XTYPES
/// 1.3 section 7.4.3 lays it out: a 4-byte encapsulation header, each number aligned to its size,
/// strings counting their terminating NUL).

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace sonarmap::detail {

/// A ROS time (seconds and nanoseconds since the epoch, as a message stores them) in seconds: the
/// one conversion the readers use, so a writer that stamps a time can say what comes back.
inline double rosStampSeconds(double seconds, double nanoseconds) { return seconds + 1e-9 * nanoseconds; }

/// What a field's elements are, resolved once when the schema is parsed (not per message).
enum class RosKind : std::uint8_t {
  kBool, kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kInt64, kUint64, kFloat32, kFloat64,
  kString, kTime, kDuration, kMessage
};

/// One field of a message type.
struct RosField {
  std::string name;
  std::string type;   ///< a builtin ("float32", "time", …) or a full message name ("std_msgs/Header")
  int array = -1;     ///< −1: not an array; 0: variable length; > 0: fixed length
  RosKind kind = RosKind::kMessage;  ///< set by RosSchema from `type`
  std::size_t message = 0;           ///< kMessage: the type's index in its schema (RosSchema::fieldsAt)
};

/// How a log serializes its messages: ROS 1's, or CDR (ROS 2).
enum class RosEncoding { kRos1, kCdr };

/// The message types of one connection: its top type and every type it uses.
class RosSchema {
 public:
  /// Parses `definition` (the connection's message_definition) of the message type `type`
  /// ("pkg/Name"): its first section defines `type`, each "MSG: pkg/Name" section after a line of
  /// '=' another; comments (#) and constants (TYPE NAME=VALUE) are dropped.
  /// @throws Error (core/errors.hpp) naming the line for a field that does not parse, or a field
  ///         whose message type the definition does not define.
  /// With kCdr, ROS 2 names are read as ROS 1 ones ("pkg/msg/Name" as "pkg/Name",
  /// builtin_interfaces/Time as time), bounds dropped and default values ignored.
  RosSchema(const std::string& type, const std::string& definition, RosEncoding encoding = RosEncoding::kRos1);

  const std::string& root() const { return root_; }
  RosEncoding encoding() const { return encoding_; }
  /// The fields of message type `type`, in order.
  /// @throws Error when the schema does not define it.
  const std::vector<RosField>& fields(const std::string& type) const;
  /// The fields of the message type of index `index` (RosField::message; 0 is the root type).
  const std::vector<RosField>& fieldsAt(std::size_t index) const { return types_[index]; }
  /// Whether every field of the message type of index `index` is a single number (an array of it
  /// decodes as a RosTable).
  bool isTable(std::size_t index) const { return tables_[index]; }
  /// Whether `type` is a builtin type (numbers, bool, byte, char, string, time, duration).
  static bool isBuiltin(const std::string& type);
  /// The type reached from the top type along the fields `path` (none of them arrays), or empty
  /// when a step is missing.
  std::string typeAt(const std::vector<std::string>& path) const;
  /// Whether the message at `path` holds every field of `names` as a number (not an array).
  bool holdsNumbers(const std::vector<std::string>& path, std::initializer_list<const char*> names) const;

 private:
  std::string root_;
  RosEncoding encoding_ = RosEncoding::kRos1;
  /// The message types: names_[i] has the fields types_[i]; index 0 is the root.
  std::vector<std::string> names_;
  std::vector<std::vector<RosField>> types_;
  std::vector<bool> tables_;
};

struct RosValue;
/// A message or a nested message: its fields (the schema's: valid while the schema that decoded
/// it lives) and their values, in the same order.
struct RosStruct {
  const std::vector<RosField>* fields = nullptr;
  std::vector<RosValue> values;
};

/// An array of a message type whose fields are all single numbers (RosSchema::isTable: a sonar's
/// IntensityBin[] of a distance and an intensity), decoded as one table of numbers, row by row,
/// instead of one value per element.
struct RosTable {
  const std::vector<RosField>* fields = nullptr;  ///< the element type's (valid while its schema lives)
  std::vector<double> values;                     ///< rows × columns, row-major
  std::size_t columns() const { return fields->size(); }
  std::size_t rows() const { return fields->empty() ? 0 : values.size() / fields->size(); }
  /// The column of field `name`, or columns() when the element type has none.
  std::size_t column(const std::string& name) const;
};

/// A decoded value: a number (every numeric builtin and bool; time and duration in seconds), a
/// string, the bytes of a uint8, int8, byte or char array (kept as bytes: a sonar's intensities),
/// an array of messages of numbers as a table, an array of other values, or a nested message.
struct RosValue {
  std::variant<double, std::string, std::vector<std::uint8_t>, std::vector<RosValue>, RosStruct, RosTable> value;

  /// The field `name` of a nested message, nullptr when this is no message or has no such field.
  const RosValue* field(const std::string& name) const;
};

/// The decoded value reached along the fields `path` (as RosSchema::typeAt found them).
const RosValue& valueAt(const RosValue& message, const std::vector<std::string>& path);

/// The number `value` holds. @throws Error("its WHAT is not a finite number") for none, a NaN or
/// an infinity.
double finiteNumber(const RosValue* value, const std::string& what);

/// Decodes one serialized message of the schema's root type, in the schema's encoding.
/// @throws Error naming the field when the bytes end before the message does, or when bytes remain
///         after it.
RosValue decodeRosMessage(const RosSchema& schema, std::span<const std::uint8_t> bytes);

}  // namespace sonarmap::detail
