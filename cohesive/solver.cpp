#include "cohesive/solver.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ecm::cohesive {

namespace {

// The bordered matrix: the bulk, every interface diagonal, the load column and the control row
// (and a structural zero at the corner).
struct BorderedSystem {
  Eigen::SparseMatrix<double> matrix;
  std::vector<Eigen::Index> diagonal;   // value index of each interface node's diagonal entry

  BorderedSystem(const HalfModel& m, const Eigen::SparseMatrix<double>& bulk) {
    const int n = m.equations;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(bulk.nonZeros() + m.interface.size() + 2 * n + 1);
    for (int k = 0; k < bulk.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(bulk, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    for (const InterfaceNode& i : m.interface) t.emplace_back(i.equation, i.equation, 0.0);
    for (int r = 0; r < n; ++r) {
      if (m.loadPattern[r] != 0.0) t.emplace_back(r, n, -m.loadPattern[r]);
      if (m.control[r] != 0.0) t.emplace_back(n, r, m.control[r]);
    }
    t.emplace_back(n, n, 0.0);
    matrix.resize(n + 1, n + 1);
    matrix.setFromTriplets(t.begin(), t.end());  // sums duplicates, keeps explicit zeros
    matrix.makeCompressed();
    for (const InterfaceNode& i : m.interface) {
      const int col = i.equation;
      Eigen::Index k = matrix.outerIndexPtr()[col];
      while (matrix.innerIndexPtr()[k] != col) ++k;
      diagonal.push_back(k);
    }
  }
};

struct Trial {
  Eigen::VectorXd internal;              // interface forces (equation space, half model)
  std::vector<double> stiffness;         // per interface node: 2 A dt/ddelta
  std::vector<InterfaceState> states;    // at the trial jumps
  std::vector<InterfaceResponse> responses;
  bool finite = true;
  std::string lawFailure;  // a jump the law cannot answer (past a table's end): a failed iteration
};

double jumpOf(const InterfaceNode& i, const Eigen::VectorXd& u) { return 2.0 * i.sign * u[i.equation]; }

Trial evaluate(const HalfModel& m, const InterfaceLaw& law, const std::vector<InterfaceState>& committed, const Eigen::VectorXd& u) {
  Trial t;
  t.internal = Eigen::VectorXd::Zero(m.equations);
  t.states = committed;
  t.stiffness.resize(m.interface.size());
  t.responses.resize(m.interface.size());
  for (std::size_t k = 0; k < m.interface.size(); ++k) {
    const InterfaceNode& i = m.interface[k];
    InterfaceResponse r;
    try {
      r = updateInterface(law, t.states[k], jumpOf(i, u));
    } catch (const InterfaceLawError& e) {
      t.lawFailure = e.what();
      return t;
    }
    // The half model holds half the crack's energy, A phi(2 s u_n) / 2: its force s A t and
    // its stiffness 2 A dt/ddelta.
    t.internal[i.equation] += i.sign * i.area * r.traction;
    t.stiffness[k] = 2.0 * i.area * r.tangent;
    t.responses[k] = r;
    if (!std::isfinite(r.traction) || !std::isfinite(r.tangent)) t.finite = false;
  }
  return t;
}

}  // namespace

SolveResult solveControlled(const HalfModel& m, const InterfaceLaw& law, const SolverSettings& s,
                            const std::function<void(const StepRecord&)>& onStep) {
  const int n = m.equations;
  const Eigen::SparseMatrix<double> bulk = bulkStiffness(m);
  BorderedSystem system(m, bulk);
  // A0: the bordered matrix with the interface at rest (its elastic stiffness), factorised once.
  const std::vector<double> stiffness0 = evaluate(m, law, std::vector<InterfaceState>(m.interface.size()), Eigen::VectorXd::Zero(n)).stiffness;
  for (std::size_t k = 0; k < m.interface.size(); ++k) system.matrix.valuePtr()[system.diagonal[k]] += stiffness0[k];
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(system.matrix);
  if (lu.info() != Eigen::Success) throw std::runtime_error("the bordered matrix at rest is singular: is the model held against rigid-body motion?");
  Eigen::MatrixXd z(n + 1, m.interface.size());  // A0^{-1} S
  {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n + 1);
    for (std::size_t k = 0; k < m.interface.size(); ++k) {
      e[m.interface[k].equation] = 1.0;
      z.col(k) = lu.solve(e);
      e[m.interface[k].equation] = 0.0;
    }
  }
  Eigen::MatrixXd stZ(m.interface.size(), m.interface.size());  // S^T Z
  for (std::size_t k = 0; k < m.interface.size(); ++k) stZ.row(k) = z.row(m.interface[k].equation);

  SolveResult result;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  double lambda = 0.0;
  std::vector<InterfaceState> states(m.interface.size());
  std::vector<double> dissipated(m.interface.size(), 0.0);  // per area
  std::vector<InterfaceResponse> responses(m.interface.size());

  StepRecord rec;
  result.history.push_back(rec);
  if (onStep) onStep(rec);

