#pragma once
// Runs one of the tools as a user does (std::system, the binary's path from a compile definition
// such as ECM_MPM) and keeps its exit status, stdout and stderr. The exit statuses are those of
// io/cli_exit.hpp: 0 done, 1 run failed or stopped early, 2 bad input, 3 stopped with a checkpoint,
// 10-20 an ecm-mpm run failed (one status per failure kind).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/cli_exit.hpp"

namespace ecm::test {

struct ToolRun {
  int status = -1;  // the exit status; -1 when the tool did not exit (killed by a signal)
  std::string out, err;
};

// A path as one shell word (built by appending: GCC 12 warns falsely, -Wrestrict, on "'" + s).
inline std::string shellQuoted(const std::filesystem::path& p) {
  std::string word(1, '\'');
  word += p.string();
  word += '\'';
  return word;
}

// Runs `binary args` (args already shell words) with stdout and stderr caught in files of `scratch`.
inline ToolRun runTool(const std::string& binary, const std::string& args, const std::filesystem::path& scratch) {
  const auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::filesystem::path out = scratch / "tool-stdout", err = scratch / "tool-stderr";
  const std::string cmd = shellQuoted(binary) + " " + args + " > " + shellQuoted(out) + " 2> " + shellQuoted(err);
  const int status = std::system(cmd.c_str());
  ToolRun r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read(out);
  r.err = read(err);
  return r;
}

}  // namespace ecm::test
