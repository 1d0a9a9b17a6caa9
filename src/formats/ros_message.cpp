/// @file ros_message.cpp
/// ROS message definitions and their serialized messages, ROS 1 and CDR (see ros_message.hpp).

#include "ros_message.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

/// Deepest nesting of messages decoded: a definition whose type holds itself would never end.
constexpr int kMaxDepth = 32;

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") + 1 - first);
}

/// `type` as a full name: builtins as they are, "Header" as std_msgs/Header, a name without a
/// package in the package of the message that uses it.
std::string fullName(const std::string& type, const std::string& package) {
  if (RosSchema::isBuiltin(type) || type.find('/') != std::string::npos) return type;
  if (type == "Header") return "std_msgs/Header";
  return package.empty() ? type : package + "/" + type;
}

std::string packageOf(const std::string& type) {
  const auto slash = type.find('/');
  return slash == std::string::npos ? std::string() : type.substr(0, slash);
}

/// A ROS 2 type name as a ROS 1 one: "pkg/msg/Name" is "pkg/Name"; builtin_interfaces' Time and
/// Duration are the builtins time and duration (the same two 32-bit integers); a bounded string
/// "string<=N" is a string and a bounded sequence "T[<=N]" a sequence (rosidl's interface
/// definition: design.ros2.org/articles/legacy_interface_definition.html).
std::string ros2Name(const std::string& type) {
  const auto open = type.find('[');
  std::string base = type.substr(0, open);
  std::string suffix = open == std::string::npos ? std::string() : type.substr(open);
  if (suffix.rfind("[<=", 0) == 0) suffix = "[]";
  base = base.substr(0, base.find("<="));
  if (const auto msg = base.find("/msg/"); msg != std::string::npos) base.erase(msg, 4);
  if (base == "builtin_interfaces/Time") base = "time";
  if (base == "builtin_interfaces/Duration") base = "duration";
  return base + suffix;
}

/// Parses one field line ("float32[] ranges", "uint8[16] id"; ROS 2: a default value may follow
/// the name); false for a constant.
bool parseField(const std::string& line, const std::string& package, RosEncoding encoding, RosField& field) {
  std::istringstream words(line);
  std::string type, name;
  if (!(words >> type >> name)) throw Error("the message definition line '" + line + "' is not TYPE NAME");
  // A constant ("int32 X=1", "int32 X = 1") is not in the serialized message; a ROS 2 default
  // value ("int32 x 5", "string s \"a=b\"") is.
  const auto after_name = line.find(name, line.find(type) + type.size()) + name.size();
  const auto next = line.find_first_not_of(" \t", after_name);
  if (name.find('=') != std::string::npos || (next != std::string::npos && line[next] == '=')) return false;
  if (encoding == RosEncoding::kCdr) type = ros2Name(type);
  field.array = -1;
  if (const auto open = type.find('['); open != std::string::npos) {
    const auto close = type.find(']', open);
    if (close != type.size() - 1) throw Error("the message definition line '" + line + "' has a malformed array type");
    const std::string length = type.substr(open + 1, close - open - 1);
    field.array = 0;
    if (!length.empty()) {
      try {
        field.array = std::stoi(length);
      } catch (const std::exception&) {
        throw Error("the message definition line '" + line + "' has an array length that is not a number");
      }
      if (field.array <= 0) throw Error("the message definition line '" + line + "' has an array length <= 0");
    }
    type = type.substr(0, open);
  }
  field.name = name;
  field.type = fullName(type, package);
  return true;
}

/// Where a value lies in its message, kept as a chain on the stack and written out only for an
/// error ("bins[12].intensity"): decoding builds no text.
struct Path {
  const Path* parent = nullptr;
  const std::string* name = nullptr;  ///< a field, or nullptr for an array element
  std::size_t index = 0;              ///< the element's index
};

std::string pathText(const Path* path) {
  if (path == nullptr) return "the message";
  std::string text = pathText(path->parent);
  if (text == "the message") text.clear();
  if (path->name != nullptr) return text.empty() ? *path->name : text + "." + *path->name;
  return text + "[" + std::to_string(path->index) + "]";
}

