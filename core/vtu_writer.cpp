#include "core/vtu_writer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <locale>
#include <set>
#include <system_error>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal {

namespace {

namespace fs = std::filesystem;

// The arrays are copied from memory as they are and the file says byte_order="LittleEndian".
static_assert(std::endian::native == std::endian::little, "vtu_writer assumes a little-endian host");

// Shortest text that reads back to the same double; independent of the global locale.
std::string number_text(double v) {
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

// Names and file names end up in attributes; a '"' or '&' must not break the XML.
std::string xml_escape(const std::string& s) {
  std::string r;
  r.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      case '\'':
        r += "&apos;";
        break;
      default:
        r += c;
    }
  }
  return r;
}

// Base64 straight into the stream. VTK decodes the UInt32 header and the data of an uncompressed
// inline array as ONE base64 stream, so the encoder must carry the 1-2 bytes that do not fill a
// 3-byte group from one put() to the next instead of padding each piece.
class Base64Writer {
 public:
  explicit Base64Writer(std::ostream& out) : out_(out) {}

  void put(const void* data, std::size_t size) {
    auto p = static_cast<const unsigned char*>(data);
    while (size > 0 && npend_ != 0) {  // complete a group started by the previous piece
      pend_[npend_++] = *p++;
      --size;
      if (npend_ == 3) {
        group(pend_.data(), 3);
        npend_ = 0;
      }
    }
    for (; size >= 3; p += 3, size -= 3) group(p, 3);
    for (; size > 0; --size) pend_[npend_++] = *p++;
  }

  void finish() {
    if (npend_ > 0) group(pend_.data(), npend_);
    npend_ = 0;
    out_.write(buf_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }

 private:
  void group(const unsigned char* g, int n) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const std::uint32_t v = (std::uint32_t{g[0]} << 16) | (n > 1 ? std::uint32_t{g[1]} << 8 : 0u) | (n > 2 ? g[2] : 0u);
    if (used_ + 4 > buf_.size()) {
      out_.write(buf_.data(), static_cast<std::streamsize>(used_));
      used_ = 0;
    }
    buf_[used_++] = kAlphabet[(v >> 18) & 63];
    buf_[used_++] = kAlphabet[(v >> 12) & 63];
    buf_[used_++] = n > 1 ? kAlphabet[(v >> 6) & 63] : '=';
    buf_[used_++] = n > 2 ? kAlphabet[v & 63] : '=';
  }

  std::ostream& out_;
  std::array<unsigned char, 3> pend_{};
  int npend_ = 0;
  std::array<char, 64 * 1024> buf_{};  // few large writes instead of one per group
  std::size_t used_ = 0;
};

// One inline binary DataArray; `feed` hands the payload (exactly `bytes` bytes) to the encoder,
// in pieces, so no array is ever copied whole. Sizes were checked against UInt32 beforehand.
template <class Feed>
void data_array(std::ostream& out, const char* type, const std::string& name, int components, std::uint64_t bytes,
                Feed&& feed) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << xml_escape(name) << "\" NumberOfComponents=\""
      << components << "\" format=\"binary\">\n          ";
  Base64Writer b64(out);
  const auto header = static_cast<std::uint32_t>(bytes);
  b64.put(&header, sizeof header);
  feed(b64);
  b64.finish();
  out << "\n        </DataArray>\n";
}

// Chunk size for arrays generated on the fly (points as Float32, connectivity, offsets, types).
constexpr std::size_t kChunk = 4096;

std::string where_of(const fs::path& file) { return "VTU file '" + file.string() + "'"; }

// The points and the time; returns the bytes of the points' array (Float32, 12 per point).
std::uint64_t validate_points(const fs::path& file, const std::vector<double>& xyz, double time) {
  const std::string where = where_of(file);
  if (xyz.size() % 3 != 0)
    throw InputError(where + ": " + std::to_string(xyz.size()) + " coordinates is not a multiple of 3 (x,y,z)");
  if (!std::isfinite(time)) throw InputError(where + ": the time " + number_text(time) + " is not finite");
  return xyz.size() / 3 * 12;
}

