// CSV tables: full-precision writing, write failures naming the path, reading measured curves.
#include <gtest/gtest.h>

#include <cstdlib>

#include "io/csv_reader.hpp"
#include "io/csv_writer.hpp"
#include "io/output_error.hpp"
#include "temp_dir.hpp"

namespace ecm::io {
namespace {

using test::expectContains;
using test::inputError;
using test::readFile;
using test::TempDir;

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
