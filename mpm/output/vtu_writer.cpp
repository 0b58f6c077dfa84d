#include "mpm/output/vtu_writer.hpp"

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

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
// Field values are Float32 (for looking at; particles_final.csv and checkpoints keep every
// digit), positions Float64, ids and flags the smallest integer type: 115 bytes per particle.
class AppendedArrays {
 public:
  explicit AppendedArrays(std::string& data) : data_(data) { data_.clear(); }
  // The XML tag of an array whose values come next in the appended block.
  template <class T, class F>
  void add(std::string& xml, const char* name, int components, std::size_t n, F&& value) {
    xml += "        <DataArray type=\"";
    xml += vtkType<T>();
    xml += "\" Name=\"";
    xml += name;
    xml += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"appended\" offset=\"" +
           std::to_string(data_.size()) + "\"/>\n";
    const std::uint64_t bytes = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(components) * sizeof(T);
    data_.append(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    const std::size_t at = data_.size();
    data_.resize(at + bytes);
    char* out = data_.data() + at;
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < components; ++c, out += sizeof(T)) {
        const T v = static_cast<T>(value(i, c));
        std::memcpy(out, &v, sizeof v);
      }
  }

 private:
  template <class T>
  static const char* vtkType() {
    if constexpr (std::is_same_v<T, double>) return "Float64";
    if constexpr (std::is_same_v<T, float>) return "Float32";
    if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
    if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
  }
  std::string& data_;
};

static_assert(std::endian::native == std::endian::little, "the VTU files declare byte_order LittleEndian");

}  // namespace

void writeVtu(const Particles& p, double time, const std::filesystem::path& path, std::string* scratch) {
  const std::size_t n = p.size();
  if (n > static_cast<std::size_t>(INT32_MAX)) throw std::length_error("VTU snapshot: more than 2^31 particles");
  auto band = [&](std::size_t i) -> const BandState* {
    return p.band[i] >= 0 ? &p.bands[static_cast<std::size_t>(p.band[i])] : nullptr;
  };
  std::string own;
  AppendedArrays a(scratch ? *scratch : own);
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<!-- ecm-mpm particles; units: mm, N, MPa, t, s -->\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">";
  put(out, time);
  out += "</DataArray>\n    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">\n";
  out += "      <PointData Scalars=\"damage\" Vectors=\"displacement\">\n";
  a.add<float>(out, "displacement", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.displacement(i)[c] : 0.0; });
  a.add<float>(out, "velocity", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.velocity[i][c] : 0.0; });
  a.add<float>(out, "stress", 3, n, [&](std::size_t i, int c) { return p.stress[i][c]; });  // xx, yy, xy (MPa)
  a.add<float>(out, "strain", 3, n, [&](std::size_t i, int c) { return p.strain[i][c]; });  // xx, yy, gamma_xy
  a.add<float>(out, "damage", 1, n, [&](std::size_t i, int) { return p.damage(i); });
  a.add<float>(out, "crack_normal", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->crackNormal[c] : 0.0;
  });
  a.add<float>(out, "jump", 3, n, [&](std::size_t i, int c) {
    const BandState* b = band(i);
    return b && c < 2 ? b->jump[c] : 0.0;
  });
  a.add<float>(out, "opening", 1, n, [&](std::size_t i, int) {
    const BandState* b = band(i);
    return b ? b->normalJump() : 0.0;
  });
  if (!p.secondBand.empty()) {  // second_band: orthogonal (docs/model.md)
    a.add<float>(out, "damage_2", 1, n, [&](std::size_t i, int) {
      const BandState* b = p.secondBandOf(i);
      return b ? b->damage() : 0.0;
    });
    a.add<float>(out, "crack_normal_2", 3, n, [&](std::size_t i, int c) {
      const BandState* b = p.secondBandOf(i);
      return b && c < 2 ? b->crackNormal[c] : 0.0;
    });
    a.add<float>(out, "opening_2", 1, n, [&](std::size_t i, int) {
      const BandState* b = p.secondBandOf(i);
      return b ? b->normalJump() : 0.0;
    });
  }
  a.add<std::uint8_t>(out, "material", 1, n, [&](std::size_t i, int) { return p.material[i]; });
  a.add<std::uint8_t>(out, "cracked", 1, n, [&](std::size_t i, int) { return p.band[i] >= 0 ? 1 : 0; });
  out += "      </PointData>\n      <Points>\n";
  a.add<double>(out, "position", 3, n, [&](std::size_t i, int c) { return c < 2 ? p.position[i][c] : 0.0; });
  out += "      </Points>\n      <Cells>\n";
  a.add<std::int32_t>(out, "connectivity", 1, n, [](std::size_t i, int) { return i; });
  a.add<std::int32_t>(out, "offsets", 1, n, [](std::size_t i, int) { return i + 1; });
  a.add<std::uint8_t>(out, "types", 1, n, [](std::size_t, int) { return 1; });  // VTK_VERTEX
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  io::writeFileAtomically(path, {out, scratch ? *scratch : own, "\n  </AppendedData>\n</VTKFile>\n"});
}

VtuSeries::VtuSeries(std::filesystem::path dir, std::string stem) : dir_(std::move(dir)), stem_(std::move(stem)) {}

std::string VtuSeries::fileName(std::size_t index) const {
  char name[64];
  std::snprintf(name, sizeof name, "_%05zu.vtu", index);
  return stem_ + name;
}

void VtuSeries::add(const Particles& particles, double time) {
  const std::string file = fileName(entries_.size());
  writeVtu(particles, time, dir_ / file, &scratch_);
  entries_.emplace_back(time, file);
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
