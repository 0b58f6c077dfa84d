// Axial vibration of a free-free elastic bar, mode 1. Closed form (e.g. Graff, Wave Motion in
// Elastic Solids, sec. 1.3): u(X, t) = (v0 / omega) cos(pi X / L) sin(omega t), omega = pi c / L,
// c = sqrt(E / rho), period T = 2 L / c. Measured through the modal coordinate
// q(t) = sum m u phi / sum m phi^2 (phi = cos(pi X / L)), whose exact value is (v0/omega) sin(omega t).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

struct Measured {
  double periodError;     // relative
  double amplitudeError;  // relative
  double energyDrift;     // max |E - E0| / E0 of the time-centred energy (see below)
  double naiveDrift;      // the same with E = kinetic(v^{n+1}) + strain(u^{n+1})
};

Measured vibrate(const BarSetup& bar) {
  ExplicitSolver solver(bar.scene(), 1);
  bar.setInitialVelocity(solver);
  const auto& p = solver.particles();
  std::vector<double> phi(p.size());
  double den = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) phi[i] = bar.mode(p.position[i][0]), den += p.mass[i] * phi[i] * phi[i];
  auto modal = [&] {
    double num = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) num += p.mass[i] * p.displacement(i)[0] * phi[i];
    return num / den;
  };
  // The explicit update is staggered: particle velocities after step n+1 are the velocities of
  // the interval [t_n, t_{n+1}]. The energy such a scheme conserves for a linear system is
  // E_n = sum m v^{n-1/2}.v^{n+1/2} / 2 + strain(u^n) (leapfrog's discrete energy; e.g. Hairer,
  // Lubich, Wanner, Geometric Numerical Integration, sec. I.1.4). Pairing kinetic(v^{n+1/2})
  // with strain(u^{n+1}) oscillates by O(omega dt) instead (reported as naiveDrift). USF updates
  // the stress first, from the grid velocities of the previous interval: its strain after step
  // n+1 is that of u^n, so there the strain energy after the step enters.
  const Energies e0 = solver.energies();
  const double energy0 = e0.kinetic + e0.strain;
  double drift = 0.0, naive = 0.0, centred0 = NAN;
  std::vector<Vec2> before;
  std::vector<double> t{0.0}, q{0.0};
  double upCrossing = NAN;
  while (solver.time() < 1.3 * bar.period()) {
    const double strainBefore = solver.energies().strain;
    before = p.velocity;
    solver.advance();
    t.push_back(solver.time());
    q.push_back(modal());
    const Energies e = solver.energies();
    naive = std::max(naive, std::abs(e.kinetic + e.strain - energy0) / energy0);
    if (solver.step() > 1) {  // v^{-1/2} does not exist for the first step
      double kinetic = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i) kinetic += 0.5 * p.mass[i] * before[i].dot(p.velocity[i]);
      const double centred = kinetic + (bar.scheme == UpdateScheme::USF ? e.strain : strainBefore);
      if (std::isnan(centred0)) centred0 = centred;
      drift = std::max(drift, std::abs(centred - centred0) / centred0);
    }
    const std::size_t n = q.size() - 1;
    if (std::isnan(upCrossing) && t[n] > 0.75 * bar.period() && q[n - 1] < 0.0 && q[n] >= 0.0)
      upCrossing = t[n - 1] + (t[n] - t[n - 1]) * (-q[n - 1]) / (q[n] - q[n - 1]);
  }
  // Peak of the first half period by a parabola through the largest sample and its neighbours.
  std::size_t k = 1;
  for (std::size_t i = 1; i + 1 < q.size() && t[i] < 0.5 * bar.period(); ++i)
    if (q[i] > q[k]) k = i;
  const double a = q[k - 1], b = q[k], c = q[k + 1];
  const double peak = b + 0.125 * (a - c) * (a - c) / (2.0 * b - a - c);
  const double exactAmplitude = bar.v0() / bar.omega();
  return {upCrossing / bar.period() - 1.0, peak / exactAmplitude - 1.0, drift, naive};
}

class BarVibration : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(BarVibration, PeriodAndAmplitudeWithinOnePercentAt64CellsAndConverge) {
  std::map<int, Measured> m;
  for (int cells : {16, 32, 64, 128}) {
    BarSetup bar;
    bar.cells = cells;
    bar.shape = GetParam();
    m[cells] = vibrate(bar);
  }
  std::printf("[ bar ] %-8s cells  period-err   amplitude-err  energy-drift\n", toString(GetParam()));
  for (const auto& [n, r] : m)
    std::printf("[ bar ] %-8s %5d  %+.3e  %+.3e     %.2e\n", toString(GetParam()), n, r.periodError, r.amplitudeError,
                r.energyDrift);
  auto order = [&](double Measured::*f, int n) { return std::log2(std::abs(m[n].*f) / std::abs(m[2 * n].*f)); };
  std::printf("[ bar ] %-8s observed order (32->64, 64->128): period %.2f %.2f, amplitude %.2f %.2f\n",
              toString(GetParam()), order(&Measured::periodError, 32), order(&Measured::periodError, 64),
              order(&Measured::amplitudeError, 32), order(&Measured::amplitudeError, 64));
  EXPECT_LT(std::abs(m[64].periodError), 0.01);
  EXPECT_LT(std::abs(m[64].amplitudeError), 0.01);
  EXPECT_LT(std::abs(m[128].periodError), std::abs(m[32].periodError));  // converges
}

INSTANTIATE_TEST_SUITE_P(Shapes, BarVibration,
                         ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2),
                         [](const auto& info) { return std::string(toString(info.param)); });

// Undamped elastic run: kinetic + strain energy constant within 0.5% (no dissipation, no
// external work), for every update scheme.
class EnergyBalance : public ::testing::TestWithParam<UpdateScheme> {};

TEST_P(EnergyBalance, KineticPlusStrainConstant) {
  BarSetup bar;
  bar.scheme = GetParam();
  const Measured m = vibrate(bar);
  std::printf("[ energy ] %s: max drift %.3e (naive kinetic(v^{n+1}) + strain(u^{n+1}): %.3e)\n", toString(GetParam()),
              m.energyDrift, m.naiveDrift);
  EXPECT_LT(m.energyDrift, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Schemes, EnergyBalance,
                         ::testing::Values(UpdateScheme::USF, UpdateScheme::USL, UpdateScheme::MUSL),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace ecm::mpm::test