// The fields of `n` points (or cells, `what`); returns the bytes of the widest one.
std::uint64_t validate_fields(const fs::path& file, const std::vector<VtuPointData>& fields, std::uint64_t n,
                              const std::string& what) {
  const std::string where = where_of(file);
  std::uint64_t widest = 0;
  std::set<std::string> names;
  for (const auto& f : fields) {
    const std::string field = where + ": " + what + " field '" + f.name + "'";
    if (f.name.empty()) throw InputError(where + ": a " + what + " field has an empty name");
    if (!names.insert(f.name).second) throw InputError(field + " appears more than once");
    if (f.components != 1 && f.components != 3 && f.components != 6)
      throw InputError(field + " has " + std::to_string(f.components) +
                       " components; expected 1 (scalar), 3 (vector) or 6 (symmetric tensor)");
    if (f.values.size() != n * static_cast<std::uint64_t>(f.components))
      throw InputError(field + " has " + std::to_string(f.values.size()) + " values; expected " + std::to_string(n) +
                       " " + what + "s x " + std::to_string(f.components) +
                       " components = " + std::to_string(n * f.components));
    widest = std::max<std::uint64_t>(widest, n * 4 * f.components);
  }
  return widest;
}

void check_array_size(const fs::path& file, std::uint64_t widest, std::uint64_t n, const std::string& what) {
  if (widest > std::numeric_limits<std::uint32_t>::max())
    throw InputError(where_of(file) + ": " + std::to_string(n) + " " + what +
                     "s give an array over 4 GiB, more than a UInt32 header can describe; split the cloud");
}

// The number of points a cell of this type takes: exactly `n`, or at least `n` when `at_least`.
std::pair<std::size_t, bool> points_of(VtuCellType type) {
  switch (type) {
    case VtuCellType::vertex:
      return {1, false};
    case VtuCellType::line:
      return {2, false};
    case VtuCellType::triangle:
      return {3, false};
    case VtuCellType::polygon:
      return {3, true};
    case VtuCellType::quad:
      return {4, false};
    case VtuCellType::hexahedron:
      return {8, false};
  }
  return {0, false};
}

// Returns the bytes of the widest of the cells' arrays (Int64 connectivity and offsets).
std::uint64_t validate_cells(const fs::path& file, const VtuCells& c, std::uint64_t n_points) {
  const std::string where = where_of(file) + ": ";
  if (c.offsets.size() != c.types.size())
    throw InputError(where + std::to_string(c.offsets.size()) + " cell offsets for " + std::to_string(c.types.size()) +
                     " cell types; expected one of each per cell");
  std::int64_t begin = 0;
  for (std::size_t k = 0; k < c.types.size(); ++k) {
    const std::string cell = where + "cell " + std::to_string(k);
    const std::int64_t end = c.offsets[k];
    if (end <= begin || end > static_cast<std::int64_t>(c.connectivity.size()))
      throw InputError(cell + ": offset " + std::to_string(end) + " is not in (" + std::to_string(begin) + ", " +
                       std::to_string(c.connectivity.size()) + "]");
    const auto [want, at_least] = points_of(c.types[k]);
    const auto have = static_cast<std::size_t>(end - begin);
    if (want == 0) throw InputError(cell + ": unknown cell type " + std::to_string(int(c.types[k])));
    if (at_least ? have < want : have != want)
      throw InputError(cell + " (VTK type " + std::to_string(int(c.types[k])) + ") has " + std::to_string(have) +
                       " points; expected " + (at_least ? "at least " : "") + std::to_string(want));
    for (std::int64_t i = begin; i < end; ++i)
      if (c.connectivity[std::size_t(i)] < 0 || static_cast<std::uint64_t>(c.connectivity[std::size_t(i)]) >= n_points)
        throw InputError(cell + " names point " + std::to_string(c.connectivity[std::size_t(i)]) + " of " +
                         std::to_string(n_points));
    begin = end;
  }
  if (static_cast<std::size_t>(begin) != c.connectivity.size())
    throw InputError(where + std::to_string(c.connectivity.size() - std::size_t(begin)) +
                     " connectivity entries after the last cell's end");
  return 8 * std::max<std::uint64_t>(c.connectivity.size(), c.offsets.size());
}

