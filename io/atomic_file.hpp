#pragma once
// Whole-file writes that never leave a half-written file behind: write PATH.tmp, then rename.
#include <filesystem>
#include <string_view>

namespace ecm::io {

// Throws OutputError naming the path when any step fails (the temporary file is removed).
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace ecm::io
