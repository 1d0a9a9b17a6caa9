#include "eval_scoring_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <utility>

#include <nlohmann/json.hpp>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// One key of the file: the eval option it stands for and how its value goes into EvalArgs.
struct Key {
  const char* name;  ///< the option without its dashes
  std::function<void(const json& value, const fs::path& folder, EvalArgs& args)> apply;
};

[[noreturn]] void throwKind(const std::string& path, const char* key, const char* kind) {
  throw ValueError("--scoring " + path + ": \"" + key + "\" must be " + kind);
}

std::vector<Key> keys(const std::string& path) {
  // A file name relative to the scoring file's folder.
  const auto file = [&path](const char* key) {
    return [&path, key](const json& value, const fs::path& folder, std::string& field) {
      if (!value.is_string()) throwKind(path, key, "a file name");
      const fs::path name = value.get<std::string>();
      field = name.is_absolute() ? name.string() : (folder / name).string();
    };
  };
  const auto number = [&path](const json& value, const char* key) {
    if (!value.is_number()) throwKind(path, key, "a number");
    return value.get<double>();
  };
  const auto numbers = [&path](const json& value, const char* key, std::size_t count) {
    if (!value.is_array() || value.size() != count ||
        !std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); })) {
      throwKind(path, key, count == 6 ? "an array of 6 numbers" : "an array of numbers");
    }
    return value.get<std::vector<double>>();
  };
  return {
      {"truth",
       [&path](const json& value, const fs::path& folder, EvalArgs& args) {
         if (!value.is_string()) throwKind(path, "truth", "a scene file or a built-in scene's name");
         const fs::path name = value.get<std::string>();
         // A scene beside the file, else the name as given (a built-in scene, or a path from here).
         args.truth = !name.is_absolute() && fs::exists(folder / name) ? (folder / name).string() : name.string();
       }},
      {"max-range", [=](const json& v, const fs::path&, EvalArgs& args) { args.max_range_m = number(v, "max-range"); }},
      {"vertical-aperture",
       [=](const json& v, const fs::path&, EvalArgs& args) {
         args.vertical_aperture_deg = number(v, "vertical-aperture");
       }},
      {"sensor-pose",
       [=, &path](const json& v, const fs::path&, EvalArgs& args) {
         if (!v.is_array()) throwKind(path, "sensor-pose", "an array of [x, y, z, roll, pitch, yaw] arrays");
         args.sensor_pose.clear();
         for (const json& pose : v) {
           for (const double value : numbers(pose, "sensor-pose", 6)) args.sensor_pose.push_back(value);
         }
       }},
      {"heard-by", [=](const json& v, const fs::path& folder, EvalArgs& args) { file("heard-by")(v, folder, args.heard.beams); }},
      {"nav", [=](const json& v, const fs::path& folder, EvalArgs& args) { file("nav")(v, folder, args.heard.nav_csv); }},
      {"mounting", [=](const json& v, const fs::path&, EvalArgs& args) { args.heard.mounting = numbers(v, "mounting", 6); }},
      {"sonar",
       [&path](const json& v, const fs::path&, EvalArgs& args) {
         if (!v.is_string()) throwKind(path, "sonar", "a head preset's name");
         args.heard.sonar = v.get<std::string>();
       }},
  };
}

}  // namespace

void writeScoringFile(std::ostream& out, const ScoringFile& file) {
  // One option a line and one pose a line, each value as JSON writes it (doubles read back exactly).
  out << "{\n \"truth\": " << json(file.truth).dump() << ",\n \"max-range\": " << json(file.max_range_m).dump()
      << ",\n \"vertical-aperture\": " << json(file.vertical_aperture_deg).dump() << ",\n \"sensor-pose\": [";
  for (std::size_t i = 0; i < file.sensor_poses.size(); ++i) {
    out << (i == 0 ? "\n  " : ",\n  ") << json(file.sensor_poses[i]).dump();
  }
  out << "\n ],\n \"heard-by\": " << json(file.heard_by).dump() << ",\n \"nav\": " << json(file.nav).dump()
      << ",\n \"mounting\": " << json(file.mounting).dump() << ",\n \"sonar\": " << json(file.sonar).dump()
      << "\n}\n";
}

void applyScoringFile(const std::string& path, const CLI::App& cmd, EvalArgs& args) {
  std::ifstream in(path);
  if (!in) throw ValueError("--scoring: cannot read '" + path + "'");
  const json object = json::parse(in, nullptr, false);
  if (object.is_discarded() || !object.is_object()) {
    throw ValueError("--scoring " + path + ": not a JSON object of eval's options");
  }
  const fs::path folder = fs::path(path).parent_path();
  const std::vector<Key> accepted = keys(path);
  for (const auto& [name, value] : object.items()) {
    const auto key = std::find_if(accepted.begin(), accepted.end(), [&](const Key& k) { return name == k.name; });
    if (key == accepted.end()) {
      std::string names;
      for (const Key& k : accepted) names += (names.empty() ? "" : ", ") + std::string(k.name);
      throw ValueError("--scoring " + path + ": unknown key \"" + name + "\" (keys: " + names + ")");
    }
    const std::string flag = "--" + name;
    // The sonar's positions are --sensor's or --sensor-pose's, whichever the command line gave.
    const bool given = cmd.count(flag) > 0 || (name == "sensor-pose" && cmd.count("--sensor") > 0);
    if (given) continue;
    key->apply(value, folder, args);
    args.file_options.push_back(flag);
  }
}

}  // namespace sonarmap::cli