void validate(const fs::path& file, const std::vector<double>& xyz, const std::vector<VtuPointData>& fields,
              double time) {
  const std::uint64_t n = xyz.size() / 3;
  const std::uint64_t points = validate_points(file, xyz, time);
  // Float32 points take 12 bytes per point, more than Int64 connectivity's 8.
  check_array_size(file, std::max(points, validate_fields(file, fields, n, "point")), n, "point");
}

// Writes the grid to a temporary name and renames it: `cells(out)` writes the <Cells> arrays.
template <class WriteCells>
void write_grid(const fs::path& file, const std::vector<double>& xyz, std::size_t n_cells,
                const std::vector<VtuPointData>& point_fields, const std::vector<VtuPointData>& cell_fields,
                double time, WriteCells&& cells) {
  const std::string final_path = file.string();
  const std::string tmp = temporary_path_for(final_path);

  // Removes the temporary on any exception thrown while writing (commit_file cleans up itself).
  struct TmpGuard {
    const std::string& path;
    bool armed = true;
    ~TmpGuard() {
      std::error_code ignored;
      if (armed) fs::remove(path, ignored);
    }
  } guard{tmp};

  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out) {
    const int err = errno;
    throw RunError("cannot write '" + final_path + "': cannot create '" + tmp + "': " + std::strerror(err));
  }
  out.imbue(std::locale::classic());  // no thousands separators in the counts, whatever the global locale
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n"
         "  <UnstructuredGrid>\n"
         "    <FieldData>\n"
         "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">\n"
         "        "
      << number_text(time)
      << "\n"
         "      </DataArray>\n"
         "    </FieldData>\n"
         "    <Piece NumberOfPoints=\""
      << xyz.size() / 3 << "\" NumberOfCells=\"" << n_cells
      << "\">\n"
         "      <PointData>\n";
  for (const auto& f : point_fields)
    data_array(out, "Float32", f.name, f.components, f.values.size() * sizeof(float),
               [&](Base64Writer& b) { b.put(f.values.data(), f.values.size() * sizeof(float)); });
  out << "      </PointData>\n";
  if (!cell_fields.empty()) {
    out << "      <CellData>\n";
    for (const auto& f : cell_fields)
      data_array(out, "Float32", f.name, f.components, f.values.size() * sizeof(float),
                 [&](Base64Writer& b) { b.put(f.values.data(), f.values.size() * sizeof(float)); });
    out << "      </CellData>\n";
  }
  out << "      <Points>\n";
  data_array(out, "Float32", "Points", 3, xyz.size() * sizeof(float), [&](Base64Writer& b) {
    std::array<float, 3 * kChunk> chunk;
    for (std::size_t i = 0; i < xyz.size(); i += chunk.size()) {
      const std::size_t m = std::min(chunk.size(), xyz.size() - i);
      std::transform(xyz.begin() + i, xyz.begin() + i + m, chunk.begin(),
                     [](double v) { return static_cast<float>(v); });
      b.put(chunk.data(), m * sizeof(float));
    }
  });
  out << "      </Points>\n"
         "      <Cells>\n";
  cells(out);
  out << "      </Cells>\n"
         "    </Piece>\n"
         "  </UnstructuredGrid>\n"
         "</VTKFile>\n";
  out.close();  // a full disk often shows only when the buffer is flushed
  if (!out) throw RunError("cannot write '" + final_path + "': writing '" + tmp + "' failed");
  guard.armed = false;
  commit_file(tmp, final_path);
}

}  // namespace

