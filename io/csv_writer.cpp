#include "io/csv_writer.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "io/output_error.hpp"

namespace ecm::io {

namespace {
constexpr std::size_t kBufferSize = 1 << 16;

std::string failure(int err) { return std::strerror(err ? err : EIO); }
}  // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header)
    : path_(path), columns_(header.size()) {
  if (header.empty()) throw std::invalid_argument("CsvWriter: empty header for " + path.string());
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw OutputError(path, failure(errno));
  std::string line;
  for (std::size_t i = 0; i < header.size(); ++i) line += (i ? "," : "") + header[i];
  buffer_.reserve(kBufferSize + 1024);
  buffer_ = line + "\n";
}

CsvWriter::~CsvWriter() {
  if (!file_) return;
  try {
    close();
  } catch (const std::exception& e) {
    if (!failed_) std::cerr << "warning: " << e.what() << '\n';
  }
}

void CsvWriter::row(std::span<const double> values) {
  if (!file_) throw OutputError(path_, "the file is already closed");
  if (values.size() != columns_)
    throw std::invalid_argument("CsvWriter " + path_.string() + ": row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_) + " columns");
  char buf[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) buffer_ += ',';
    const auto r = std::to_chars(buf, buf + sizeof buf, values[i]);
    buffer_.append(buf, r.ptr);
  }
  buffer_ += '\n';
  ++rows_;
  if (buffer_.size() >= kBufferSize) writeBuffer();
}

void CsvWriter::writeBuffer() {
  if (buffer_.empty()) return;
  errno = 0;
  const std::size_t n = std::fwrite(buffer_.data(), 1, buffer_.size(), file_);
  if (n != buffer_.size()) {
    failed_ = true;
    throw OutputError(path_, failure(errno));
  }
  buffer_.clear();
}

void CsvWriter::flush() {
  if (!file_) return;
  writeBuffer();
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_)) {
    failed_ = true;
    throw OutputError(path_, failure(errno));
  }
}

void CsvWriter::close() {
  if (!file_) return;
  std::FILE* f = file_;
  try {
    flush();
  } catch (...) {
    file_ = nullptr;
    std::fclose(f);
    throw;
  }
  file_ = nullptr;
  errno = 0;
  if (std::fclose(f) != 0) throw OutputError(path_, failure(errno));
}

}  // namespace ecm::io
