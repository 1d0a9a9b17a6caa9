#include "sonarmap/formats/log_reader.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/formats/v4log_reader.hpp"

namespace sonarmap {

SonarLog readSonarLog(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".mat") return readCrasMat(path);
  if (extension == ".csv") return readBeamCsv(path);
  if (extension == ".v4log") return readSeaNetV4Log(path);
  throw FileError("'" + path + "': unknown sonar log type '" + extension + "', expected .mat, .csv or .V4LOG");
}

}  // namespace sonarmap