/// Reads the message bytes in order; in CDR each number is first aligned to its size (at most 8)
/// from `origin`, the byte after the encapsulation header (OMG's CDR, DDS-XTYPES 1.3, 7.4.3.2).
class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, bool cdr, std::size_t origin) : bytes_(bytes), at_(origin), origin_(origin), cdr_(cdr) {}
  template <class T>
  T take(const Path* where) {
    T value;
    if (cdr_) {
      const std::size_t misaligned = (at_ - origin_) % sizeof(T);
      if (misaligned != 0) {
        need(sizeof(T) - misaligned, where);
        at_ += sizeof(T) - misaligned;
      }
    }
    need(sizeof(T), where);
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));  // ROS 1 and this machine: little-endian
    at_ += sizeof(T);
    return value;
  }
  std::span<const std::uint8_t> takeBytes(std::size_t count, const Path* where) {
    need(count, where);
    const auto out = bytes_.subspan(at_, count);
    at_ += count;
    return out;
  }
  std::size_t remaining() const { return bytes_.size() - at_; }
  bool cdr() const { return cdr_; }

 private:
  void need(std::size_t count, const Path* where) const {
    if (count > bytes_.size() - at_) {
      throw Error("the message ends within " + pathText(where) + " (byte " + std::to_string(at_) + " of " +
                  std::to_string(bytes_.size()) + ")");
    }
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  std::size_t origin_ = 0;
  bool cdr_ = false;
};

/// The kind of a builtin type name; kMessage for any other.
RosKind kindOf(const std::string& type) {
  static const std::array<std::pair<const char*, RosKind>, 16> kinds{{
      {"bool", RosKind::kBool},       {"int8", RosKind::kInt8},       {"uint8", RosKind::kUint8},
      {"byte", RosKind::kUint8},      {"char", RosKind::kUint8},      {"int16", RosKind::kInt16},
      {"uint16", RosKind::kUint16},   {"int32", RosKind::kInt32},     {"uint32", RosKind::kUint32},
      {"int64", RosKind::kInt64},     {"uint64", RosKind::kUint64},   {"float32", RosKind::kFloat32},
      {"float64", RosKind::kFloat64}, {"string", RosKind::kString},   {"time", RosKind::kTime},
      {"duration", RosKind::kDuration}}};
  for (const auto& [name, kind] : kinds) {
    if (type == name) return kind;
  }
  return RosKind::kMessage;
}

double decodeNumber(RosKind kind, Reader& in, const Path* where) {
  switch (kind) {
    case RosKind::kBool:
    case RosKind::kUint8: return in.take<std::uint8_t>(where);
    case RosKind::kInt8: return in.take<std::int8_t>(where);
    case RosKind::kInt16: return in.take<std::int16_t>(where);
    case RosKind::kUint16: return in.take<std::uint16_t>(where);
    case RosKind::kInt32: return in.take<std::int32_t>(where);
    case RosKind::kUint32: return in.take<std::uint32_t>(where);
    case RosKind::kInt64: return static_cast<double>(in.take<std::int64_t>(where));
    case RosKind::kUint64: return static_cast<double>(in.take<std::uint64_t>(where));
    case RosKind::kFloat32: return in.take<float>(where);
    case RosKind::kFloat64: return in.take<double>(where);
    case RosKind::kTime:
    case RosKind::kDuration: {
      // time: uint32 seconds and nanoseconds; duration: int32 both. ROS 2 (builtin_interfaces): an
      // int32 sec and a uint32 nanosec for both.
      if (in.cdr()) {
        const double seconds = in.take<std::int32_t>(where);
        return rosStampSeconds(seconds, in.take<std::uint32_t>(where));
      }
      if (kind == RosKind::kTime) {
        const double seconds = in.take<std::uint32_t>(where);
        return rosStampSeconds(seconds, in.take<std::uint32_t>(where));
      }
      const double seconds = in.take<std::int32_t>(where);
      return rosStampSeconds(seconds, in.take<std::int32_t>(where));
    }
    default: return 0.0;  // kString, kMessage: not numbers (decodeElement)
  }
}

