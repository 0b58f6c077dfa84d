// Materials in YAML: the paper's data files, references, rejections and write-then-read.
#include "io/material_yaml.hpp"

#include <gtest/gtest.h>

#include "temp_dir.hpp"

namespace ecm::io {
namespace {

using namespace ecm::test;  // expectContains, inputError, readFile, TempDir

const std::filesystem::path kData = std::filesystem::path(ECM_SOURCE_DIR) / "data";

TEST(MaterialYaml, DenConcreteHasThePaperValues) {
  const MaterialParams p = loadMaterialFile(kData / "materials" / "den-concrete.yaml");
  EXPECT_EQ(p.name, "den-concrete");
  EXPECT_EQ(p.model, ModelKind::Enriched);
  EXPECT_EQ(p.elastic.hypothesis, Hypothesis::PlaneStress);
  EXPECT_EQ(p.elastic.youngsModulus, 32000.0);
  EXPECT_EQ(p.elastic.poissonRatio, 0.2);
  EXPECT_EQ(p.density, 2.4e-9);
  EXPECT_EQ(p.tensileStrength, 3.0);
  EXPECT_EQ(p.softeningModulus, 8.184);
  EXPECT_EQ(p.softeningExponent, 0.128);
  EXPECT_EQ(p.bandWidth, 0.05);
  EXPECT_EQ(p.fractureEnergy, 0.11);
  EXPECT_EQ(p.regularisedForSize, 0.0);
}

TEST(MaterialYaml, RvePhasesHaveTable1Values) {
  struct Phase {
    const char* file;
    double e, ft, ep;
  };
  for (const Phase& ph : {Phase{"rve-inclusion.yaml", 45000, 3.0, 10}, Phase{"rve-matrix.yaml", 30000, 2.0, 10},
                          Phase{"rve-itz.yaml", 30000, 1.5, 20}}) {
    SCOPED_TRACE(ph.file);
    const MaterialParams p = loadMaterialFile(kData / "materials" / ph.file);
    EXPECT_EQ(p.model, ModelKind::Enriched);
    EXPECT_EQ(p.elastic.youngsModulus, ph.e);
    EXPECT_EQ(p.elastic.poissonRatio, 0.2);
    EXPECT_EQ(p.tensileStrength, ph.ft);
    EXPECT_EQ(p.softeningModulus, ph.ep);
    EXPECT_EQ(p.softeningExponent, 0.179);
    EXPECT_EQ(p.bandWidth, 0.005);
    EXPECT_EQ(p.density, 2.4e-9);
  }
}

TEST(MaterialYaml, FileReferenceResolvesBesideTheReferrerThenInTheDataDir) {
  const TempDir dir;
  const auto scene = dir.write("scene.yaml", "material:\n  file: den-concrete.yaml\n");
  const YamlMap root = loadYamlFile(scene);
  EXPECT_EQ(readMaterial(root.child("material"), kData).softeningModulus, 8.184);  // from data/materials
  EXPECT_NO_THROW(root.finish());

  std::string local = readFile(kData / "materials" / "den-concrete.yaml");
  local.replace(local.find("32000"), 5, "31000");
  dir.write("den-concrete.yaml", local);
  EXPECT_EQ(readMaterial(loadYamlFile(scene).child("material"), kData).elastic.youngsModulus, 31000.0);
}

TEST(MaterialYaml, MissingReferenceListsWhereItLooked) {
  const TempDir dir;
  const auto scene = dir.write("scene.yaml", "steps: 3\nmaterial:\n  file: granite.yaml\n");
  const InputError e = inputError([&] { readMaterial(loadYamlFile(scene).child("material"), kData); });
  EXPECT_EQ(e.file, scene.string());
  EXPECT_EQ(e.line, 3);
  expectContains(e.what(), "key 'material.file': material file 'granite.yaml' not found");
  expectContains(e.what(), (kData / "materials" / "granite.yaml").string());
}

TEST(MaterialYaml, FileReferenceStandsAlone) {
  const TempDir dir;
  const auto scene = dir.write("scene.yaml", "material:\n  file: den-concrete.yaml\n  youngs_modulus: 1\n");
  const InputError e = inputError([&] { readMaterial(loadYamlFile(scene).child("material"), kData); });
  EXPECT_EQ(e.line, 3);
  expectContains(e.what(), "unknown key 'youngs_modulus' in 'material' (allowed: file)");
}

constexpr const char* kElastic =
    "name: steel\n"               // 1
    "model: linear_elastic\n"     // 2
    "hypothesis: plane_strain\n"  // 3
    "youngs_modulus: 200000\n"    // 4
    "poisson_ratio: 0.3\n";       // 5

TEST(MaterialYaml, KeysAModelDoesNotUseAreRefused) {
  const YamlMap ok = parseYaml(kElastic, "steel.yaml");
  const MaterialParams p = readMaterial(ok);
  EXPECT_EQ(p.model, ModelKind::LinearElastic);
  EXPECT_EQ(p.elastic.hypothesis, Hypothesis::PlaneStrain);
  const InputError e = inputError([] { readMaterial(parseYaml(std::string(kElastic) + "band_width: 0.05\n", "steel.yaml")); });
  EXPECT_EQ(e.line, 6);
  expectContains(e.what(), "key 'band_width': is not used by model linear_elastic");
}

constexpr const char* kEnriched =
    "name: c\n"                   // 1
    "model: enriched\n"           // 2
    "hypothesis: plane_stress\n"  // 3
    "youngs_modulus: 32000\n"     // 4
    "poisson_ratio: 0.2\n"        // 5
    "tensile_strength: 3.0\n"     // 6
    "softening_modulus: 8.184\n"  // 7
    "softening_exponent: 0.128\n";// 8

TEST(MaterialYaml, KeysAModelNeedsAreRequired) {
  const InputError e = inputError([] { readMaterial(parseYaml(kEnriched, "c.yaml")); });
  EXPECT_EQ(e.file, "c.yaml");
  EXPECT_EQ(e.line, 1);
  expectContains(e.what(), "missing key 'band_width'");
}

TEST(MaterialYaml, RangeErrorsOfValidateComeBackWithTheKeyLine) {
  std::string text = std::string(kEnriched) + "band_width: 0.05\n";
  text.replace(text.find("0.128"), 5, "0.6");
  const InputError e = inputError([&] { readMaterial(parseYaml(text, "c.yaml")); });
  EXPECT_EQ(e.line, 8);
  expectContains(e.what(), "softening_exponent");
  expectContains(e.what(), "(0, 0.5)");

  std::string nu = std::string(kEnriched) + "band_width: 0.05\n";
  nu.replace(nu.find("0.2\n"), 3, "0.5");
  const InputError en = inputError([&] { readMaterial(parseYaml(nu, "c.yaml")); });
  EXPECT_EQ(en.line, 5);
  expectContains(en.what(), "poisson_ratio");
}

TEST(MaterialYaml, AnErrorWithoutAQuotedKeyStillComesBackAtItsKeysLine) {
  // second_band on a model without a band: the material library names the key as data
  // (ParameterError::key), so the reader reports second_band's line (9), not the map's (1).
  std::string text = std::string(kEnriched) + "second_band: orthogonal\n";
  text.replace(text.find("enriched"), 8, "smeared_crack");
  const InputError e = inputError([&] { readMaterial(parseYaml(text, "s.yaml")); });
  EXPECT_EQ(e.line, 9) << e.what();
  expectContains(e.what(), "second_band");
}

TEST(MaterialYaml, SmearedRegularisationReplacesTheSofteningModulus) {
  std::string text = std::string(kEnriched) + "regularised_for_size: 100\nfracture_energy: 0.11\n";
  text.replace(text.find("enriched"), 8, "smeared_crack");
  const InputError e = inputError([&] { readMaterial(parseYaml(text, "s.yaml")); });
  EXPECT_EQ(e.line, 7);
  expectContains(e.what(), "key 'softening_modulus': is replaced by the crack-band value");
  text.erase(text.find("softening_modulus"), std::string("softening_modulus: 8.184\n").size());
  const MaterialParams p = readMaterial(parseYaml(text, "s.yaml"));
  EXPECT_EQ(p.regularisedForSize, 100.0);
  EXPECT_EQ(p.fractureEnergy, 0.11);
}

void expectSame(const MaterialParams& a, const MaterialParams& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.elastic.hypothesis, b.elastic.hypothesis);
  EXPECT_EQ(a.elastic.youngsModulus, b.elastic.youngsModulus);
  EXPECT_EQ(a.elastic.poissonRatio, b.elastic.poissonRatio);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.tensileStrength, b.tensileStrength);
  EXPECT_EQ(a.softeningModulus, b.softeningModulus);
  EXPECT_EQ(a.softeningExponent, b.softeningExponent);
  EXPECT_EQ(a.bandWidth, b.bandWidth);
  EXPECT_EQ(a.fractureEnergy, b.fractureEnergy);
  EXPECT_EQ(a.regularisedForSize, b.regularisedForSize);
}

