#pragma once
// Every tool's command line parsed the one way (io/cli_exit.hpp): CLI11's messages in the tools'
// error form, "TOOL: error: REASON" and the help hint; --help exits 0, a bad command line 2.
// Included by the tools' mains only: the io library itself does not use CLI11.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "io/cli_exit.hpp"

namespace ecm::io {

// Parses argv into app. The exit status to end the tool with now (--help answered, or a bad
// command line reported), or nullopt to go on.
inline std::optional<int> parseCommandLine(CLI::App& app, const std::string& tool, int argc, char** argv) {
  app.failure_message([tool](const CLI::App*, const CLI::Error& e) {
    return errorLine(tool, e.what()) + "Run with --help for more information.\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return commandLineStatus(app.exit(e));
  }
  return std::nullopt;
}

}  // namespace ecm::io
