#pragma once
// The output folder of a run: created with its parents and proven writable before any work starts.
#include <filesystem>

namespace ecm::io {

// Creates `dir` (and parents) if needed, then writes and removes a probe file in it.
// Throws OutputError naming the folder when it cannot be created or written. Returns `dir`.
std::filesystem::path prepareOutputDir(const std::filesystem::path& dir);

}  // namespace ecm::io
