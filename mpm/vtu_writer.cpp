#include "mpm/vtu_writer.hpp"

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>

#include "io/atomic_file.hpp"

namespace ecm::mpm {

namespace {

// Shortest round-trip form of a double (the .pvd index and the TIME field).
void put(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// VTK XML with the arrays in one raw appended block (header_type UInt64, little endian): each
// array is its byte count then its values, so a snapshot is written at memory speed (ASCII
// formatting of every number cost ~25 % of a DEN coarse run at the scene's output interval).
class AppendedArrays {
 public:
  // The XML tag of an array whose values come next in the appended block.
  template <class T, class F>
  void add(std::string& xml, const char* type, const char* name, int components, std::size_t n, F&& value) {
    xml += "        <DataArray type=\"";
    xml += type;
    xml += "\" Name=\"";
    xml += name;
    xml += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"appended\" offset=\"" +
           std::to_string(data_.size()) + "\"/>\n";
    const std::uint64_t bytes = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(components) * sizeof(T);
    append(&bytes, sizeof bytes);
    const std::size_t at = data_.size();
    data_.resize(at + bytes);
    T* out = reinterpret_cast<T*>(data_.data() + at);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < components; ++c) *out++ = static_cast<T>(value(i, c));
  }
  const std::string& data() const { return data_; }

 private:
  void append(const void* p, std::size_t bytes) { data_.append(static_cast<const char*>(p), bytes); }
  std::string data_;
};

static_assert(std::endian::native == std::endian::little, "the VTU files declare byte_order LittleEndian");

}  // namespace

void writeVtu(const Solver& solver, const std::filesystem::path& path) {
  const Particles& p = solver.particles();
  const std::size_t n = p.size();
  auto band = [&](std::size_t i) -> const BandState* {
    return p.band[i] >= 0 ? &p.bands[static_cast<std::size_t>(p.band[i])] : nullptr;
  };
  AppendedArrays a;
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<!-- ecm-mpm particles; units: mm, N, MPa, t, s -->\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">";
  put(out, solver.time());
  out += "</DataArray>\n    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">\n";
  out += "      <PointData Scalars=\"damage\" Vectors=\"displacement\">\n";
  a.add<double>(out, "Float64", "displacement", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.displacement[i][c] : 0.0; });
  a.add<double>(out, "Float64", "velocity", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.velocity[i][c] : 0.0; });
  a.add<double>(out, "Float64", "stress", 3, n, [&](std::size_t i, int c) { return p.stress[i][c]; });  // xx, yy, xy (MPa)
  a.add<double>(out, "Float64", "strain", 3, n, [&](std::size_t i, int c) { return p.strain[i][c]; });  // xx, yy, gamma_xy
  a.add<double>(out, "Float64", "damage", 1, n, [&](std::size_t i, int) { return solver.damage(i); });
  a.add<double>(out, "Float64", "crack_normal", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->crackNormal[c] : 0.0;
  });
  a.add<double>(out, "Float64", "jump", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->jump[c] : 0.0;
  });
  a.add<double>(out, "Float64", "opening", 1, n, [&](std::size_t i, int) {
    const BandState* b = band(i);
    return b ? b->normalJump() : 0.0;
  });
  a.add<double>(out, "Float64", "material", 1, n, [&](std::size_t i, int) { return static_cast<double>(p.material[i]); });
  a.add<double>(out, "Float64", "cracked", 1, n, [&](std::size_t i, int) { return p.band[i] >= 0 ? 1.0 : 0.0; });
  out += "      </PointData>\n      <Points>\n";
  a.add<double>(out, "Float64", "position", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.position[i][c] : 0.0; });
  out += "      </Points>\n      <Cells>\n";
  a.add<std::int64_t>(out, "Int64", "connectivity", 1, n, [](std::size_t i, int) { return i; });
  a.add<std::int64_t>(out, "Int64", "offsets", 1, n, [](std::size_t i, int) { return i + 1; });
  a.add<std::uint8_t>(out, "UInt8", "types", 1, n, [](std::size_t, int) { return 1; });  // VTK_VERTEX
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  out += a.data();
  out += "\n  </AppendedData>\n</VTKFile>\n";
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
