#pragma once
// Whole-file writes that never leave a half-written file behind: write PATH.tmp, then rename.
#include <filesystem>
#include <initializer_list>
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
// The same for a file made of consecutive parts (no copy into one buffer first). The one-text
// form above calls this one with {text}.
void writeFileAtomically(const std::filesystem::path& path, std::initializer_list<std::string_view> parts,
                         Durability d = Durability::Rename);

}  // namespace ecm::io
