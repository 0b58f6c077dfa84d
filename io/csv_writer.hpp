#pragma once
// Tables of numbers as CSV: one header line, then rows of doubles in shortest round-trip form
// (full precision). Written through a buffer that is flushed at flush() and on destruction;
// every write failure (bad path, full disk) is an OutputError naming the path.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace ecm::io {

class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header);
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

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::size_t columns_;
  std::size_t rows_ = 0;
  bool failed_ = false;  // a write error was already thrown: the destructor stays quiet
  std::string buffer_;
  void writeBuffer();  // hands the buffer to the C stream
};

}  // namespace ecm::io
