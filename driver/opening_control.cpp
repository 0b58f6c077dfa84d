#include "driver/opening_control.hpp"

#include <cmath>
#include <vector>

namespace ecm::driver {

OpeningOutcome openingControlStep(const TwoPhasePoint& model, MaterialPoint& point, const OpeningTarget& t,
                                  double tolerance, int maxIterations) {
  const BandState& b = *point.band;
  const auto surface = model.bandLaw().loadingSurface(b.integrity);
  const Vec2 normal = b.crackNormal, sliding = b.slidingDirection();
  const JumpMap n = jumpToStrain(normal);
  const double f = b.volumeFraction, h = model.bandWidth();
  const Tangent& a = model.stiffness();
  std::vector<int> free;
  Voigt direction = Voigt::Zero();
  for (int i = 0; i < 3; ++i) {
    if (t.control[i] == Control::Stress) free.push_back(i);
    else direction[i] = t.direction[i];
  }
  const int m = static_cast<int>(free.size());
  const int dim = m + 2;  // [lambda, eps_s..., sliding jump]
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 5, 5>;
  Vec u = Vec::Zero(dim);
  u[dim - 1] = sliding.dot(b.jump);

  struct Trial {
    Voigt strain;
    Vec2 jump;
    BandEquilibrium eq;
    Vec residual;
  };
  const auto evaluate = [&](const Vec& x) {
    Trial tr;
    tr.strain = point.strain + x[0] * direction;
    for (int i = 0; i < m; ++i) tr.strain[free[i]] += x[1 + i];
    tr.jump = t.normalJump * normal + x[dim - 1] * sliding;
    tr.eq = model.equilibrium(b, surface, tr.strain, tr.jump, true);
    tr.residual.resize(dim);
    for (int i = 0; i < m; ++i) tr.residual[i] = tr.eq.stress[free[i]] - t.stress[free[i]];
    tr.residual.tail<2>() = tr.eq.residual;
    return tr;
  };
  // d sigma / d eps = a/(1-f); d sigma / d[u] = -f/((1-f) h) a N   (Eqs. (2)-(4))
  // d r / d eps = N^T a/(1-f); d r / d[u] = -K                     (Eqs. (6), (9))
  // The bulk stress a (eps - f eps_L) / (1 - f) carries the round-off of a : eps amplified by
  // 1 / (1 - f) (Eq. (4)): the tolerance cannot be tighter than that.
  const double tol = tolerance + TwoPhasePoint::kRoundOff * (a * point.strain).norm() / (1.0 - f);
  const Tangent dSdE = a / (1.0 - f);
  const JumpMap dSdJ = -f / ((1.0 - f) * h) * a * n;
  Trial tr = evaluate(u);
  OpeningOutcome out;
  int it = 0;
  for (; tr.residual.norm() > tol && it < maxIterations; ++it) {
    Mat g(dim, dim);
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 5> dStrain = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 5>::Zero(3, dim);
    Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 5> dJump = Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 5>::Zero(2, dim);
    dStrain.col(0) = direction;
    for (int i = 0; i < m; ++i) dStrain(free[i], 1 + i) = 1.0;
    dJump.col(dim - 1) = sliding;
    const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 5> dStress = dSdE * dStrain + dSdJ * dJump;
    for (int i = 0; i < m; ++i) g.row(i) = dStress.row(free[i]);
    g.bottomRows<2>() = n.transpose() * dSdE * dStrain - tr.eq.jacobian * dJump;
    const Vec step = g.partialPivLu().solve(-tr.residual);
    if (!step.allFinite()) break;
    double alpha = 1.0;
    Trial next;
    for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
      next = evaluate(u + alpha * step);
      if (next.residual.norm() < (1.0 - 1e-4 * alpha) * tr.residual.norm()) break;
    }
    u += alpha * step;
    tr = next;
  }
  out.loadFactor = u[0];
  out.step.iterations = it;
  out.step.controlResidual = tr.residual.norm();
  out.step.result.stress = tr.eq.stress;
  out.step.result.residual = tr.eq.residual.norm();
  out.step.result.iterations = it;
  if (!(tr.residual.norm() <= tol)) {
    out.step.result.status = UpdateStatus::NotConverged;
    return out;
  }
  out.step.result.tangent = model.consistentTangent(b, tr.eq);
  out.step.dissipation = f * model.bandLaw().dissipation(b.integrity, tr.eq.band.integrity);  // f int Y dD
  out.step.result.dissipation = out.step.dissipation;
  out.step.strainIncrement = tr.strain - point.strain;
  point.strain = tr.strain;
  point.band->jump = tr.jump;
  point.band->integrity = tr.eq.band.integrity;
  return out;
}

}  // namespace ecm::driver
