#pragma once
// Whole-file writes that never leave a half-written file behind: write PATH.tmp, then rename.
#include <filesystem>
#include <string_view>

namespace ecm::io {

enum class Durability {
  Rename,  // atomic for readers: the old or the new file, never half of one
  Sync,    // also survives a crash of the machine: PATH.tmp is fsync'ed before the rename and the
           // folder after it (checkpoints)
};

// Throws OutputError naming the path when any step fails (the temporary file is removed and an
// existing PATH is left as it was).
void writeFileAtomically(const std::filesystem::path& path, std::string_view text, Durability d = Durability::Rename);

}  // namespace ecm::io
