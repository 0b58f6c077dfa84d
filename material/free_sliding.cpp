#include "material/free_sliding.hpp"

#include <cmath>

namespace ecm {

FreeSliding::FreeSliding(const Mat4& k, bool bothFailed) {
  if (!bothFailed && k.partialPivLu().rcond() >= kFreeSlidingRank) return;  // (not taken where rcond is NaN)
  svd.compute(k, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const auto& sigma = svd.singularValues();
  active = sigma[3] < kFreeSlidingRank * sigma[0];
  svd.setThreshold(kFreeSlidingRank);
}

double FreeSliding::rangeNorm(const Vec4& r) const {
  const Vec4 projected = svd.matrixU().transpose() * r;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < svd.rank(); ++i) sum += projected[i] * projected[i];
  return std::sqrt(sum);
}

}  // namespace ecm
