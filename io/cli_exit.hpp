#pragma once
// The exit status of every tool (ecm-point, ecm-calibrate, ecm-mpm, ecm-rve, ecm-study):
//   0 done;
//   1 the run failed or stopped early, outputs so far kept (a simulation failure, a point that
//     did not converge, a computation without a result, an output file that could not be
//     written once the run had begun);
//   2 bad input: a missing or unreadable file, an unknown key, a wrong type, a value out of
//     range, a bad command line, an output folder that cannot be used;
//   3 stopped on request with a checkpoint (ecm-mpm: a signal or --max-steps): resume it;
//   10-20 (ecm-mpm) the run failed, outputs so far kept, one status per failure kind (the table of
//     kinds, names and statuses: mpm/core/errors.cpp; summary.json's failure.kind names it).
// Free of CLI11: each main parses its command line through io/command_line.hpp, which passes
// app.exit(e) to commandLineStatus.
// Every error message a tool prints has one form, errorLine(): "ecm-mpm: error: REASON" (an
// input's reason is "FILE:LINE: reason"); CLI11's own messages take it through
// app.failure_message(...).
#include <cstdio>
#include <string>
#include <string_view>

namespace ecm::io {

inline constexpr int kExitDone = 0, kExitRunFailed = 1, kExitBadInput = 2, kExitStopped = 3;
// The first and last of ecm-mpm's failure statuses: a script tells a failed run by the range.
inline constexpr int kExitFirstFailureKind = 10, kExitLastFailureKind = 20;

// The status of a command line CLI11 refused or answered: CLI11's own code (what app.exit(e)
// returns, after printing the message on stderr or the help on stdout) is 0 for --help and
// non-zero for every error (105 for a missing file of CLI::ExistingFile, 106 for a missing
// argument, ...); every error is bad input.
constexpr int commandLineStatus(int cli11ExitCode) { return cli11ExitCode == 0 ? kExitDone : kExitBadInput; }

// "TOOL: error: MESSAGE\n".
inline std::string errorLine(std::string_view tool, std::string_view message) {
  return std::string(tool) + ": error: " + std::string(message) + "\n";
}
inline void printError(std::string_view tool, std::string_view message) {
  std::fputs(errorLine(tool, message).c_str(), stderr);
}

}  // namespace ecm::io
