#pragma once
// The error every writer of io/ throws when a file or folder cannot be written: it names the path.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace ecm::io {

struct OutputError : std::runtime_error {
  OutputError(const std::filesystem::path& where, const std::string& reason)
      : std::runtime_error("cannot write '" + where.string() + "': " + reason), path(where), reason(reason) {}
  std::filesystem::path path;
  std::string reason;
};

}  // namespace ecm::io
