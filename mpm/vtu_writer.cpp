#include "mpm/vtu_writer.hpp"

#include <charconv>
#include <cstdio>

#include "io/atomic_file.hpp"

namespace ecm::mpm {

namespace {

// Shortest round-trip form of a double.
void put(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

template <class F>
void dataArray(std::string& out, const char* name, int components, std::size_t n, F&& value) {
  out += "        <DataArray type=\"Float64\" Name=\"";
  out += name;
  out += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    out += "          ";
    for (int c = 0; c < components; ++c) {
      if (c) out += ' ';
      put(out, value(i, c));
    }
    out += '\n';
  }
  out += "        </DataArray>\n";
}

}  // namespace

void writeVtu(const Solver& solver, const std::filesystem::path& path) {
  const Particles& p = solver.particles();
  const std::size_t n = p.size();
  auto band = [&](std::size_t i) -> const BandState* {
    return p.band[i] >= 0 ? &p.bands[static_cast<std::size_t>(p.band[i])] : nullptr;
  };
  std::string out;
  out.reserve(n * 400 + 1024);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<!-- ecm-mpm particles; units: mm, N, MPa, t, s -->\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">";
  put(out, solver.time());
  out += "</DataArray>\n    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">\n";
  out += "      <PointData Scalars=\"damage\" Vectors=\"displacement\">\n";
  dataArray(out, "displacement", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.displacement[i][c] : 0.0; });
  dataArray(out, "velocity", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.velocity[i][c] : 0.0; });
  dataArray(out, "stress", 3, n, [&](std::size_t i, int c) { return p.stress[i][c]; });  // xx, yy, xy (MPa)
  dataArray(out, "strain", 3, n, [&](std::size_t i, int c) { return p.strain[i][c]; });  // xx, yy, gamma_xy
  dataArray(out, "damage", 1, n, [&](std::size_t i, int) { return solver.damage(i); });
  dataArray(out, "crack_normal", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->crackNormal[c] : 0.0;
  });
  dataArray(out, "jump", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->jump[c] : 0.0;
  });
  dataArray(out, "opening", 1, n, [&](std::size_t i, int) {
    const BandState* b = band(i);
    return b ? b->normalJump() : 0.0;
  });
  dataArray(out, "material", 1, n, [&](std::size_t i, int) { return static_cast<double>(p.material[i]); });
  dataArray(out, "cracked", 1, n, [&](std::size_t i, int) { return p.band[i] >= 0 ? 1.0 : 0.0; });
  out += "      </PointData>\n      <Points>\n";
  dataArray(out, "position", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.position[i][c] : 0.0; });
  out += "      </Points>\n      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out += std::to_string(i) + (i + 1 == n || i % 16 == 15 ? "\n" : " ");
  out += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out += std::to_string(i + 1) + (i + 1 == n || i % 16 == 15 ? "\n" : " ");
  out += "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out += (i + 1 == n || i % 32 == 31) ? "1\n" : "1 ";  // VTK_VERTEX
  out += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  io::writeFileAtomically(path, out);
}

VtuSeries::VtuSeries(std::filesystem::path dir, std::string stem) : dir_(std::move(dir)), stem_(std::move(stem)) {}

std::string VtuSeries::fileName(std::size_t index) const {
  char name[64];
  std::snprintf(name, sizeof name, "_%05zu.vtu", index);
  return stem_ + name;
}

void VtuSeries::add(const Solver& solver) {
  const std::string file = fileName(entries_.size());
  writeVtu(solver, dir_ / file);
  entries_.emplace_back(solver.time(), file);
  writeIndex();
}

void VtuSeries::writeIndex() const {
  std::string index = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [t, f] : entries_) {
    index += "    <DataSet timestep=\"";
    put(index, t);
    index += "\" part=\"0\" file=\"" + f + "\"/>\n";
  }
  index += "  </Collection>\n</VTKFile>\n";
  io::writeFileAtomically(indexPath(), index);
}

std::vector<double> VtuSeries::times() const {
  std::vector<double> t;
  for (const auto& e : entries_) t.push_back(e.first);
  return t;
}

void VtuSeries::resume(const std::vector<double>& times) {
  entries_.clear();
  for (const double t : times) entries_.emplace_back(t, fileName(entries_.size()));
  std::error_code ec;
  for (std::size_t i = entries_.size(); std::filesystem::remove(dir_ / fileName(i), ec); ++i) {
  }
  writeIndex();
}

}  // namespace ecm::mpm
