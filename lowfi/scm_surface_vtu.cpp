#include "lowfi/scm_surface_vtu.hpp"

#include <cstdint>
#include <unordered_map>

#include "core/vtu_writer.hpp"

namespace terracal::lowfi {

std::size_t write_scm_surface_vtu(const std::filesystem::path& file, const ScmTerrain& terrain, double time) {
  const ScmNodeGrid& grid = terrain.grid();
  const double h = terrain.settings().grid;
  std::vector<double> xyz;
  VtuPointData sinkage{"plastic_sinkage", 1, {}}, sigma{"pressure", 1, {}}, tau{"shear_stress", 1, {}};
  std::unordered_map<ScmNodeGrid::Key, std::int64_t> index;
  for (const auto& [key, node] : grid.nodes()) {
    const int i = int(key >> 32), j = int(std::int32_t(std::uint32_t(key & 0xffffffff)));
    index[key] = std::int64_t(xyz.size() / 3);
    xyz.insert(xyz.end(), {i * h, j * h, grid.free_surface(i, j)});
    sinkage.values.push_back(float(node.plastic_sinkage));
    sigma.values.push_back(float(node.sigma));
    tau.values.push_back(float(node.tau));
  }
  VtuCells cells;
  for (const auto& [key, corner] : index) {
    const int i = int(key >> 32), j = int(std::int32_t(std::uint32_t(key & 0xffffffff)));
    const auto right = index.find(ScmNodeGrid::key(i + 1, j)), up = index.find(ScmNodeGrid::key(i, j + 1)),
               diagonal = index.find(ScmNodeGrid::key(i + 1, j + 1));
    if (right == index.end() || up == index.end() || diagonal == index.end()) continue;
    cells.add(VtuCellType::quad, {corner, right->second, diagonal->second, up->second});
  }
  write_vtu_cells(file, xyz, cells, {sinkage, sigma, tau}, {}, time);
  return index.size();
}

}  // namespace terracal::lowfi