RosValue decodeStruct(const RosSchema& schema, std::size_t type, Reader& in, const Path* where, int depth);

RosValue decodeElement(const RosSchema& schema, const RosField& field, Reader& in, const Path* where, int depth) {
  if (field.kind == RosKind::kMessage) return decodeStruct(schema, field.message, in, where, depth);
  if (field.kind != RosKind::kString) return {decodeNumber(field.kind, in, where)};
  // string: a uint32 length, then the bytes (CDR: the length counts a terminating NUL)
  const auto length = in.take<std::uint32_t>(where);
  const auto text = in.takeBytes(length, where);
  std::string out(text.begin(), text.end());
  if (in.cdr() && !out.empty() && out.back() == '\0') out.pop_back();
  return {std::move(out)};
}

RosValue decodeField(const RosSchema& schema, const RosField& field, Reader& in, const Path* where, int depth) {
  if (field.array < 0) return decodeElement(schema, field, in, where, depth);
  const std::size_t count = field.array > 0 ? static_cast<std::size_t>(field.array) : in.take<std::uint32_t>(where);
  if (field.kind == RosKind::kUint8 || field.kind == RosKind::kInt8) {
    const auto bytes = in.takeBytes(count, where);
    return {std::vector<std::uint8_t>(bytes.begin(), bytes.end())};
  }
  // Every element takes a byte at least: a count beyond the bytes left cannot be honest.
  if (count > in.remaining()) {
    throw Error("the array " + pathText(where) + " declares " + std::to_string(count) + " elements in " +
                std::to_string(in.remaining()) + " bytes");
  }
  if (field.kind == RosKind::kMessage && schema.isTable(field.message)) {
    RosTable table;
    table.fields = &schema.fieldsAt(field.message);
    table.values.reserve(count * table.fields->size());
    for (std::size_t i = 0; i < count; ++i) {
      const Path element{where, nullptr, i};
      for (const RosField& column : *table.fields) {
        const Path cell{&element, &column.name, 0};
        table.values.push_back(decodeNumber(column.kind, in, &cell));
      }
    }
    return {std::move(table)};
  }
  std::vector<RosValue> items;
  items.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Path element{where, nullptr, i};
    items.push_back(decodeElement(schema, field, in, &element, depth));
  }
  return {std::move(items)};
}

RosValue decodeStruct(const RosSchema& schema, std::size_t type, Reader& in, const Path* where, int depth) {
  if (depth >= kMaxDepth) throw Error("the message nests deeper than " + std::to_string(kMaxDepth) + " at " + pathText(where));
  const std::vector<RosField>& fields = schema.fieldsAt(type);
  RosStruct decoded;
  decoded.fields = &fields;
  decoded.values.reserve(fields.size());
  for (const RosField& field : fields) {
    const Path child{where, &field.name, 0};
    decoded.values.push_back(decodeField(schema, field, in, &child, depth + 1));
  }
  return {std::move(decoded)};
}

}  // namespace

bool RosSchema::isBuiltin(const std::string& type) { return kindOf(type) != RosKind::kMessage; }

RosSchema::RosSchema(const std::string& type, const std::string& definition, RosEncoding encoding)
    : root_(encoding == RosEncoding::kCdr ? ros2Name(type) : type), encoding_(encoding) {
  const auto typeIndex = [this](const std::string& name) {
    const auto found = std::find(names_.begin(), names_.end(), name);
    if (found != names_.end()) return static_cast<std::size_t>(found - names_.begin());
    names_.push_back(name);
    types_.emplace_back();
    return names_.size() - 1;
  };
  std::istringstream lines(definition);
  std::string line, current = root_;
  std::size_t fields = typeIndex(root_);
  while (std::getline(lines, line)) {
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    if (line.find_first_not_of('=') == std::string::npos) continue;  // the separator before a section
    if (line.rfind("MSG:", 0) == 0) {
      current = trimmed(line.substr(4));
      if (encoding == RosEncoding::kCdr) current = ros2Name(current);
      fields = typeIndex(current);
      continue;
    }
    RosField field;
    if (parseField(line, packageOf(current), encoding, field)) types_[fields].push_back(field);
  }
  for (std::size_t t = 0; t < types_.size(); ++t) {
    for (RosField& field : types_[t]) {
      field.kind = kindOf(field.type);
      if (field.kind != RosKind::kMessage) continue;
      const auto found = std::find(names_.begin(), names_.end(), field.type);
      if (found == names_.end()) {
        throw Error("the message definition of " + type + " uses " + field.type + " (field " + names_[t] + "." +
                    field.name + ") without defining it");
      }
      field.message = static_cast<std::size_t>(found - names_.begin());
    }
  }
  for (const std::vector<RosField>& fields : types_) {
    tables_.push_back(!fields.empty() && std::all_of(fields.begin(), fields.end(), [](const RosField& f) {
      return f.array < 0 && f.kind != RosKind::kMessage && f.kind != RosKind::kString;
    }));
  }
}

