#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "io/output_error.hpp"

namespace ecm::io {

namespace {

// fsync of a folder, so that a rename inside it is on disk. Best effort: some file systems
// refuse to sync folders (EINVAL), which says nothing about the file itself.
void syncFolder(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view text, Durability d) {
  writeFileAtomically(path, {text}, d);
}

void writeFileAtomically(const std::filesystem::path& path, std::initializer_list<std::string_view> parts, Durability d) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw OutputError(path, std::strerror(errno));
  errno = 0;
  bool written = true;
  for (const std::string_view text : parts) written = written && std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool flushed = written && std::fflush(f) == 0;
  const bool synced = flushed && (d == Durability::Rename || ::fsync(::fileno(f)) == 0);
  const int err = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !synced || !closed) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw OutputError(path, std::strerror(err ? err : EIO));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw OutputError(path, "rename from " + tmp.filename().string() + " failed: " + ec.message());
  }
  if (d == Durability::Sync) syncFolder(path.parent_path());
}

}  // namespace ecm::io