void write_vtu_points(const fs::path& file, const std::vector<double>& xyz, const std::vector<VtuPointData>& fields,
                      double time) {
  validate(file, xyz, fields, time);  // before any file exists
  const std::size_t n = xyz.size() / 3;
  write_grid(file, xyz, n, fields, {}, time, [n](std::ostream& out) {
    // Vertex i is point i; offsets are the running end of each one-point cell.
    auto counting = [n](std::int64_t first) {
      return [n, first](Base64Writer& b) {
        std::array<std::int64_t, kChunk> chunk;
        for (std::size_t i = 0; i < n; i += kChunk) {
          const std::size_t m = std::min(kChunk, n - i);
          for (std::size_t k = 0; k < m; ++k) chunk[k] = first + static_cast<std::int64_t>(i + k);
          b.put(chunk.data(), m * sizeof(std::int64_t));
        }
      };
    };
    data_array(out, "Int64", "connectivity", 1, n * sizeof(std::int64_t), counting(0));
    data_array(out, "Int64", "offsets", 1, n * sizeof(std::int64_t), counting(1));
    data_array(out, "UInt8", "types", 1, n, [n](Base64Writer& b) {
      std::array<std::uint8_t, kChunk> vertex;
      vertex.fill(1);  // VTK_VERTEX
      for (std::size_t i = 0; i < n; i += kChunk) b.put(vertex.data(), std::min(kChunk, n - i));
    });
  });
}

void write_vtu_cells(const fs::path& file, const std::vector<double>& xyz, const VtuCells& cells,
                     const std::vector<VtuPointData>& point_fields, const std::vector<VtuPointData>& cell_fields,
                     double time) {
  // Everything checked before any file exists.
  const std::uint64_t n = xyz.size() / 3;
  const std::uint64_t points = validate_points(file, xyz, time);
  check_array_size(file, std::max(points, validate_fields(file, point_fields, n, "point")), n, "point");
  check_array_size(file,
                   std::max(validate_cells(file, cells, n), validate_fields(file, cell_fields, cells.size(), "cell")),
                   cells.size(), "cell");
  write_grid(file, xyz, cells.size(), point_fields, cell_fields, time, [&cells](std::ostream& out) {
    data_array(out, "Int64", "connectivity", 1, cells.connectivity.size() * sizeof(std::int64_t), [&](Base64Writer& b) {
      b.put(cells.connectivity.data(), cells.connectivity.size() * sizeof(std::int64_t));
    });
    data_array(out, "Int64", "offsets", 1, cells.offsets.size() * sizeof(std::int64_t),
               [&](Base64Writer& b) { b.put(cells.offsets.data(), cells.offsets.size() * sizeof(std::int64_t)); });
    static_assert(sizeof(VtuCellType) == 1);
    data_array(out, "UInt8", "types", 1, cells.types.size(),
               [&](Base64Writer& b) { b.put(cells.types.data(), cells.types.size()); });
  });
}

void write_pvd(const fs::path& file, const std::vector<std::pair<double, std::string>>& entries) {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [time, name] : entries) {
    if (name.empty()) throw InputError("PVD file '" + file.string() + "': an entry has an empty file name");
    if (!std::isfinite(time))
      throw InputError("PVD file '" + file.string() + "': entry '" + name + "' has a non-finite time");
    text += "    <DataSet timestep=\"" + number_text(time) + "\" group=\"\" part=\"0\" file=\"" + xml_escape(name) +
            "\"/>\n";
  }
  text += "  </Collection>\n</VTKFile>\n";
  write_text_atomically(file.string(), text);
}

std::vector<std::pair<double, std::string>> read_pvd(const fs::path& file) {
  std::vector<std::pair<double, std::string>> entries;
  std::ifstream in(file);
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (line.find("<DataSet ") == std::string::npos) continue;
    // Our own writer's attributes: timestep="T" ... file="NAME" (names with no characters to escape).
    const auto t = line.find("timestep=\""), f = line.find("file=\"");
    const auto t_end = t == std::string::npos ? t : line.find('"', t + 10);
    const auto f_end = f == std::string::npos ? f : line.find('"', f + 6);
    double time = 0;
    const bool ok = t_end != std::string::npos && f_end != std::string::npos &&
                    std::from_chars(line.data() + t + 10, line.data() + t_end, time).ptr == line.data() + t_end;
    if (!ok)
      throw InputError(file.string() + ":" + std::to_string(line_no) +
                       ": not a DataSet entry of a terracal collection");
    entries.emplace_back(time, line.substr(f + 6, f_end - f - 6));
  }
  return entries;
}

}  // namespace terracal