std::string RosSchema::typeAt(const std::vector<std::string>& path) const {
  std::string type = root_;
  for (const std::string& name : path) {
    if (isBuiltin(type)) return {};
    const std::vector<RosField>& list = fields(type);
    const auto field = std::find_if(list.begin(), list.end(), [&](const RosField& f) { return f.name == name && f.array < 0; });
    if (field == list.end()) return {};
    type = field->type;
  }
  return type;
}

bool RosSchema::holdsNumbers(const std::vector<std::string>& path, std::initializer_list<const char*> names) const {
  const std::string type = typeAt(path);
  if (type.empty() || isBuiltin(type)) return false;
  for (const char* name : names) {
    std::vector<std::string> child = path;
    child.emplace_back(name);
    const std::string field_type = typeAt(child);
    if (field_type.empty() || !isBuiltin(field_type) || field_type == "string") return false;
  }
  return true;
}

const RosValue& valueAt(const RosValue& message, const std::vector<std::string>& path) {
  const RosValue* value = &message;
  for (const std::string& name : path) value = value->field(name);
  return *value;
}

double finiteNumber(const RosValue* value, const std::string& what) {
  const double* number = value != nullptr ? std::get_if<double>(&value->value) : nullptr;
  if (number == nullptr || !std::isfinite(*number)) throw Error("its " + what + " is not a finite number");
  return *number;
}

const std::vector<RosField>& RosSchema::fields(const std::string& type) const {
  const auto found = std::find(names_.begin(), names_.end(), type);
  if (found == names_.end()) throw Error("the message definition does not define " + type);
  return types_[static_cast<std::size_t>(found - names_.begin())];
}

const RosValue* RosValue::field(const std::string& name) const {
  const auto* decoded = std::get_if<RosStruct>(&value);
  if (decoded == nullptr) return nullptr;
  for (std::size_t i = 0; i < decoded->values.size(); ++i) {
    if ((*decoded->fields)[i].name == name) return &decoded->values[i];
  }
  return nullptr;
}

std::size_t RosTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < fields->size(); ++c) {
    if ((*fields)[c].name == name) return c;
  }
  return fields->size();
}

RosValue decodeRosMessage(const RosSchema& schema, std::span<const std::uint8_t> bytes) {
  const bool cdr = schema.encoding() == RosEncoding::kCdr;
  if (cdr) {
    // The encapsulation header: 0x00 0x01 is plain CDR, little-endian; 0x00 0x00 big-endian.
    if (bytes.size() < 4) throw Error("the message is shorter than its CDR encapsulation header");
    if (bytes[0] != 0x00 || bytes[1] != 0x01) {
      throw Error("the message's CDR encapsulation is not little-endian plain CDR (0x00 0x01)");
    }
  }
  Reader in(bytes, cdr, cdr ? 4 : 0);
  RosValue message = decodeStruct(schema, 0, in, nullptr, 0);
  if (in.remaining() > (cdr ? 3u : 0u)) {  // CDR pads a message to a multiple of 4 bytes
    throw Error(std::to_string(in.remaining()) + " bytes remain after the " + schema.root() + " message");
  }
  return message;
}

}  // namespace sonarmap::detail
