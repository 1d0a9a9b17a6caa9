#include "full_tool.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "run_command.hpp"

#ifndef SONARMAP_FULL_TOOL_RELATIVE_DIR
#error "SONARMAP_FULL_TOOL_RELATIVE_DIR: the full tool's folder relative to the installed sonarmap's"
#endif

namespace sonarmap::cli {

std::vector<std::string> fullToolCandidates(const std::string& lean_path, const std::string& relative_dir) {
  const std::filesystem::path folder = std::filesystem::path(lean_path).parent_path();
  return {(folder / "sonarmap-full").string(), (folder / relative_dir / "sonarmap-full").lexically_normal().string()};
}

int execFullTool(char** argv) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return fail(1, ("cannot find the sonarmap executable (/proc/self/exe): " + error.message()).c_str());
  std::string tried;
  for (const std::string& candidate : fullToolCandidates(self.string(), SONARMAP_FULL_TOOL_RELATIVE_DIR)) {
    ::execv(candidate.c_str(), argv);  // returns only on failure
    tried += (tried.empty() ? "" : ", ") + candidate + " (" + std::strerror(errno) + ")";
  }
  return fail(1, ("the full sonarmap tool is missing: tried " + tried).c_str());
}

}  // namespace sonarmap::cli