  // The force scale of the residual test: f_t' times the ligament area of the half model's load
  // path (the order of the peak load), so that the test does not vanish at rest.
  const double forceScale = law.tensileStrength() * m.ligamentArea;
  const auto fillLigament = [&] {
    result.displacement = u;
    result.ligament.clear();
    for (std::size_t k = 0; k < m.interface.size(); ++k)
      result.ligament.push_back({m.interface[k].position, jumpOf(m.interface[k], u), responses[k].traction, dissipated[k]});
  };
  double control = 0.0, step = std::min(s.firstStep, s.maxStep);
  int stepNumber = 0;
  while (control < s.finalControl * (1.0 - 1e-12)) {
    const double target = std::min(control + step, s.finalControl);
    Eigen::VectorXd uTrial = u;
    double lambdaTrial = lambda;
    bool converged = false;
    int iterations = 0;
    std::string reason;
    Trial trial;
    double lastIncrement = INFINITY;  // |du|_inf of the last iteration
    for (iterations = 0; iterations <= s.maxIterations; ++iterations) {
      trial = evaluate(m, law, states, uTrial);
      if (!trial.lawFailure.empty()) { reason = trial.lawFailure; break; }
      if (!trial.finite) { reason = "non-finite interface response"; break; }
      const Eigen::VectorXd residual = bulk * uTrial + trial.internal - lambdaTrial * m.loadPattern;
      const double scale = std::max(forceScale, std::abs(lambdaTrial) * m.loadPattern.cwiseAbs().maxCoeff());
      const double controlError = target - m.control.dot(uTrial);
      if (iterations > 0 && residual.cwiseAbs().maxCoeff() <= s.tolerance * scale &&
          lastIncrement <= 1e-6 * std::max(uTrial.cwiseAbs().maxCoeff(), 1e-12) &&
          std::abs(controlError) <= 1e-12 * std::max(std::abs(target), 1e-12)) {
        converged = true;
        break;
      }
      if (iterations == s.maxIterations) { reason = "no convergence in " + std::to_string(s.maxIterations) + " iterations"; break; }
      Eigen::VectorXd rhs(n + 1);
      rhs.head(n) = -residual;
      rhs[n] = controlError;
      // The bordered matrix is the one factorised at rest plus the interface nodes' stiffness
      // changes on their diagonal, A = A0 + S D S^T: Woodbury's identity solves it with A0's
      // factors and a dense system of the interface's size,
      //   x = y - Z (I + D S^T Z)^{-1} D S^T y,  y = A0^{-1} b,  Z = A0^{-1} S.
      const Eigen::VectorXd y = lu.solve(rhs);
      Eigen::VectorXd change(m.interface.size());
      for (std::size_t k = 0; k < m.interface.size(); ++k) change[k] = trial.stiffness[k] - stiffness0[k];
      Eigen::MatrixXd small = Eigen::MatrixXd::Identity(change.size(), change.size());
      Eigen::VectorXd dsy(change.size());
      for (std::size_t k = 0; k < m.interface.size(); ++k) {
        small.row(k) += change[k] * stZ.row(k);
        dsy[k] = change[k] * y[m.interface[k].equation];
      }
      const Eigen::PartialPivLU<Eigen::MatrixXd> smallLu(small);
      const double smallCondition = smallLu.rcond();
      if (!(smallCondition > 1e-14)) { reason = "singular bordered matrix (rcond " + std::to_string(smallCondition) + ")"; break; }
      const Eigen::VectorXd d = y - z * smallLu.solve(dsy);
      if (!d.allFinite()) { reason = "non-finite increment"; break; }
      uTrial += d.head(n);
      lastIncrement = d.head(n).cwiseAbs().maxCoeff();
      lambdaTrial += d[n];
    }
    if (!converged) {
      if (step <= s.minStep) {
        std::ostringstream msg;
        msg.precision(10);
        msg << "step " << stepNumber + 1 << " failed at " << m.controlName << " = " << target << " mm (from " << control
            << " mm, increment " << step << " mm at the smallest allowed " << s.minStep << "): " << reason;
        fillLigament();
        throw SolveFailure(msg.str(), std::move(result));
      }
      step = std::max(0.5 * step, s.minStep);
      continue;
    }
    // Commit.
    const double loadDispOld = m.loadPattern.dot(u);
    const double lambdaOld = lambda;
    u = uTrial;
    lambda = lambdaTrial;
    states = trial.states;
    responses = trial.responses;
    for (std::size_t k = 0; k < m.interface.size(); ++k) dissipated[k] += responses[k].dissipation;
    control = target;
    ++stepNumber;
    const StepRecord prev = result.history.back();
    StepRecord r;
    r.step = stepNumber;
    r.control = m.control.dot(u);
    r.load = m.loadScale * lambda;
    r.loadDisplacement = m.loadDisplacementScale * m.loadPattern.dot(u);
    // Full specimen = 2 x half model.
    r.externalWork = prev.externalWork + 2.0 * 0.5 * (lambdaOld + lambda) * (m.loadPattern.dot(u) - loadDispOld);
    r.bulkEnergy = 2.0 * 0.5 * u.dot(bulk * u);
    for (std::size_t k = 0; k < m.interface.size(); ++k) {
      r.interfaceEnergy += m.interface[k].area * responses[k].stored;
      r.dissipation += m.interface[k].area * dissipated[k];
    }
    r.balanceError = r.externalWork > 0.0
                         ? std::abs(r.externalWork - r.bulkEnergy - r.interfaceEnergy - r.dissipation) / r.externalWork
                         : 0.0;
    r.iterations = iterations;
    result.history.push_back(r);
    if (onStep) onStep(r);
    if (iterations <= 4) step = std::min(1.5 * step, s.maxStep);
    // The load may change by at most maxLoadStep per step (the trapezoidal work's error is made
    // where the curve bends, where the interface nodes start to soften: before the peak).
    const double loadChange = std::abs(r.load - prev.load);
    if (s.maxLoadStep > 0.0 && loadChange > 0.0) step = std::max(std::min(step, (target - prev.control) * s.maxLoadStep / loadChange), s.minStep);
  }
  fillLigament();
  return result;
}

}  // namespace ecm::cohesive
