// CSV tables: full-precision writing, write failures naming the path, reading measured curves.
#include <gtest/gtest.h>

#include <cstdlib>

#include "io/csv_reader.hpp"
#include "io/csv_writer.hpp"
#include "io/output_error.hpp"
#include "temp_dir.hpp"

namespace ecm::io {
namespace {

using namespace ecm::test;  // expectContains, inputError, readFile, TempDir

TEST(CsvWriter, WritesHeaderAndRowsAtFullPrecision) {
  const TempDir dir;
  const auto path = dir.path() / "t.csv";
  {
    CsvWriter w(path, {"w", "sigma"});
    w.row({0.1 + 0.2, 1.0 / 3.0});
    w.row({1e-300, -2.5});
    w.flush();
    EXPECT_EQ(readFile(path), "w,sigma\n0.30000000000000004,0.3333333333333333\n1e-300,-2.5\n");
    w.row({3.0, 4.0});
    EXPECT_EQ(w.rows(), 3u);
  }  // the destructor flushes the last row
  const CsvTable t = readCsv(path, 2);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.header, (std::vector<std::string>{"w", "sigma"}));
  EXPECT_EQ(t.rows[0][0], 0.1 + 0.2);  // bit-exact round trip
  EXPECT_EQ(t.rows[0][1], 1.0 / 3.0);
  EXPECT_EQ(t.rows[2][1], 4.0);
  EXPECT_EQ(t.lines, (std::vector<int>{2, 3, 4}));
}

TEST(CsvWriter, RowLengthMustMatchTheHeader) {
  const TempDir dir;
  CsvWriter w(dir.path() / "t.csv", {"a", "b"});
  EXPECT_THROW(w.row({1.0}), std::invalid_argument);
}

TEST(CsvWriter, UnwritablePathThrowsNamingIt) {
  const TempDir dir;
  const auto path = dir.path() / "no-such-folder" / "t.csv";
  try {
    CsvWriter w(path, {"a"});
    FAIL() << "no exception for " << path;
  } catch (const OutputError& e) {
    expectContains(e.what(), path.string());
    EXPECT_EQ(e.path, path);
  }
}

TEST(CsvWriter, FullDiskIsDetectedAtFlush) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  CsvWriter w("/dev/full", {"a", "b"});
  w.row({1.0, 2.0});
  try {
    w.flush();
    FAIL() << "writing to /dev/full did not fail";
  } catch (const OutputError& e) {
    expectContains(e.what(), "/dev/full");
  }
}

TEST(CsvWriter, RowsOfAFullDiskAreReportedAtTheLatestAtClose) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  CsvWriter w("/dev/full", {"a", "b"});
  try {
    for (int i = 0; i < 100000; ++i) w.row({1.0 * i, 2.0});  // more than the buffer holds
    w.close();
    FAIL() << "writing to /dev/full did not fail";
  } catch (const OutputError& e) {
    expectContains(e.what(), "cannot write '/dev/full'");
  }
}

// A write that fails (here: beyond the file size limit, as on a full disk) leaves the file as
// the last successful flush() wrote it: whole rows only.
TEST(CsvWriter, FailedWriteCutsTheFileBackToTheLastFlush) {
  const TempDir dir;
  const auto path = dir.path() / "t.csv";
  std::string flushed;
  {
    const test::FileSizeLimit limit(100);
    CsvWriter w(path, {"w", "sigma"});
    try {
      for (int i = 0; i < 100; ++i) {
        w.row({0.1 * i, 1.0 / 3.0});
        w.flush();
        flushed = readFile(path);
      }
      FAIL() << "the size limit did not stop the writer";
    } catch (const OutputError& e) {
      expectContains(e.what(), path.string());
    }
    EXPECT_THROW(w.row({1.0, 2.0}), OutputError);  // and it stays failed
  }
  EXPECT_GT(flushed.size(), 30u);
  EXPECT_EQ(readFile(path), flushed);
  EXPECT_EQ(flushed.back(), '\n');
}

// Resume: a writer continues a file where an earlier one stood (its bytes and digest after a
// flush); rows written after that point are cut off, and the result is what one writer writing
// the kept rows and then the new ones would have written.
TEST(CsvWriter, ResumeContinuesWhereTheRecordedWriterStood) {
  const TempDir dir;
  const auto path = dir.path() / "h.csv", reference = dir.path() / "r.csv";
  CsvWriter::Resume at;
  {
    CsvWriter w(path, {"t", "x"});
    w.row({0.0, 1.0});
    w.row({1.0, 2.0});
    w.flush();
    at = {w.bytes(), w.digest(), w.rows()};
    w.row({2.0, 3.0});  // after the recorded point: cut off by the resume
  }
  {
    CsvWriter w(path, {"t", "x"}, at);
    EXPECT_EQ(w.rows(), 2u);
    w.row({2.0, 30.0});
  }
  std::uint64_t digest = 0;
  {
    CsvWriter r(reference, {"t", "x"});
    r.row({0.0, 1.0});
    r.row({1.0, 2.0});
    r.row({2.0, 30.0});
    r.flush();
    digest = r.digest();
  }
  EXPECT_EQ(readFile(path), "t,x\n0,1\n1,2\n2,30\n");
  EXPECT_EQ(readFile(path), readFile(reference));
  {
    CsvWriter::Resume end{std::filesystem::file_size(path), digest, 3};
    EXPECT_NO_THROW(CsvWriter(path, {"t", "x"}, end));
  }
  // A changed prefix, a shorter file or another header are refused, and the file is left alone.
  const std::string before = readFile(path);
  EXPECT_THROW(CsvWriter(path, {"t", "x"}, CsvWriter::Resume{at.bytes, at.digest ^ 1, 2}), std::runtime_error);
  EXPECT_THROW(CsvWriter(path, {"t", "x"}, CsvWriter::Resume{1000, at.digest, 2}), std::runtime_error);
  EXPECT_THROW(CsvWriter(path, {"t", "y"}, at), std::runtime_error);
  EXPECT_THROW(CsvWriter(dir.path() / "none.csv", {"t", "x"}, at), std::runtime_error);
  EXPECT_EQ(readFile(path), before);
}

TEST(CsvReader, SkipsCommentsAndReadsWithoutHeader) {
  const TempDir dir;
  const auto path = dir.write("m.csv", "# measured\n\n0, 3.0\n0.01,2.5\n+0.02 , 1e0\n");
  const CsvTable t = readCsv(path, 2);
  EXPECT_TRUE(t.header.empty());
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[2][0], 0.02);
  EXPECT_EQ(t.lines[0], 3);
}

TEST(CsvReader, BadCellsAndRaggedRowsNameTheLine) {
  const TempDir dir;
  const auto bad = dir.write("bad.csv", "w,sigma\n0,3\n0.1,x\n");
  const InputError e = inputError([&] { readCsv(bad, 2); });
  EXPECT_EQ(e.file, bad.string());
  EXPECT_EQ(e.line, 3);
  expectContains(e.what(), "'x' is not a number");
  const auto ragged = dir.write("r.csv", "0,3\n0.1,2,7\n");
  const InputError r = inputError([&] { readCsv(ragged, 2); });
  EXPECT_EQ(r.line, 2);
  expectContains(r.what(), "expected 2 numbers, got 3");
  const InputError nan = inputError([&] { readCsv(dir.write("n.csv", "0,nan\n"), 2); });
  expectContains(nan.what(), "not finite");
  const InputError missing = inputError([&] { readCsv(dir.path() / "none.csv"); });
  expectContains(missing.what(), "none.csv:1: cannot open file");
}

}  // namespace
}  // namespace ecm::io
