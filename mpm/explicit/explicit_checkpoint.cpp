#include "mpm/explicit/explicit_checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <string_view>
#include <type_traits>

#include "mpm/output/checkpoint_codec.hpp"

namespace ecm::mpm {

namespace {

constexpr char kMagic[8] = {'E', 'C', 'M', 'M', 'P', 'M', 'C', 'K'};
using checkpoint::Decoder;
using checkpoint::Encoder;

}  // namespace

void writeExplicitCheckpoint(const std::filesystem::path& path, const ExplicitSolver& solver, const ExplicitBookkeeping& run,
                     std::uint64_t sceneHash) {
  Encoder e;
  checkpoint::putHead(e, sceneHash, solver.threads());

  const ExplicitSolver::StepState s = solver.stepState();
  e.put(s.time);
  e.put(s.timeStep);
  e.put(static_cast<std::int64_t>(s.step));
  e.put(s.externalWork);
  e.put(s.dissipated);
  e.put(s.damping);
  e.put(static_cast<std::int64_t>(s.substepped));
  e.put(static_cast<std::int64_t>(s.released));
  e.put(static_cast<std::int64_t>(s.massScaled));
  checkpoint::putConditions(e, s.reactions, s.conditionDisplacements);
  e.count(s.appliedLoads.size());
  e.array(s.appliedLoads);
  e.count(s.deferred.size());
  e.array(s.deferred);

  checkpoint::putPlatens(e, solver.state().platens);
  checkpoint::putParticles(e, solver.particles());
  solver.state().crackPaths.encode(e);
  const ScatterOrder& order = solver.state().order;  // the scatter's plan and measured rows
  e.count(order.chunks());
  for (std::size_t c = 0; c < order.chunks(); ++c) {
    e.put(static_cast<std::int32_t>(order.measured[c].lo));
    e.put(static_cast<std::int32_t>(order.measured[c].hi));
    e.put(static_cast<std::int32_t>(order.planned[c].lo));
    e.put(static_cast<std::int32_t>(order.planned[c].hi));
  }

  e.put(run.nextOutput);
  checkpoint::putPeaks(e, run);
  checkpoint::putOutputs(e, run);

  checkpoint::writeSealed(path, kMagic, kCheckpointVersion, e.bytes());
}

ExplicitBookkeeping readExplicitCheckpoint(const std::filesystem::path& path, ExplicitSolver& solver, std::uint64_t sceneHash) {
  const std::string where = "checkpoint '" + path.string() + "'";
  auto refuse = [&](const std::string& why) -> void { throw CheckpointError(where + ": " + why); };
  std::string file;
  const std::string_view payload = checkpoint::readSealed(path, kMagic, kCheckpointVersion, "an ecm-mpm checkpoint", file);
  Decoder d(payload, where);
  ExplicitBookkeeping run;
  run.threads = checkpoint::getHead(d, sceneHash, where);

  ExplicitSolver::StepState s;
  s.time = d.get<double>();
  s.timeStep = d.get<double>();
  s.step = static_cast<long>(d.get<std::int64_t>());
  s.externalWork = d.get<double>();
  s.dissipated = d.get<double>();
  s.damping = d.get<double>();
  s.substepped = static_cast<long>(d.get<std::int64_t>());
  s.released = static_cast<long>(d.get<std::int64_t>());
  s.massScaled = static_cast<long>(d.get<std::int64_t>());
  const std::size_t conditions = checkpoint::getConditions(d, s.reactions, s.conditionDisplacements);
  d.array(s.appliedLoads, d.count(2 * sizeof(double)));
  d.array(s.deferred, d.count(sizeof(std::uint32_t)));
  if (conditions != solver.conditions().size() || s.appliedLoads.size() != solver.loads().size())
    refuse("it has " + std::to_string(conditions) + " conditions and " + std::to_string(s.appliedLoads.size()) +
           " loads, the scene " + std::to_string(solver.conditions().size()) + " and " +
           std::to_string(solver.loads().size()));
  // Bitwise: dt follows from the grid and the materials (which the scene hash does not cover
  // when they come from material files).
  if (s.timeStep != solver.timeStep())
    refuse("its time step " + std::to_string(s.timeStep) + " s differs from the scene's " +
           std::to_string(solver.timeStep()) + " s (a material file or the grid changed)");

  checkpoint::getPlatens(d, solver.editState().platens);
  checkpoint::getParticles(d, solver.editParticles(), solver.materials().size(), where);
  solver.editState().crackPaths.decode(d);
  std::vector<std::int32_t> rows;
  d.array(rows, 4 * d.count(4 * sizeof(std::int32_t)));
  ScatterOrder& order = solver.editState().order;
  if (rows.size() != 4 * order.chunks())
    refuse("it has " + std::to_string(rows.size() / 4) + " chunks in its scatter order, the scene " +
           std::to_string(order.chunks()));
  for (std::size_t c = 0; c < order.chunks(); ++c) {
    order.measured[c] = {rows[4 * c], rows[4 * c + 1]};
    order.planned[c] = {rows[4 * c + 2], rows[4 * c + 3]};
  }
  groupChunks(order);

  run.nextOutput = d.get<double>();
  checkpoint::getPeaks(d, run);
  checkpoint::getOutputs(d, run);
  if (!d.done()) refuse("corrupted (bytes left after the payload)");
  try {
    solver.restoreStepState(s);
  } catch (const std::invalid_argument& e) {
    refuse(e.what());
  }
  return run;
}

}  // namespace ecm::mpm
