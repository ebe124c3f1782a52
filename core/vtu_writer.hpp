#pragma once
// Point clouds (SPH particles) and meshes of cells (a vehicle's bodies) as VTK XML UnstructuredGrid
// files (.vtu) and ParaView collections (.pvd), written with the standard library only so no VTK
// install is needed to produce them.
// Data arrays are inline base64 "binary" (header_type UInt32, LittleEndian): about a third larger
// than raw appended data but still valid XML, and far smaller and faster than ASCII.
// Both writers go through a hidden temporary file and a rename (core/atomic_file.hpp), so ParaView
// watching a folder never sees a half-written file.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace terracal {

// One named field per point (or, for write_vtu_cells's cell fields, per cell).
struct VtuPointData {
  std::string name;
  // 1 (scalar), 3 (vector) or 6 (symmetric tensor in ParaView's order xx, yy, zz, xy, yz, xz).
  int components = 1;
  std::vector<float> values;  // n_points * components, point-major
};

// Writes the points `xyz` (x,y,z triples, stored as Float32) with one VTK_VERTEX cell per point and
// the point-data arrays; `time` goes into the FieldData array "TimeValue" (read by ParaView).
// Throws InputError (before touching any file) when xyz.size() is not a multiple of 3, a field's
// size is not n_points * components, components is not 1, 3 or 6, or a name is empty or repeated;
// also when an array exceeds the 4 GiB that a UInt32 header can describe. Throws RunError when the
// file cannot be written; the final name is then untouched and no temporary is left.
void write_vtu_points(const std::filesystem::path& file, const std::vector<double>& xyz,
                      const std::vector<VtuPointData>& fields, double time = 0.0);

// The cell types write_vtu_cells takes (VTK's numbers).
enum class VtuCellType : std::uint8_t { vertex = 1, line = 3, triangle = 5, polygon = 7, quad = 9, hexahedron = 12 };

// Cells of an unstructured grid: cell k joins the points connectivity[offsets[k - 1] .. offsets[k])
// (from 0 for the first), in VTK's order for its type (a hexahedron: the bottom face, then the top
// face above it, both counterclockwise seen from the top).
struct VtuCells {
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets;  // the running end of each cell in connectivity
  std::vector<VtuCellType> types;

  std::size_t size() const { return types.size(); }
  void add(VtuCellType type, std::initializer_list<std::int64_t> points) { add(type, std::vector(points)); }
  void add(VtuCellType type, const std::vector<std::int64_t>& points) {
    connectivity.insert(connectivity.end(), points.begin(), points.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(type);
  }
};

// Writes the points `xyz` (x,y,z triples, stored as Float32), the cells, the point-data arrays
// (n_points * components values each) and the cell-data arrays (n_cells * components each) as
// write_vtu_points does. Throws InputError (before touching any file) as write_vtu_points does, and
// also when the cells' arrays disagree in length, a cell names a point that does not exist or has a
// number of points its type cannot have (vertex 1, line 2, triangle 3, quad 4, hexahedron 8, polygon 3
// or more). RunError as write_vtu_points.
void write_vtu_cells(const std::filesystem::path& file, const std::vector<double>& xyz, const VtuCells& cells,
                     const std::vector<VtuPointData>& point_fields, const std::vector<VtuPointData>& cell_fields,
                     double time = 0.0);

// Writes a ParaView collection listing (time, file name relative to the .pvd's folder) pairs in
// the order given. Throws InputError for an empty file name, RunError when the write fails.
void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& entries);

// The (time, file name) entries of a collection that write_pvd wrote, in order; empty when the file
// does not exist. A resumed run continues the collection of the run it resumes. Throws InputError for
// an entry it cannot read (naming the file and the line).
std::vector<std::pair<double, std::string>> read_pvd(const std::filesystem::path& file);

}  // namespace terracal
