#include "highfi/vehicle/vehicle_vtu.hpp"

#include <algorithm>
#include <cmath>

namespace terracal::vehicle {
namespace {

using mb::RigidBody;

// Builds the mesh one part at a time: points with their body's velocity, cells with their ids.
struct MeshBuilder {
  VehicleMesh m;

  std::int64_t point(const RigidBody& b, const Vec3& local) {
    const Vec3 x = b.point(local), u = b.point_velocity(local);
    m.xyz.insert(m.xyz.end(), {x.x(), x.y(), x.z()});
    m.velocity.insert(m.velocity.end(), {float(u.x()), float(u.y()), float(u.z())});
    return std::int64_t(m.xyz.size() / 3 - 1);
  }
  void cell(VtuCellType type, const std::vector<std::int64_t>& points, int body, VtuPart part) {
    m.cells.add(type, points);
    m.body.push_back(body);
    m.name_id.push_back(int(part));
  }
};

// The points each body carries, in its own frame: its joints' points, its springs', shocks' and
// bushings' ends, each once.
std::vector<std::vector<Vec3>> attachment_points(const mb::MbSystem& s) {
  std::vector<std::vector<Vec3>> out(s.bodies.size());
  const auto add = [&](int b, const Vec3& p) {
    if (b < 0 || std::size_t(b) >= out.size()) return;
    auto& list = out[std::size_t(b)];
    if (std::none_of(list.begin(), list.end(), [&](const Vec3& q) { return (q - p).norm() < 1e-9; })) list.push_back(p);
  };
  for (const mb::Joint& j : s.joints) add(j.i, j.si), add(j.j, j.sj);
  for (const mb::SpringDamper& e : s.springs) add(e.i, e.si), add(e.j, e.sj);
  for (const mb::Bushing& e : s.bushings) add(e.i, e.si), add(e.j, e.sj);
  return out;
}

// A closed cylinder about the body's y axis through its centre: the side's quads, then both end caps.
void add_wheel(MeshBuilder& out, const RigidBody& b, int body, double radius, double width, int facets) {
  facets = std::max(facets, 3);
  std::vector<std::int64_t> outer, inner;
  for (int k = 0; k < facets; ++k) {
    const double a = 2 * M_PI * k / facets;
    const Vec3 rim(radius * std::cos(a), 0, radius * std::sin(a));
    outer.push_back(out.point(b, rim + Vec3(0, 0.5 * width, 0)));
    inner.push_back(out.point(b, rim - Vec3(0, 0.5 * width, 0)));
  }
  for (int k = 0; k < facets; ++k) {
    const int n = (k + 1) % facets;
    out.cell(VtuCellType::quad, {outer[k], outer[n], inner[n], inner[k]}, body, VtuPart::wheel);
  }
  out.cell(VtuCellType::polygon, outer, body, VtuPart::wheel);
  std::reverse(inner.begin(), inner.end());  // both caps facing out
  out.cell(VtuCellType::polygon, inner, body, VtuPart::wheel);
}

// The box, in the body's frame, around its centre of mass and `points` (each side at least 1 cm).
void add_box(MeshBuilder& out, const RigidBody& b, int body, const std::vector<Vec3>& points) {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (int d = 0; d < 3; ++d)
    if (hi[d] - lo[d] < 0.01) {
      const double mid = 0.5 * (lo[d] + hi[d]);
      lo[d] = mid - 0.005, hi[d] = mid + 0.005;
    }
  std::vector<std::int64_t> corners;
  for (const double z : {lo.z(), hi.z()})
    for (const auto& [x, y] : {std::pair{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}})
      corners.push_back(out.point(b, Vec3(x, y, z)));
  out.cell(VtuCellType::hexahedron, corners, body, VtuPart::chassis);
}

// A line between each two of the points (a vertex where there is one).
void add_frame(MeshBuilder& out, const RigidBody& b, int body, std::vector<Vec3> points, VtuPart part) {
  if (points.size() < 2) points.insert(points.begin(), Vec3::Zero());  // the centre of mass
  std::vector<std::int64_t> ids;
  for (const Vec3& p : points) ids.push_back(out.point(b, p));
  if (ids.size() == 1) out.cell(VtuCellType::vertex, ids, body, part);
  for (std::size_t a = 0; a < ids.size(); ++a)
    for (std::size_t c = a + 1; c < ids.size(); ++c) out.cell(VtuCellType::line, {ids[a], ids[c]}, body, part);
}

// A line from a point of body i to a point of body j (a distance joint, a spring).
void add_link(MeshBuilder& out, const mb::MbSystem& s, int i, const Vec3& si, int j, const Vec3& sj, VtuPart part) {
  const std::int64_t a = out.point(s.bodies[std::size_t(i)], si), c = out.point(s.bodies[std::size_t(j)], sj);
  out.cell(VtuCellType::line, {a, c}, -1, part);
}

}  // namespace

double drawn_tire_width(const FullVehicleSpec& spec) {
  return spec.scm_wheel.width > 0 ? spec.scm_wheel.width : spec.tire.unloaded_radius * (12.5 / 18.5);
}

VehicleMesh vehicle_mesh(const FullVehicle& v, int wheel_facets) {
  const mb::MbSystem& s = v.system();
  // What each body is.
  std::vector<VtuPart> part(s.bodies.size(), VtuPart::other_body);
  part[std::size_t(v.chassis())] = VtuPart::chassis;
  for (const WishboneSide& w : v.corners()) {
    part[std::size_t(w.spindle)] = VtuPart::wheel;
    part[std::size_t(w.upright)] = VtuPart::upright;
    part[std::size_t(w.upper_arm)] = VtuPart::upper_arm;
    part[std::size_t(w.lower_arm)] = VtuPart::lower_arm;
  }
  if (v.has_steering()) {
    part[std::size_t(v.steering_link())] = VtuPart::steering_link;  // the Pitman arm's link or the rack
    if (!v.spec().rack_steering) part[std::size_t(v.steering().arm)] = VtuPart::pitman_arm;
  }
  const std::vector<std::vector<Vec3>> points = attachment_points(s);
  const double radius = v.spec().tire.unloaded_radius, width = drawn_tire_width(v.spec());
  MeshBuilder out;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const RigidBody& body = s.bodies[b];
    if (part[b] == VtuPart::wheel)
      add_wheel(out, body, int(b), radius, width, wheel_facets);
    else if (part[b] == VtuPart::chassis)
      add_box(out, body, int(b), points[b]);
    else
      add_frame(out, body, int(b), points[b], part[b]);
  }
  // The distance joints (tie rods, the idler) and the springs and shocks, each a line.
  for (std::size_t k = 0; k < s.joints.size(); ++k) {
    const mb::Joint& j = s.joints[k];
    if (j.type != mb::JointType::distance) continue;
    VtuPart p = VtuPart::distance_link;
    if (std::any_of(v.corners().begin(), v.corners().end(),
                    [&](const WishboneSide& w) { return w.tierod_joint == int(k); }))
      p = VtuPart::tie_rod;
    else if (v.has_steering() && (j.i == v.steering_link() || j.j == v.steering_link()))
      p = VtuPart::idler;
    add_link(out, s, j.i, j.si, j.j, j.sj, p);
  }
  for (const mb::SpringDamper& e : s.springs) add_link(out, s, e.i, e.si, e.j, e.sj, VtuPart::spring);
  return std::move(out.m);
}

std::vector<std::string> vehicle_body_names(const FullVehicle& v) {
  std::vector<std::string> names;
  for (const RigidBody& b : v.system().bodies) names.push_back(b.name);
  return names;
}

void write_vehicle_vtu(const std::filesystem::path& file, const FullVehicle& v, double time) {
  const VehicleMesh m = vehicle_mesh(v);
  const auto floats = [](const std::vector<int>& ids) { return std::vector<float>(ids.begin(), ids.end()); };
  write_vtu_cells(file, m.xyz, m.cells, {{"velocity", 3, m.velocity}},
                  {{"body", 1, floats(m.body)}, {"name_id", 1, floats(m.name_id)}}, time);
}

}  // namespace terracal::vehicle
