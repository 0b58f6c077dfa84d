// Out-of-range parameters are rejected naming the parameter, its value and the allowed range.
#include <gtest/gtest.h>

#include <cmath>

#include "material/material.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

MaterialParams concrete() { return test::paperConcreteMaterial(); }

// The error carries the parameter's key as data (ParameterError::key: the YAML readers report the
// key's line from it), and the message names it with the value and the allowed range.
void expectRejected(MaterialParams p, const std::string& name, const std::string& range) {
  try {
    Material m(p);
    FAIL() << "accepted a bad " << name;
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.key, name) << e.what();
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(range), std::string::npos) << e.what();
  }
}

TEST(Parameters, RejectsEachOutOfRangeValue) {
  MaterialParams p = concrete();
  p.elastic.youngsModulus = 0.0;
  expectRejected(p, "youngs_modulus", "(0,");
  p = concrete(), p.elastic.poissonRatio = 0.5;
  expectRejected(p, "poisson_ratio", "(-1, 0.5)");
  p = concrete(), p.tensileStrength = -1.0;
  expectRejected(p, "tensile_strength", "(0,");
  p = concrete(), p.softeningModulus = 0.0;
  expectRejected(p, "softening_modulus", "(0,");
  p = concrete(), p.softeningExponent = 0.5;  // int F dD diverges for n >= 0.5
  expectRejected(p, "softening_exponent", "(0, 0.5)");
  p = concrete(), p.bandWidth = 0.0;
  expectRejected(p, "band_width", "(0,");
  p = concrete(), p.tensileStrength = std::nan("");
  expectRejected(p, "tensile_strength", "nan");
  p = concrete(), p.elastic.youngsModulus = INFINITY;
  expectRejected(p, "youngs_modulus", "inf");
  p = concrete(), p.model = ModelKind::LinearElastic, p.secondBand = SecondBandOption::Orthogonal;
  expectRejected(p, "second_band", "needs the enriched model");
}

TEST(Parameters, EffectiveSizeMustExceedTheBandWidth) {
  // Eq. (1): f = h / H must lie in (0, 1).
  const Material m(concrete());
  MaterialPoint point;
  const UpdateResult r = m.update(point, Voigt(1e-3, 0.0, 0.0), EffectiveSize::fixed(test::kBandWidth), SnapBackPolicy::Stop);
  EXPECT_EQ(r.status, UpdateStatus::SizeTooSmall);
  EXPECT_EQ(r.refusedSize, test::kBandWidth);
  EXPECT_FALSE(point.band);
  EXPECT_EQ(point.strain, Voigt::Zero()) << "a refused update leaves the state unchanged";
  // The bound h (1 + 1e-6) = 0.05000005 mm in the message (docs/model.md).
  EXPECT_NE(m.explain(r).find("0.05000005"), std::string::npos) << m.explain(r);
}

}  // namespace
}  // namespace ecm
