/// @file ros_message.cpp
/// ROS 1 message definitions and their serialized messages (see ros_message.hpp).

#include "ros_message.hpp"

#include <array>
#include <cstring>
#include <sstream>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

/// The builtin types of the msg format.
constexpr std::array<const char*, 16> kBuiltins{"bool",   "int8",   "uint8",   "byte",    "char",   "int16",
                                                 "uint16", "int32",  "uint32",  "int64",   "uint64", "float32",
                                                 "float64", "string", "time",   "duration"};
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

/// Parses one field line ("float32[] ranges", "uint8[16] id"); false for a constant.
bool parseField(const std::string& line, const std::string& package, RosField& field) {
  std::istringstream words(line);
  std::string type, name;
  if (!(words >> type >> name)) throw Error("the message definition line '" + line + "' is not TYPE NAME");
  if (line.find('=') != std::string::npos) return false;  // a constant: not in the serialized message
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

/// Reads the message bytes in order.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  template <class T>
  T take(const std::string& what) {
    T value;
    need(sizeof(T), what);
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));  // ROS 1 and this machine: little-endian
    at_ += sizeof(T);
    return value;
  }
  std::span<const std::uint8_t> takeBytes(std::size_t count, const std::string& what) {
    need(count, what);
    const auto out = bytes_.subspan(at_, count);
    at_ += count;
    return out;
  }
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  void need(std::size_t count, const std::string& what) const {
    if (count > bytes_.size() - at_) {
      throw Error("the message ends within " + what + " (byte " + std::to_string(at_) + " of " +
                  std::to_string(bytes_.size()) + ")");
    }
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

RosValue decodeType(const RosSchema& schema, const std::string& type, Reader& in, const std::string& path, int depth);

RosValue decodeBuiltin(const std::string& type, Reader& in, const std::string& path) {
  if (type == "bool" || type == "uint8" || type == "byte" || type == "char") return {static_cast<double>(in.take<std::uint8_t>(path))};
  if (type == "int8") return {static_cast<double>(in.take<std::int8_t>(path))};
  if (type == "int16") return {static_cast<double>(in.take<std::int16_t>(path))};
  if (type == "uint16") return {static_cast<double>(in.take<std::uint16_t>(path))};
  if (type == "int32") return {static_cast<double>(in.take<std::int32_t>(path))};
  if (type == "uint32") return {static_cast<double>(in.take<std::uint32_t>(path))};
  if (type == "int64") return {static_cast<double>(in.take<std::int64_t>(path))};
  if (type == "uint64") return {static_cast<double>(in.take<std::uint64_t>(path))};
  if (type == "float32") return {static_cast<double>(in.take<float>(path))};
  if (type == "float64") return {in.take<double>(path)};
  if (type == "time" || type == "duration") {
    // time: uint32 seconds and nanoseconds; duration: int32 both.
    if (type == "time") {
      const double seconds = in.take<std::uint32_t>(path);
      return {seconds + 1e-9 * in.take<std::uint32_t>(path)};
    }
    const double seconds = in.take<std::int32_t>(path);
    return {seconds + 1e-9 * in.take<std::int32_t>(path)};
  }
  // string
  const auto length = in.take<std::uint32_t>(path);
  const auto text = in.takeBytes(length, path);
  return {std::string(text.begin(), text.end())};
}

RosValue decodeField(const RosSchema& schema, const RosField& field, Reader& in, const std::string& path, int depth) {
  if (field.array < 0) return decodeType(schema, field.type, in, path, depth);
  const std::size_t count = field.array > 0 ? static_cast<std::size_t>(field.array) : in.take<std::uint32_t>(path);
  if (field.type == "uint8" || field.type == "byte" || field.type == "char" || field.type == "int8") {
    const auto bytes = in.takeBytes(count, path);
    return {std::vector<std::uint8_t>(bytes.begin(), bytes.end())};
  }
  // Every element takes a byte at least: a count beyond the bytes left cannot be honest.
  if (count > in.remaining()) throw Error("the array " + path + " declares " + std::to_string(count) + " elements in " +
                                          std::to_string(in.remaining()) + " bytes");
  std::vector<RosValue> items;
  items.reserve(count);
  for (std::size_t i = 0; i < count; ++i) items.push_back(decodeType(schema, field.type, in, path + "[" + std::to_string(i) + "]", depth));
  return {std::move(items)};
}

RosValue decodeType(const RosSchema& schema, const std::string& type, Reader& in, const std::string& path, int depth) {
  if (RosSchema::isBuiltin(type)) return decodeBuiltin(type, in, path);
  if (depth >= kMaxDepth) throw Error("the message nests deeper than " + std::to_string(kMaxDepth) + " at " + path);
  RosStruct fields;
  for (const RosField& field : schema.fields(type)) {
    fields.names.push_back(field.name);
    fields.values.push_back(decodeField(schema, field, in, path.empty() ? field.name : path + "." + field.name, depth + 1));
  }
  return {std::move(fields)};
}

}  // namespace

bool RosSchema::isBuiltin(const std::string& type) {
  for (const char* builtin : kBuiltins) {
    if (type == builtin) return true;
  }
  return false;
}

RosSchema::RosSchema(const std::string& type, const std::string& definition) : root_(type) {
  std::istringstream lines(definition);
  std::string line, current = type;
  std::vector<RosField>* fields = &types_[type];
  while (std::getline(lines, line)) {
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    if (line.find_first_not_of('=') == std::string::npos) continue;  // the separator before a section
    if (line.rfind("MSG:", 0) == 0) {
      current = trimmed(line.substr(4));
      fields = &types_[current];
      continue;
    }
    RosField field;
    if (parseField(line, packageOf(current), field)) fields->push_back(field);
  }
  for (const auto& [name, list] : types_) {
    for (const RosField& field : list) {
      if (!isBuiltin(field.type) && types_.find(field.type) == types_.end()) {
        throw Error("the message definition of " + type + " uses " + field.type + " (field " + name + "." + field.name +
                    ") without defining it");
      }
    }
  }
}

const std::vector<RosField>& RosSchema::fields(const std::string& type) const {
  const auto found = types_.find(type);
  if (found == types_.end()) throw Error("the message definition does not define " + type);
  return found->second;
}

const RosValue* RosValue::field(const std::string& name) const {
  const auto* fields = std::get_if<RosStruct>(&value);
  if (fields == nullptr) return nullptr;
  for (std::size_t i = 0; i < fields->names.size(); ++i) {
    if (fields->names[i] == name) return &fields->values[i];
  }
  return nullptr;
}

RosValue decodeRosMessage(const RosSchema& schema, std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  RosValue message = decodeType(schema, schema.root(), in, "", 0);
  if (in.remaining() != 0) {
    throw Error(std::to_string(in.remaining()) + " bytes remain after the " + schema.root() + " message");
  }
  return message;
}

}  // namespace sonarmap::detail