TEST(MaterialYaml, WriteThenReadGivesTheSameMaterialBitForBit) {
  const TempDir dir;
  MaterialParams p;
  p.name = "calibrated: concrete #2";  // needs quoting in YAML
  p.model = ModelKind::Enriched;
  p.elastic = {32000.0 / 3.0, 0.1 + 0.1, Hypothesis::PlaneStrain};
  p.density = 2.4e-9;
  p.tensileStrength = 3.0000000000000004;
  p.softeningModulus = 8.183989765432101;
  p.softeningExponent = 0.128;
  p.bandWidth = 0.05;
  p.fractureEnergy = 0.11;
  writeMaterialFile(p, dir.path() / "m.yaml");
  expectSame(loadMaterialFile(dir.path() / "m.yaml"), p);

  MaterialParams s = p;
  s.name = "smeared";
  s.model = ModelKind::SmearedCrack;
  s.softeningModulus = 0.0;
  s.bandWidth = 0.0;
  s.regularisedForSize = 25.0;
  writeMaterialFile(s, dir.path() / "s.yaml");
  expectSame(loadMaterialFile(dir.path() / "s.yaml"), s);

  MaterialParams e;
  e.name = "elastic";
  e.model = ModelKind::LinearElastic;
  e.elastic = {70000.0, 0.33, Hypothesis::PlaneStress};
  writeMaterialFile(e, dir.path() / "e.yaml");
  expectSame(loadMaterialFile(dir.path() / "e.yaml"), e);
  expectContains(readFile(dir.path() / "e.yaml"), "Units: mm, N, MPa, tonne");
}

}  // namespace
}  // namespace ecm::io
