#pragma once
// Run summaries as JSON, written atomically (FILE.tmp, then rename): a reader never sees half a file.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace ecm::io {

// Throws OutputError naming the path. Non-finite numbers are written as null (JSON has no NaN).
void writeJsonSummary(const nlohmann::json& summary, const std::filesystem::path& path, int indent = 2);

}  // namespace ecm::io
