// The PROPS and the input-deck card for a material of ecm's (umat/umat_props.hpp): PROPS read
// back by the UMAT give the material they were written from, the card declares as many
// constants as it lists (CalculiX crashes on fewer), one *MATERIAL per element size, and what a
// code cannot take is refused with the reason.
#include "umat/umat_props.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "umat/umat_layout.hpp"

namespace ecm::umat {
namespace {

MaterialParams concrete() {
  return {.name = "den-concrete", .model = ModelKind::Enriched, .elastic = {32000.0, 0.2, Hypothesis::PlaneStress},
          .density = 2.4e-9, .tensileStrength = 3.0, .softeningModulus = 8.184, .softeningExponent = 0.128,
          .bandWidth = 0.05};
}

// The constants of every *USER MATERIAL in a card, with its declared count.
struct CardMaterial {
  std::string name;
  int declared = 0;
  std::vector<double> constants;
};
std::vector<CardMaterial> readCard(const std::string& card) {
  std::vector<CardMaterial> out;
  std::istringstream in(card);
  std::string line;
  bool data = false;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    std::smatch m;
    if (std::regex_search(line, m, std::regex("^\\*MATERIAL, NAME=(\\S+)"))) {
      out.push_back({m[1], 0, {}});
      data = false;
    } else if (std::regex_search(line, m, std::regex("^\\*USER MATERIAL, CONSTANTS=(\\d+)"))) {
      out.back().declared = std::stoi(m[1]);
      data = true;
    } else if (line.rfind("*", 0) == 0) {
      data = false;
    } else if (data) {
      std::istringstream values(line);
      std::string v;
      while (std::getline(values, v, ',')) out.back().constants.push_back(std::stod(v));
      EXPECT_LE(std::count(line.begin(), line.end(), ',') + 1, 8) << "at most eight constants a line: " << line;
    }
  }
  return out;
}

TEST(UmatProps, PropsHoldTheMaterialInTheUmatsLayout) {
  // The layout of umat/umat_layout.hpp (docs/fe-codes.md, PROPS); the UMAT reading these PROPS
  // back is tested by ecm-point --umat against the 3D point (tests/driver/umat_driver_test.cpp).
  const std::vector<double> p = propsFor(concrete(), 2.5, SnapBackPolicy::Release);
  ASSERT_EQ(p.size(), static_cast<std::size_t>(kMinProps));
  EXPECT_EQ(p[kModel], 1.0);
  EXPECT_EQ(p[kYoungsModulus], 32000.0);
  EXPECT_EQ(p[kPoissonRatio], 0.2);
  EXPECT_EQ(p[kTensileStrength], 3.0);
  EXPECT_EQ(p[kSofteningModulus], 8.184);
  EXPECT_EQ(p[kSofteningExponent], 0.128);
  EXPECT_EQ(p[kBandWidth], 0.05);
  EXPECT_EQ(p[kEffectiveSize], 2.5);
  EXPECT_EQ(p[kSnapBack], 1.0);
  EXPECT_EQ(propsFor(concrete(), 2.5, SnapBackPolicy::Stop, 6).back(), 6.0);
  EXPECT_EQ(propsFor(concrete(), 2.5, SnapBackPolicy::Stop)[kSnapBack], 0.0);
}

TEST(UmatProps, WhatTheUmatDoesNotCarryIsRefused) {
  MaterialParams smeared = concrete();
  smeared.model = ModelKind::SmearedCrack;
  EXPECT_THROW(propsFor(smeared, 2.5, SnapBackPolicy::Release), ParameterError);
  MaterialParams twoBands = concrete();
  twoBands.secondBand = SecondBandOption::Orthogonal;
  EXPECT_THROW(propsFor(twoBands, 2.5, SnapBackPolicy::Release), ParameterError);
  EXPECT_THROW(propsFor(concrete(), 0.05, SnapBackPolicy::Release), ParameterError);  // H = h: no room for the bulk
}

TEST(UmatProps, TheCardDeclaresTheConstantsItListsOneMaterialPerElementSize) {
  CardRequest r{.name = "concrete", .effectiveSizes = {2.5, 5.0}, .snapBack = SnapBackPolicy::Release,
                .dialect = Dialect::CalculiX, .source = "a test"};
  const std::string card = materialCard(concrete(), r);
  const std::vector<CardMaterial> materials = readCard(card);
  ASSERT_EQ(materials.size(), 2u);
  EXPECT_EQ(materials[0].name, "ABAQUS_CONCRETE_H2p5");  // CalculiX calls a UMAT for ABAQUS* names
  EXPECT_EQ(materials[1].name, "ABAQUS_CONCRETE_H5");
  for (const CardMaterial& m : materials) {
    EXPECT_EQ(m.declared, static_cast<int>(m.constants.size()));
    EXPECT_EQ(m.declared, kMinProps);
  }
  EXPECT_EQ(materials[0].constants, propsFor(concrete(), 2.5, SnapBackPolicy::Release));
  EXPECT_EQ(materials[1].constants[kEffectiveSize], 5.0);
  EXPECT_NE(card.find("*DEPVAR\n17\n"), std::string::npos);
  EXPECT_NE(card.find("*DENSITY\n2.4e-09\n"), std::string::npos);
  // Abaqus: the name as given, H = 0 takes CELENT.
  r.dialect = Dialect::Abaqus;
  r.effectiveSizes = {0.0};
  const std::vector<CardMaterial> abaqus = readCard(materialCard(concrete(), r));
  ASSERT_EQ(abaqus.size(), 1u);
  EXPECT_EQ(abaqus[0].name, "CONCRETE");
  EXPECT_EQ(abaqus[0].constants[kEffectiveSize], 0.0);
}

TEST(UmatProps, ACardCalculiXCannotUseIsRefused) {
  CardRequest r;
  r.name = "concrete";
  r.effectiveSizes = {0.0};
  EXPECT_THROW(materialCard(concrete(), r), ParameterError);  // CalculiX passes no CELENT
  r.effectiveSizes = {2.5};
  r.name = "con crete";
  EXPECT_THROW(materialCard(concrete(), r), ParameterError);
  r.name = "concrete";
  r.effectiveSizes = {};
  EXPECT_THROW(materialCard(concrete(), r), ParameterError);
}

}  // namespace
}  // namespace ecm::umat
