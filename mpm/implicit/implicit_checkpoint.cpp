// Checkpoints of implicit_static runs (mpm/implicit/implicit_checkpoint.hpp).
#include "mpm/implicit/implicit_checkpoint.hpp"

#include <stdexcept>

#include "mpm/output/checkpoint_codec.hpp"

namespace ecm::mpm {

namespace {

constexpr char kMagic[8] = {'E', 'C', 'M', 'I', 'M', 'P', 'C', 'K'};

}  // namespace

void writeImplicitCheckpoint(const std::filesystem::path& path, const ImplicitSolver& solver, const ImplicitBookkeeping& run,
                             std::uint64_t sceneHash) {
  checkpoint::Encoder e;
  checkpoint::putHead(e, sceneHash, solver.setup().threads);
  const ImplicitSolver::SavedState s = solver.saved();
  e.put(s.time);
  e.put(s.loadFactor);
  e.put(s.nextPiece);
  e.put(s.nextOpening);
  e.put(static_cast<std::int64_t>(s.steps));
  e.put(s.externalWork);
  e.put(s.internalWork);
  e.put(s.dissipated);
  e.put(s.dashpotWork);
  e.put(static_cast<std::int64_t>(s.released));
  checkpoint::putConditions(e, s.reactions, s.conditionDisplacements);
  e.count(s.stencilBases.size());
  e.array(s.stencilBases);
  e.count(s.prescribed.size());
  e.array(s.prescribed);
  const Eigen::SparseMatrix<double>& k = s.factored;
  e.put(static_cast<std::int64_t>(k.rows()));
  if (k.rows() > 0) {
    e.count(static_cast<std::size_t>(k.nonZeros()));
    for (Eigen::Index c = 0; c <= k.cols(); ++c) e.put(static_cast<std::int32_t>(k.outerIndexPtr()[c]));
    for (Eigen::Index i = 0; i < k.nonZeros(); ++i) e.put(static_cast<std::int32_t>(k.innerIndexPtr()[i]));
    for (Eigen::Index i = 0; i < k.nonZeros(); ++i) e.put(k.valuePtr()[i]);
    e.put(static_cast<std::uint8_t>(s.factoredReduced));
    e.count(s.platenLayout.size());
    for (const auto& layout : s.platenLayout)
      for (const bool prescribed : layout) e.put(static_cast<std::uint8_t>(prescribed));
    e.count(s.tieLayout.size());
    for (const NodeTie& tie : s.tieLayout) {
      e.put(tie.node);
      e.put(static_cast<std::int32_t>(tie.sources));
      for (const std::int32_t source : tie.source) e.put(source);
      for (const double c : tie.coefficient) e.put(c);
    }
  }
  const std::vector<double> lastIncrement(s.lastIncrement.data(), s.lastIncrement.data() + s.lastIncrement.size());
  e.count(lastIncrement.size());
  e.array(lastIncrement);
  e.put(s.lastLoadFactorIncrement);
  e.put(s.lastOpening);
  checkpoint::putPlatens(e, solver.platens());
  checkpoint::putParticles(e, solver.particles());
  solver.crackPaths().encode(e);
  e.put(run.progress);
  e.put(run.nextSnapshot);
  checkpoint::putPeaks(e, run);
  e.put(run.linearSolveSeconds);
  for (const long v : {run.iterations, run.halvings, run.released, run.factorizations, run.mostIterations, run.relaxed})
    e.put(static_cast<std::int64_t>(v));
  e.put(static_cast<std::int64_t>(run.krylovIterations));
  e.put(static_cast<std::int64_t>(run.stabilized));
  checkpoint::putOutputs(e, run);
  checkpoint::writeSealed(path, kMagic, kImplicitCheckpointVersion, e.bytes());
}

ImplicitBookkeeping readImplicitCheckpoint(const std::filesystem::path& path, ImplicitSolver& solver, std::uint64_t sceneHash) {
  const std::string where = "checkpoint '" + path.string() + "'";
  auto refuse = [&](const std::string& why) -> void { throw CheckpointError(where + ": " + why); };
  std::string file;
  const std::string_view payload = checkpoint::readSealed(path, kMagic, kImplicitCheckpointVersion,
                                                          "an ecm-mpm implicit_static checkpoint", file);
  checkpoint::Decoder d(payload, where);
  ImplicitBookkeeping run;
  run.threads = checkpoint::getHead(d, sceneHash, where);
  ImplicitSolver::SavedState s;
  s.time = d.get<double>();
  s.loadFactor = d.get<double>();
  s.nextPiece = d.get<double>();
  s.nextOpening = d.get<double>();
  s.steps = static_cast<long>(d.get<std::int64_t>());
  s.externalWork = d.get<double>();
  s.internalWork = d.get<double>();
  s.dissipated = d.get<double>();
  s.dashpotWork = d.get<double>();
  s.released = static_cast<long>(d.get<std::int64_t>());
  checkpoint::getConditions(d, s.reactions, s.conditionDisplacements);
  d.array(s.stencilBases, d.count(sizeof(std::int32_t)));
  d.array(s.prescribed, d.count(1));
  const auto rows = d.get<std::int64_t>();
  if (rows < 0 || rows > static_cast<std::int64_t>(s.prescribed.size())) refuse("corrupted (its tangent's size)");
  if (rows > 0) {
    const std::size_t nnz = d.count(sizeof(std::int32_t) + sizeof(double));
    std::vector<std::int32_t> outer, inner;
    std::vector<double> values;
    d.array(outer, static_cast<std::size_t>(rows) + 1);
    d.array(inner, nnz);
    d.array(values, nnz);
    bool valid = outer.front() == 0 && outer.back() == static_cast<std::int32_t>(nnz);
    for (std::size_t c = 0; valid && c + 1 < outer.size(); ++c) valid = outer[c] <= outer[c + 1];
    for (const std::int32_t r : inner) valid = valid && r >= 0 && r < rows;
    if (!valid) refuse("corrupted (its tangent's indices)");
    s.factored = Eigen::Map<const Eigen::SparseMatrix<double>>(rows, rows, static_cast<Eigen::Index>(nnz), outer.data(),
                                                               inner.data(), values.data());
    s.factoredReduced = d.get<std::uint8_t>() != 0;
    s.platenLayout.resize(d.count(3));
    for (auto& layout : s.platenLayout)
      for (bool& prescribed : layout) prescribed = d.get<std::uint8_t>() != 0;
    s.tieLayout.resize(d.count(6 * sizeof(std::int32_t) + 4 * sizeof(double)));
    for (NodeTie& tie : s.tieLayout) {
      tie.node = d.get<std::int32_t>();
      tie.sources = d.get<std::int32_t>();
      for (std::int32_t& source : tie.source) source = d.get<std::int32_t>();
      for (double& c : tie.coefficient) c = d.get<double>();
    }
  }
  std::vector<double> lastIncrement;
  d.array(lastIncrement, d.count(sizeof(double)));
  s.lastIncrement = Eigen::Map<const Eigen::VectorXd>(lastIncrement.data(), static_cast<Eigen::Index>(lastIncrement.size()));
  s.lastLoadFactorIncrement = d.get<double>();
  s.lastOpening = d.get<double>();
  checkpoint::getPlatens(d, solver.editPlatens());
  checkpoint::getParticles(d, solver.editParticles(), solver.setup().materials.size(), where);
  solver.editCrackPaths().decode(d);
  run.progress = d.get<double>();
  run.nextSnapshot = d.get<double>();
  checkpoint::getPeaks(d, run);
  run.linearSolveSeconds = d.get<double>();
  for (long* v : {&run.iterations, &run.halvings, &run.released, &run.factorizations, &run.mostIterations, &run.relaxed})
    *v = static_cast<long>(d.get<std::int64_t>());
  run.krylovIterations = static_cast<long>(d.get<std::int64_t>());
  run.stabilized = static_cast<long>(d.get<std::int64_t>());
  checkpoint::getOutputs(d, run);
  if (!d.done()) refuse("corrupted (bytes left after the payload)");
  try {
    solver.restore(s);
  } catch (const std::invalid_argument& e) {
    refuse(e.what());
  }
  return run;
}

}  // namespace ecm::mpm
