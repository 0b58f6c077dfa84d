// What every tool that reads an input file answers before it runs (io/cli_exit.hpp): a missing
// input file, no input or an unknown option, and an output folder that is a file are bad input
// (exit 2) naming what is wrong; --help is done (exit 0) and lists the tool's own options. Each
// tool's runs and failures are tested beside it (tests/driver, tests/mpm, tests/study).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/temp_dir.hpp"
#include "run_tool.hpp"

namespace ecm::test {
namespace {

struct Tool {
  std::string name, binary;
  std::string before;      // arguments before the input file ("--study" for ecm-point's study)
  std::string input;       // a valid input file (empty: the tool needs none for the case)
  std::string quiet;       // the flag that keeps stderr to the error
  std::string ownOption;   // an option --help must list
  bool writesOutput = true;  // takes --out
};

std::vector<Tool> tools() {
  const std::string data = std::string(ECM_SOURCE_DIR) + "/data/";
  std::vector<Tool> t{
      {"ecm-point", ECM_POINT, "", data + "point/uniaxial-tension-H10.yaml", "", "--study"},
      {"ecm-point --study", ECM_POINT, "--study ", data + "point/snapback-study.yaml", "", "--study"},
  };
#ifdef ECM_MPM
  t.push_back({"ecm-mpm", ECM_MPM, "", data + "mpm/tension-block.yaml", "-q --no-vtu --no-plot", "--restart"});
#endif
#ifdef ECM_STUDY
  t.push_back({"ecm-study", ECM_STUDY, "", data + "studies/point-uniaxial.yaml", "-q", "--resume"});
#endif
#ifdef ECM_RVE
  t.push_back({"ecm-rve", ECM_RVE, "", "", "", "--out", false});
#endif
  return t;
}

TEST(ToolStatus, AMissingInputFileIsBadInputNamingIt) {
  TempDir tmp;
  for (const Tool& t : tools()) {
    SCOPED_TRACE(t.name);
    const ToolRun r = runTool(t.binary, t.before + shellQuoted(tmp.path() / "no-such-input.yaml"), tmp.path());
    EXPECT_EQ(r.status, io::kExitBadInput) << r.err;  // CLI11 alone would exit 105
    expectContains(r.err, "no-such-input.yaml");      // CLI11's message
  }
}

TEST(ToolStatus, NoInputOrAnUnknownOptionIsBadInputAndHelpIsDone) {
  TempDir tmp;
  for (const Tool& t : tools()) {
    SCOPED_TRACE(t.name);
    if (!t.input.empty()) {
      EXPECT_EQ(runTool(t.binary, "", tmp.path()).status, io::kExitBadInput);  // no input file
      const ToolRun unknown = runTool(t.binary, t.before + shellQuoted(t.input) + " --no-such-option", tmp.path());
      EXPECT_EQ(unknown.status, io::kExitBadInput);
      expectContains(unknown.err, "no-such-option");
    }
    const ToolRun help = runTool(t.binary, "--help", tmp.path());
    EXPECT_EQ(help.status, io::kExitDone);
    expectContains(help.out, t.ownOption);
  }
}

TEST(ToolStatus, AnOutputFolderThatIsAFileIsBadInput) {
  TempDir tmp;
  const std::filesystem::path file = tmp.write("a-file", "not a folder\n");
  for (const Tool& t : tools()) {
    if (t.input.empty() || !t.writesOutput) continue;
    SCOPED_TRACE(t.name);
    const ToolRun r = runTool(t.binary, t.before + shellQuoted(t.input) + " " + t.quiet + " --out " + shellQuoted(file), tmp.path());
    EXPECT_EQ(r.status, io::kExitBadInput) << r.err;
    expectContains(r.err, "a-file");
  }
}

}  // namespace
}  // namespace ecm::test
