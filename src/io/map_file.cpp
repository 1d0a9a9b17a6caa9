#include "sonarmap/io/map_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/octomap_full.hpp"

namespace sonarmap {

MapFormat mapFormatOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".bt") return MapFormat::kBinary;
  if (extension == ".ot") return MapFormat::kFull;
  throw FileError("'" + path + "': unknown map file extension '" + extension + "', expected .bt or .ot");
}

void writeMapFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments) {
  if (mapFormatOf(path) == MapFormat::kBinary) {
    writeBinaryFile(tree, path, comments);
  } else {
    writeFullFile(tree, path, comments);
  }
}

void writeMap(const OcTree16& tree, std::ostream& out, MapFormat format, const std::vector<std::string>& comments) {
  if (format == MapFormat::kBinary) {
    writeBinary(tree, out, comments);
  } else {
    writeFull(tree, out, comments);
  }
}

OctomapHeader readMapFileHeader(const std::string& path) {
  const char* first_line = mapFormatOf(path) == MapFormat::kBinary ? kBinaryFileFirstLine : kFullFileFirstLine;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  return readOctomapHeader(in, first_line, path);
}

OcTree16 readMapFile(const std::string& path, const OctreeOptions& options) {
  return mapFormatOf(path) == MapFormat::kBinary ? readBinaryFile(path, options) : readFullFile(path, options);
}

}  // namespace sonarmap
