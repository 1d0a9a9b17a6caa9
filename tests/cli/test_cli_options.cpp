// The mapping options of `sonarmap map` and `sonarmap live` are the library's table
// (mapping/mapping_option_table.hpp): each is a flag with the table's help, and each value the
// table refuses is a usage error (exit 2) naming the flag.
#include <gtest/gtest.h>

#include <string>

#include "cli_fixture.hpp"
#include "common/refused_option_values.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap::test {
namespace {

using cliOptions = CliTest;

TEST_F(cliOptions, MapAndLiveHelpShowEveryOptionWithTheTablesHelp) {
  for (const char* command : {"map", "live"}) {
    const ProgramRun help = run({command, "--help"});
    ASSERT_EQ(help.exit_code, 0) << help.err;
    for (const MappingOption& option : mappingOptionTable()) {
      EXPECT_NE(help.out.find(optionFlag(option)), std::string::npos) << command << ": " << optionFlag(option);
      EXPECT_NE(help.out.find(optionHelp(option)), std::string::npos) << command << ": " << optionHelp(option);
    }
  }
}

TEST_F(cliOptions, EveryRefusedValueIsAUsageErrorNamingTheFlag) {
  for (const MappingOption& option : mappingOptionTable()) {
    for (const std::string& value : refusedValues(option)) {
      const std::string given = optionFlag(option) + "=" + value;  // "=": a negative number stays a value
      const ProgramRun result = run({"map", (root_ / "missing.csv").string(), "-o", (out_ / "MAP.bt").string(), given});
      expectError(result, 2);
      EXPECT_NE(result.err.find(optionFlag(option)), std::string::npos) << given << ": " << result.err;
    }
  }
  EXPECT_EQ(listDir(out_), Names{});
}

}  // namespace
}  // namespace sonarmap::test
