// Every tool's error messages have one form, "TOOL: error: REASON" (io/cli_exit.hpp): CLI11's
// messages (an unknown option, a missing file, a folder given as a file, a value out of range)
// and the tools' own (bad input, a failed run). A number's range is printed in a few digits.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/temp_dir.hpp"
#include "run_tool.hpp"

namespace ecm::test {
namespace {

// Every line of stderr that is not the help hint starts with "TOOL: error: ".
void expectErrorForm(const std::string& tool, const ToolRun& r) {
  EXPECT_EQ(r.status, ecm::io::kExitBadInput) << tool << ": " << r.err;
  ASSERT_FALSE(r.err.empty()) << tool;
  std::istringstream lines(r.err);
  std::string line;
  int errors = 0;
  while (std::getline(lines, line)) {
    if (line.empty() || line.rfind("Run with --help", 0) == 0) continue;
    EXPECT_EQ(line.rfind(tool + ": error: ", 0), 0u) << "from " << tool << ": " << r.err;
    EXPECT_LT(line.size(), 400u) << line;  // (--threads -1 printed a range of 300 digits)
    ++errors;
  }
  EXPECT_EQ(errors, 1) << r.err;
}

struct Case {
  std::string tool, binary;
  std::vector<std::string> badArguments;  // each a whole bad command line (shell words)
};

std::vector<Case> cases(const TempDir& tmp) {
  const std::string folder = shellQuoted(tmp.path());
  const std::string missing = shellQuoted(tmp.path() / "missing.yaml");
  const std::string bad = shellQuoted(tmp.path() / "bad.yaml");
  std::vector<Case> c{
      {"ecm-point", ECM_POINT, {"--no-such-option", missing, folder, bad, ""}},
      {"ecm-calibrate", ECM_CALIBRATE, {"--no-such-option", "--E 32000 --ft 3 --h 0.05 --Ep -1 --n 0.1", "--fit bogus"}},
  };
#ifdef ECM_MPM
  c.push_back({"ecm-mpm", ECM_MPM, {"--no-such-option", missing, folder, bad, bad + " --threads -1", bad + " --max-steps 0"}});
#endif
#ifdef ECM_RVE
  c.push_back({"ecm-rve", ECM_RVE, {"--no-such-option", missing, bad}});
#endif
#ifdef ECM_STUDY
  c.push_back({"ecm-study", ECM_STUDY, {"--no-such-option", missing, folder, bad, bad + " --threads 0"}});
#endif
  return c;
}

TEST(ErrorForm, EveryToolPrintsOneForm) {
  TempDir tmp;
  std::ofstream(tmp.path() / "bad.yaml") << "name: bad\nno_such_key: 1\n";
  for (const Case& c : cases(tmp))
    for (const std::string& args : c.badArguments) {
      SCOPED_TRACE(c.tool + " " + args);
      expectErrorForm(c.tool, runTool(c.binary, args, tmp.path()));
    }
}

TEST(ErrorForm, ThreadsOutOfRangeSaysTheRangeInAFewDigits) {
#ifdef ECM_MPM
  TempDir tmp;
  std::ofstream(tmp.path() / "s.yaml") << "name: s\n";
  const ToolRun r = runTool(ECM_MPM, shellQuoted(tmp.path() / "s.yaml") + " --threads -1", tmp.path());
  EXPECT_EQ(r.status, ecm::io::kExitBadInput);
  EXPECT_NE(r.err.find("ecm-mpm: error: --threads: Value -1 not in range 0 to 4096"), std::string::npos) << r.err;
#else
  GTEST_SKIP() << "no ecm-mpm in this build";
#endif
}

}  // namespace
}  // namespace ecm::test
