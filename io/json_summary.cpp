#include "io/json_summary.hpp"

#include "io/atomic_file.hpp"

namespace ecm::io {

void writeJsonSummary(const nlohmann::json& summary, const std::filesystem::path& path, int indent) {
  writeFileAtomically(path, summary.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace ecm::io
