// GDAL is loaded only when a GeoTIFF is written: the dynamic loader's own report (LD_DEBUG=files,
// on stderr) of every object a command loads names no libgdal unless --geotiff is given; and a
// GDAL plugin that cannot be found is one line naming where it was looked for, nothing written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

/// Sets an environment variable that the commands run meanwhile inherit; restores it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

class cliGeoPlugin : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const ProgramRun sim = run({"simulate", "tank", "-o", (root_ / "sim").string(), "--turns", "1", "--bag",
                                (root_ / "run.bag").string(), "-q"});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    beams_ = (root_ / "sim" / "beams.csv").string();
    bag_ = (root_ / "run.bag").string();
  }
  /// `args` run with the loader reporting each object it loads.
  ProgramRun runTracingLoads(const Names& args) const {
    const ScopedEnv trace("LD_DEBUG", "files");
    return run(args);
  }
  std::string beams_;  ///< the simulated tank's beams, as CSV
  std::string bag_;    ///< the same as a ROS 1 bag (which live replays)
};

bool loadsGdal(const ProgramRun& r) { return r.err.find("libgdal.so") != std::string::npos; }

TEST_F(cliGeoPlugin, OnlyAGeoTiffLoadsGdal) {
  for (const Names& args : {Names{"--version"}, Names{"info", beams_},
                            Names{"map", beams_, "-o", (out_ / "map.bt").string(), "--png", (out_ / "map.png").string(), "-q"}}) {
    const ProgramRun r = runTracingLoads(args);
    ASSERT_EQ(r.exit_code, 0) << args[0] << ": " << r.err;
    EXPECT_FALSE(loadsGdal(r)) << args[0] << " loads GDAL";
    EXPECT_EQ(r.err.find("sonarmap_geotiff_gdal"), std::string::npos) << args[0] << " loads the GDAL plugin";
  }
  // The check itself sees GDAL when it is loaded: by the plugin, for --geotiff.
  const ProgramRun geo = runTracingLoads({"map", beams_, "-o", (out_ / "map.bt").string(), "--geotiff",
                                          (out_ / "map.tif").string(), "--geo-origin", "43.2961,5.37", "-q"});
  ASSERT_EQ(geo.exit_code, 0) << geo.err;
  EXPECT_TRUE(loadsGdal(geo));
  EXPECT_NE(geo.err.find("sonarmap/sonarmap_geotiff_gdal.so"), std::string::npos);
  EXPECT_EQ(readFile(out_ / "map.tif").substr(0, 4), std::string("II*\0", 4));  // a little-endian TIFF
}

TEST_F(cliGeoPlugin, AMissingPluginIsOneLineAndWritesNothing) {
  // The writer's library alone in a folder the loader searches first (LD_LIBRARY_PATH comes before
  // the tool's RUNPATH): its plugin is looked for beside it, in lib/sonarmap/, where there is none.
  const fs::path lib = root_ / "lib";
  fs::create_directory(lib);
  fs::copy_file(SONARMAP_GEOTIFF_LIBRARY, lib / fs::path(SONARMAP_GEOTIFF_LIBRARY).filename());
  const ScopedEnv search("LD_LIBRARY_PATH", lib.string());
  const std::string tried = (lib / "sonarmap" / "sonarmap_geotiff_gdal.so").string();
  for (const char* command : {"map", "live"}) {
    Names args{command, std::string(command) == "live" ? bag_ : beams_, "-o", (out_ / "map.bt").string(), "--geotiff", (out_ / "map.tif").string(),
               "--geo-origin", "43.2961,5.37", "-q"};
    if (std::string(command) == "live") args.insert(args.end(), {"--rate", "0"});
    const ProgramRun r = run(args);
    expectError(r, 1);
    EXPECT_NE(r.err.find("cannot load the GDAL plugin " + tried), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << r.err;  // dlerror()'s
    EXPECT_TRUE(listDir(out_).empty()) << command;
  }
  // Without --geotiff the same library maps as before.
  const ProgramRun plain = run({"map", beams_, "-o", (out_ / "map.bt").string(), "-q"});
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
}

}  // namespace
}  // namespace sonarmap::test
