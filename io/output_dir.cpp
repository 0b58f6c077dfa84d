#include "io/output_dir.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "io/output_error.hpp"

namespace ecm::io {

std::filesystem::path prepareOutputDir(const std::filesystem::path& dir) {
  if (dir.empty()) throw OutputError(dir, "empty output folder name");
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw OutputError(dir, "it exists and is not a folder");
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(dir, "cannot create the output folder: " + ec.message());
  const std::filesystem::path probe = dir / (".ecm-write-probe-" + std::to_string(::getpid()));
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) throw OutputError(dir, std::string("the output folder is not writable: ") + std::strerror(errno));
  const bool ok = std::fputs("probe\n", f) >= 0 && std::fflush(f) == 0;
  const int err = errno;
  std::fclose(f);
  std::filesystem::remove(probe, ec);
  if (!ok) throw OutputError(dir, std::string("the output folder is not writable: ") + std::strerror(err ? err : EIO));
  if (ec) throw OutputError(dir, "cannot remove the probe file " + probe.filename().string() + ": " + ec.message());
  return dir;
}

}  // namespace ecm::io
