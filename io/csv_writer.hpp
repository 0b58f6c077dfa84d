#pragma once
// Tables of numbers as CSV: one header line, then rows of doubles in shortest round-trip form
// (full precision). Written through a buffer that is flushed at flush() and on destruction;
// every write failure (bad path, full disk) is an OutputError naming the path, and the file is
// cut back to what the last successful flush() wrote (no half row at its end).
// A writer can also continue a file it wrote before (Resume: restarts from a checkpoint).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace ecm::io {

class CsvWriter {
 public:
  // Where an earlier writer of the same file stood: bytes() and digest() after its last flush.
  struct Resume {
    std::uint64_t bytes = 0;
    std::uint64_t digest = 0;
    std::size_t rows = 0;
  };

  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header);
  // Continues `path`: its first `at.bytes` bytes must hash to `at.digest` (else std::runtime_error
  // naming the file: it was changed or replaced); anything after them is cut off and the new rows
  // follow. `header` must be the one the file starts with.
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header, const Resume& at);
  ~CsvWriter();  // flushes and closes; a failure here can only be reported on stderr
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // One row; its length must match the header (std::invalid_argument otherwise).
  void row(std::span<const double> values);
  void row(std::initializer_list<double> values) { row(std::span<const double>(values.begin(), values.size())); }
  void flush();  // throws OutputError
  void close();  // flush and close; throws OutputError
  const std::filesystem::path& path() const { return path_; }
  std::size_t rows() const { return rows_; }
  // Everything given so far, header included: its length and FNV-1a 64 hash (io/checksum.hpp).
  // After flush() they describe the file on disk.
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t digest() const { return digest_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::size_t columns_;
  std::size_t rows_ = 0;
  std::uint64_t bytes_ = 0, digest_ = 0;
  std::uint64_t committed_ = 0;  // bytes on disk after the last successful flush
  bool failed_ = false;          // a write error was already thrown: the destructor stays quiet
  std::string buffer_;
  void append(const std::string& text);  // to the buffer, counted in bytes_ and digest_
  void writeBuffer();                    // hands the buffer to the C stream
  [[noreturn]] void fail(int err);       // closes, cuts the file back to committed_, throws
};

}  // namespace ecm::io
