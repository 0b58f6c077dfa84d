// The output files both solvers write alike (mpm/output/run_files.hpp).
#include "mpm/output/run_files.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>

#include "io/gnuplot.hpp"
#include "io/particle_map.hpp"
#include "io/output_error.hpp"
#include "mpm/output/checkpoint_codec.hpp"

namespace ecm::mpm {

std::vector<std::string> historyColumns(const Scene& scene) {
  std::vector<std::string> h{"time_s", "step"};
  for (const auto& c : scene.conditions)
    for (const char* q : {"_ux_mm", "_uy_mm", "_rx_N", "_ry_N"}) h.push_back(c.name + q);
  for (const auto& l : scene.loads)
    for (const char* q : {"_fx_N", "_fy_N"}) h.push_back(l.name + q);
  for (const char* q : {"kinetic_Nmm", "strain_Nmm", "external_work_Nmm", "dissipated_Nmm", "damping_Nmm", "cracked"})
    h.push_back(q);
  return h;
}


std::unique_ptr<io::CsvWriter> openHistory(const std::filesystem::path& dir, const std::vector<std::string>& columns,
                                           const std::filesystem::path& checkpoint, const io::CsvWriter::Resume* resume) {
  if (!resume) {
    std::error_code ignored;  // a checkpoint of an earlier run in this folder no longer applies
    std::filesystem::remove(checkpoint, ignored);
    return std::make_unique<io::CsvWriter>(dir / "history.csv", columns);
  }
  try {
    return std::make_unique<io::CsvWriter>(dir / "history.csv", columns, *resume);
  } catch (const io::OutputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw CheckpointError("cannot continue from checkpoint '" + checkpoint.string() + "': " + e.what());
  }
}

// The load-displacement curve: the first driven condition's displacement against its reaction,
// else the first load against time.
void plotLoadDisplacement(const Scene& scene, const std::filesystem::path& dir) {
  io::PlotSpec spec;
  spec.title = scene.name + ": load-displacement";
  const int base = 3;  // time, step, then 4 columns per condition (1-based gnuplot columns)
  for (std::size_t i = 0; i < scene.conditions.size(); ++i) {
    const auto& c = scene.conditions[i];
    if (!isDriven(c) || c.field) continue;
    const int d = drivenComponent(c);
    const int col = base + 4 * static_cast<int>(i);
    spec.xLabel = c.name + (d ? " u_y" : " u_x") + " (mm)";
    spec.yLabel = c.name + (d ? " reaction R_y" : " reaction R_x") + " (N)";
    spec.series.push_back({"history.csv", std::to_string(col + d) + ":" + std::to_string(col + 2 + d), "", c.name, "lines"});
    break;
  }
  if (spec.series.empty() && !scene.loads.empty()) {
    const int col = base + 4 * static_cast<int>(scene.conditions.size());
    const int d = scene.loads[0].force[1] != 0.0 ? 1 : 0;
    spec.xLabel = "time (s)";
    spec.yLabel = scene.loads[0].name + " (N)";
    spec.series.push_back({"history.csv", "1:" + std::to_string(col + d), "", scene.loads[0].name, "lines"});
  }
  if (spec.series.empty() && !scene.conditions.empty()) {  // e.g. a free vibration: the first reaction in time
    spec.title = scene.name + ": reaction";
    spec.xLabel = "time (s)";
    spec.yLabel = scene.conditions[0].name + " reaction R_x (N)";
    spec.series.push_back({"history.csv", "1:" + std::to_string(base + 2), "", scene.conditions[0].name, "lines"});
  }
  if (spec.series.empty()) return;
  io::renderPlot(spec, dir / "load_displacement.png");
}

// The final state of every particle (x, y, damage, material id, normal opening and normal of the
// band, stress), for damage and crack maps and the locking diagnosis.
// Written as PATH.tmp, then renamed: a restart rewrites it, and a reader never sees half of it.
void writeCsvAtomically(const std::filesystem::path& path, const std::vector<std::string>& columns,
                        const std::function<void(io::CsvWriter&)>& fill) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  try {
    io::CsvWriter csv(tmp, columns);
    fill(csv);
    csv.close();
  } catch (const io::OutputError& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw io::OutputError(path, e.reason);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw io::OutputError(path, "rename from " + tmp.filename().string() + " failed: " + ec.message());
}

void writeParticles(const Particles& p, const std::filesystem::path& path) {
  std::vector<std::string> columns{"x_mm", "y_mm", "damage", "material", "opening_mm", "normal_x", "normal_y",
                                   "sig_xx_MPa", "sig_yy_MPa", "sig_xy_MPa"};
  const bool twoBands = !p.secondBand.empty();  // second_band: orthogonal: the second band's columns
  if (twoBands)
    for (const char* c : {"damage_2", "opening_2_mm", "normal_x_2", "normal_y_2"}) columns.emplace_back(c);
  writeCsvAtomically(path, columns, [&](io::CsvWriter& csv) {
    std::vector<double> row;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const BandState* b = p.band[i] >= 0 ? &p.bands[static_cast<std::size_t>(p.band[i])] : nullptr;
      const Vec2 normal = b ? b->crackNormal : Vec2::Zero();
      row = {p.position[i][0], p.position[i][1], p.damage(i), static_cast<double>(p.material[i]),
             b ? b->normalJump() : 0.0, normal[0], normal[1], p.stress[i][0], p.stress[i][1], p.stress[i][2]};
      if (twoBands) {
        const BandState* b2 = p.secondBandOf(i);
        row.insert(row.end(), {b2 ? b2->damage() : 0.0, b2 ? b2->normalJump() : 0.0, b2 ? b2->crackNormal[0] : 0.0,
                               b2 ? b2->crackNormal[1] : 0.0});
      }
      csv.row(row);
    }
  });
}

// The damage map of particles_final.csv: one square point per particle, coloured by damage, laid
// out for the grid's shape (io/particle_map.hpp: a slender bar is stretched, not a sliver).
void plotDamage(const Scene& scene, std::size_t particles, const std::filesystem::path& dir) {
  const Vec2 extent = scene.grid.extent();
  io::renderPlot(io::particleMapSpec({scene.name + ": damage at the end", "particles_final.csv", "1:2:3", "damage",
                                      extent[0], extent[1], particles}),
                 dir / "damage_map.png");
}

}  // namespace ecm::mpm
