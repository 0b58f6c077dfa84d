#include "io/csv_writer.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "io/checksum.hpp"
#include "io/output_error.hpp"

namespace ecm::io {

namespace {
constexpr std::size_t kBufferSize = 1 << 16;

std::string failure(int err) { return std::strerror(err ? err : EIO); }

std::string headerLine(const std::vector<std::string>& header, const std::filesystem::path& path) {
  if (header.empty()) throw std::invalid_argument("CsvWriter: empty header for " + path.string());
  std::string line;
  for (std::size_t i = 0; i < header.size(); ++i) line += (i ? "," : "") + header[i];
  return line + "\n";
}
}  // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header)
    : path_(path), columns_(header.size()), digest_(kFnv1a64Offset) {
  const std::string line = headerLine(header, path);
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw OutputError(path, failure(errno));
  buffer_.reserve(kBufferSize + 1024);
  append(line);
}

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header, const Resume& at)
    : path_(path), columns_(header.size()), rows_(at.rows), bytes_(at.bytes), digest_(at.digest), committed_(at.bytes) {
  const std::string line = headerLine(header, path);
  auto refuse = [&](const std::string& why) { throw std::runtime_error(path.string() + ": " + why); };
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) refuse("cannot continue it: " + ec.message());
  if (size < at.bytes)
    refuse("it has " + std::to_string(size) + " bytes, fewer than the " + std::to_string(at.bytes) +
           " it had when it was continued from (it was cut or replaced)");
  std::ifstream in(path, std::ios::binary);
  std::string prefix(static_cast<std::size_t>(at.bytes), '\0');
  if (!in.read(prefix.data(), static_cast<std::streamsize>(prefix.size()))) refuse("cannot read it back");
  if (fnv1a64(prefix) != at.digest) refuse("its first " + std::to_string(at.bytes) + " bytes were changed");
  if (prefix.compare(0, line.size(), line) != 0) refuse("its header is not the expected one");
  in.close();
  std::filesystem::resize_file(path, at.bytes, ec);  // rows written after the continuation point
  if (ec) throw OutputError(path, "cannot cut it back to " + std::to_string(at.bytes) + " bytes: " + ec.message());
  file_ = std::fopen(path.c_str(), "ab");
  if (!file_) throw OutputError(path, failure(errno));
  buffer_.reserve(kBufferSize + 1024);
}

CsvWriter::~CsvWriter() {
  if (!file_) return;
  try {
    close();
  } catch (const std::exception& e) {
    if (!failed_) std::cerr << "warning: " << e.what() << '\n';
  }
}

void CsvWriter::append(const std::string& text) {
  buffer_ += text;
  bytes_ += text.size();
  digest_ = fnv1a64(text, digest_);
}

void CsvWriter::row(std::span<const double> values) {
  if (!file_) throw OutputError(path_, failed_ ? "an earlier write failed" : "the file is already closed");
  if (values.size() != columns_)
    throw std::invalid_argument("CsvWriter " + path_.string() + ": row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_) + " columns");
  char buf[32];
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';
    const auto r = std::to_chars(buf, buf + sizeof buf, values[i]);
    line.append(buf, r.ptr);
  }
  line += '\n';
  append(line);
  ++rows_;
  if (buffer_.size() >= kBufferSize) writeBuffer();
}

void CsvWriter::fail(int err) {
  failed_ = true;
  std::FILE* f = file_;
  file_ = nullptr;
  std::fclose(f);  // may try to write what the stream still holds: cut it off below
  std::error_code ec;
  if (std::filesystem::is_regular_file(path_, ec)) std::filesystem::resize_file(path_, committed_, ec);
  throw OutputError(path_, failure(err));
}

void CsvWriter::writeBuffer() {
  if (buffer_.empty()) return;
  errno = 0;
  const std::size_t n = std::fwrite(buffer_.data(), 1, buffer_.size(), file_);
  if (n != buffer_.size()) fail(errno);
  buffer_.clear();
}

void CsvWriter::flush() {
  if (!file_) {
    if (failed_) throw OutputError(path_, "an earlier write failed");
    return;
  }
  writeBuffer();
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_)) fail(errno);
  committed_ = bytes_;
}

void CsvWriter::close() {
  if (!file_) return;
  flush();
  std::FILE* f = file_;
  file_ = nullptr;
  errno = 0;
  if (std::fclose(f) != 0) throw OutputError(path_, failure(errno));
}

}  // namespace ecm::io
