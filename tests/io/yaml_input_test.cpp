// The validating YAML reader: every rejection names FILE:LINE, the key and the reason.
#include "io/yaml_input.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "io/utf8.hpp"
#include "temp_dir.hpp"

namespace ecm::io {
namespace {

using namespace ecm::test;  // inputError, TempDir, expectContains

// Checks file, 1-based line and that the message starts with "FILE:LINE: " and names `needle`.
void expectAt(const InputError& e, const std::string& file, int line, const std::string& needle) {
  EXPECT_EQ(e.file, file);
  EXPECT_EQ(e.line, line) << e.what();
  EXPECT_EQ(std::string(e.what()).rfind(file + ":" + std::to_string(line) + ": ", 0), 0u) << e.what();
  expectContains(e.what(), needle);
}

constexpr const char* kSample =
    "# comment line 1\n"      // 1
    "youngs_modulus: 32000\n" // 2
    "poisson_ratio: 0.2\n"    // 3
    "steps: 10\n"             // 4
    "verbose: true\n"         // 5
    "name: den\n"             // 6
    "load:\n"                 // 7
    "  kind: ramp\n"          // 8
    "  peak: 1.5\n"           // 9
    "origin: [1, 2]\n";       // 10

TEST(YamlInput, ReadsTypedValuesAndFinishesCleanly) {
  const YamlMap m = parseYaml(kSample, "sample.yaml");
  EXPECT_EQ(m.get<double>("youngs_modulus", Range::positive()), 32000.0);
  EXPECT_EQ(m.get<double>("poisson_ratio"), 0.2);
  EXPECT_EQ(m.get<int>("steps", Range::closed(1, 10)), 10);
  EXPECT_TRUE(m.get<bool>("verbose"));
  EXPECT_EQ(m.get<std::string>("name"), "den");
  const YamlMap load = m.child("load");
  EXPECT_EQ(load.getEnum("kind", {"ramp", "step"}), "ramp");
  EXPECT_EQ(load.get<double>("peak"), 1.5);
  EXPECT_EQ(m.getVector("origin", 2), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(m.getOr<double>("absent", 7.0), 7.0);
  EXPECT_EQ(m.getOr<int>("steps", 3), 10);
  EXPECT_NO_THROW(m.finish());
}

TEST(YamlInput, UnknownKeyNamesLineAndAllowedKeys) {
  const YamlMap m = parseYaml("a: 1\nb: 2\n\nfoo: 3\n", "u.yaml");
  m.get<double>("a");
  m.getOr<double>("b", 0.0);
  m.has("c");
  const InputError e = inputError([&] { m.finish(); });
  expectAt(e, "u.yaml", 4, "unknown key 'foo'");
  expectContains(e.what(), "(allowed: a, b, c)");
}

TEST(YamlInput, UnknownKeyInsideChildMapIsFoundFromTheRoot) {
  const YamlMap m = parseYaml(kSample, "sample.yaml");
  const YamlMap load = m.child("load");
  load.get<std::string>("kind");
  for (const char* k : {"youngs_modulus", "poisson_ratio", "steps", "verbose", "name", "origin"}) m.has(k);
  const InputError e = inputError([&] { m.finish(); });
  expectAt(e, "sample.yaml", 9, "unknown key 'peak' in 'load'");
}

TEST(YamlInput, MissingKeyNamesTheKeyAndTheMapLine) {
  const YamlMap m = parseYaml(kSample, "sample.yaml");
  expectAt(inputError([&] { m.get<double>("tensile_strength"); }), "sample.yaml", 2, "missing key 'tensile_strength'");
  const YamlMap load = m.child("load");
  expectAt(inputError([&] { load.get<double>("duration"); }), "sample.yaml", 7, "missing key 'load.duration'");
}

enum class Colour { Red, Green };
constexpr const char* toString(Colour c) { return c == Colour::Red ? "red" : "green"; }

TEST(YamlInput, AnEnumIsReadByItsSpellingsWithTheCallersDefault) {
  const YamlMap m = parseYaml("a: green\nb: blue\n", "t.yaml");
  EXPECT_EQ(m.getEnumOr("a", std::array{Colour::Red, Colour::Green}, Colour::Red), Colour::Green);
  EXPECT_EQ(m.getEnumOr("absent", std::array{Colour::Red, Colour::Green}, Colour::Green), Colour::Green);
  expectAt(inputError([&] { m.getEnumOr("b", std::array{Colour::Red, Colour::Green}, Colour::Red); }), "t.yaml", 2,
           "'blue' is not one of: red, green");
}

TEST(YamlInput, StringWhereANumberIsExpected) {
  const YamlMap m = parseYaml("a: 1\nb: abc\nc: '3.0'\n", "t.yaml");
  const InputError e = inputError([&] { m.get<double>("b"); });
  expectAt(e, "t.yaml", 2, "key 'b'");
  expectContains(e.what(), "expected a number");
  // A quoted number is a string in YAML.
  expectAt(inputError([&] { m.get<double>("c"); }), "t.yaml", 3, "expected a number, got the string '3.0'");
}

TEST(YamlInput, AStringThatIsNotUtf8TextIsRefusedWithItsLine) {
  // Found by fuzz/fuzz_point_scene.cpp: a scene name with stray bytes (0x9C) ran, and then
  // summary.json could not be written. UTF-8 text (here e-acute and a CJK character) is read.
  const YamlMap m = parseYaml("a: caf\xc3\xa9 \xe6\xb0\xb4\nb: band\x9c\x9cname\n", "t.yaml");
  EXPECT_EQ(m.get<std::string>("a"), "caf\xc3\xa9 \xe6\xb0\xb4");
  const InputError e = inputError([&] { m.get<std::string>("b"); });
  expectAt(e, "t.yaml", 2, "key 'b': is not valid UTF-8 text (a stray byte at byte 5)");
}

TEST(YamlInput, Utf8CheckFollowsRfc3629) {
  EXPECT_EQ(firstInvalidUtf8("plain ascii"), std::nullopt);
  EXPECT_EQ(firstInvalidUtf8("\xf0\x9f\x98\x80"), std::nullopt);      // U+1F600
  EXPECT_EQ(firstInvalidUtf8("ab\xc0\xaf"), 2u);                     // an overlong '/'
  EXPECT_EQ(firstInvalidUtf8("\xed\xa0\x80"), 0u);                   // a surrogate, U+D800
  EXPECT_EQ(firstInvalidUtf8("\xf4\x90\x80\x80"), 0u);               // above U+10FFFF
  EXPECT_EQ(firstInvalidUtf8("x\xe6\xb0"), 1u);                      // cut short
}

TEST(YamlInput, MapOrSequenceWhereAScalarIsExpected) {
  const YamlMap m = parseYaml("a: 1\nb:\n  c: 2\nd: [1, 2]\n", "t.yaml");
  expectAt(inputError([&] { m.get<double>("b"); }), "t.yaml", 2, "key 'b': expected a number, got a map");
  expectAt(inputError([&] { m.get<std::string>("d"); }), "t.yaml", 4, "key 'd': expected a string, got a sequence");
  expectAt(inputError([&] { m.child("a"); }), "t.yaml", 1, "key 'a': expected a map");
}

TEST(YamlInput, FractionWhereAnIntegerIsExpected) {
  const YamlMap m = parseYaml("steps: 1.5\nother: 2\n", "t.yaml");
  expectAt(inputError([&] { m.get<int>("steps"); }), "t.yaml", 1, "key 'steps': expected an integer, got '1.5'");
}

TEST(YamlInput, NonFiniteNumbersAreRejected) {
  const YamlMap m = parseYaml("a: .nan\nb: .inf\nc: -.Inf\nd: nan\n", "t.yaml");
  int line = 1;
  for (const char* k : {"a", "b", "c", "d"}) {
    const InputError e = inputError([&] { m.get<double>(k); });
    expectAt(e, "t.yaml", line++, "key '" + std::string(k) + "': expected a finite number");
  }
}

TEST(YamlInput, OutOfRangeShowsTheInterval) {
  const YamlMap m = parseYaml("n: 0.5\nE: -3\nf: 0\ng: 1\nsteps: 0\n", "r.yaml");
  const InputError e = inputError([&] { m.get<double>("n", Range::open(0.0, 0.5)); });
  expectAt(e, "r.yaml", 1, "key 'n': value 0.5 is outside the allowed range (0, 0.5)");
  expectAt(inputError([&] { m.get<double>("E", Range::positive()); }), "r.yaml", 2, "(0, inf)");
  EXPECT_EQ(m.get<double>("f", Range::closed(0.0, 1.0)), 0.0);  // closed bounds include the ends
  EXPECT_EQ(m.get<double>("g", Range::closed(0.0, 1.0)), 1.0);
  expectAt(inputError([&] { m.get<double>("f", Range::open(0.0, 1.0)); }), "r.yaml", 3, "(0, 1)");
  expectAt(inputError([&] { m.get<int>("steps", Range{1, 100, true, true}); }), "r.yaml", 5, "[1, 100]");
  EXPECT_EQ(Range::nonNegative().str(), "[0, inf)");
}

TEST(YamlInput, EnumNamesTheAllowedValues) {
  const YamlMap m = parseYaml("x: 0\nmodel: enriched_mpm\n", "e.yaml");
  const InputError e = inputError([&] { m.getEnum("model", {"enriched", "smeared_crack"}); });
  expectAt(e, "e.yaml", 2, "key 'model': 'enriched_mpm' is not one of: enriched, smeared_crack");
}

TEST(YamlInput, VectorsCheckLengthTypeAndRangeOfEachEntry) {
  const YamlMap m = parseYaml("a: [1, 2, 3]\nb:\n  - 1\n  - x\nc: [1, -1]\n", "v.yaml");
  expectAt(inputError([&] { m.getVector("a", 2); }), "v.yaml", 1, "key 'a': expected 2 numbers, got 3");
  expectAt(inputError([&] { m.getVector("b", 2); }), "v.yaml", 4, "key 'b[1]': expected a number");
  expectAt(inputError([&] { m.getVector("c", 2, Range::positive()); }), "v.yaml", 5, "key 'c[1]'");
  EXPECT_EQ(m.getVector("a", 0).size(), 3u);
}

TEST(YamlInput, SequencesOfMapsAndScalars) {
  const YamlMap m = parseYaml("items:\n  - x: 1\n  - x: 2\n    y: 3\nnames: [a, b]\n", "s.yaml");
  const std::vector<YamlMap> items = m.sequence("items");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[1].get<double>("x"), 2.0);
  items[0].get<double>("x");
  EXPECT_EQ(m.scalarSequence<std::string>("names"), (std::vector<std::string>{"a", "b"}));
  const InputError e = inputError([&] { m.finish(); });
  expectAt(e, "s.yaml", 4, "unknown key 'y' in 'items[1]'");
}

TEST(YamlInput, NullValuesDuplicatesBooleansAndRejectedKeys) {
  const YamlMap m = parseYaml("a:\nb: yes\nc: 2\n", "n.yaml");
  expectAt(inputError([&] { m.get<double>("a"); }), "n.yaml", 1, "key 'a': has no value");
  expectAt(inputError([&] { m.get<bool>("b"); }), "n.yaml", 2, "expected true or false");
  expectAt(inputError([&] { m.reject("c", "is not used here"); }), "n.yaml", 3, "key 'c': is not used here");
  expectAt(inputError([] { parseYaml("a: 1\nb: 2\na: 3\n", "d.yaml"); }), "d.yaml", 3, "duplicate key 'a'");
}

TEST(YamlInput, InvalidYamlReportsTheParserLine) {
  const TempDir dir;
  const auto path = dir.write("bad.yaml", "a: 1\nb: [1, 2\nc: 3\n");
  const InputError e = inputError([&] { loadYamlFile(path); });
  EXPECT_EQ(e.file, path.string());
  EXPECT_GE(e.line, 2);
  EXPECT_LE(e.line, 3);
  expectContains(e.what(), "invalid YAML");
  expectAt(inputError([] { parseYaml("a: 1\n  b: 2\n", "i.yaml"); }), "i.yaml", 2, "invalid YAML");
  expectAt(inputError([] { parseYaml("- 1\n- 2\n", "seq.yaml"); }), "seq.yaml", 1, "the top level: expected a map");
  expectAt(inputError([] { parseYaml("# only a comment\n", "empty.yaml"); }), "empty.yaml", 1, "empty");
}

TEST(YamlInput, MissingFileIsReportedWithItsName) {
  const TempDir dir;
  const auto path = dir.path() / "nope.yaml";
  const InputError e = inputError([&] { loadYamlFile(path); });
  expectAt(e, path.string(), 1, "does not exist");
}

TEST(YamlInput, FileMapsKnowTheirFolder) {
  const TempDir dir;
  const auto path = dir.write("sub/in.yaml", "a: 1\n");
  const YamlMap m = loadYamlFile(path);
  EXPECT_EQ(m.directory(), path.parent_path());
  EXPECT_EQ(m.get<double>("a"), 1.0);
}

}  // namespace
}  // namespace ecm::io
