// The ParaView snapshot of the full vehicle (highfi/vehicle/vehicle_vtu.hpp), on the HMMWV preset as
// built: one closed cylinder of the tire's radius about each spindle's axis, the chassis box around the
// points it carries, each other body's lines ending at its joints' points, the tie rods between their
// joint's ends, the point velocities of the bodies; and the file holding exactly that mesh.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "highfi/vehicle/vehicle_run.hpp"
#include "highfi/vehicle/vehicle_vtu.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/vtu_payload.hpp"

using namespace terracal;
using namespace terracal::vehicle;

namespace {

mb::Vec3 point_of(const VehicleMesh& m, std::int64_t k) {
  return {m.xyz[std::size_t(3 * k)], m.xyz[std::size_t(3 * k + 1)], m.xyz[std::size_t(3 * k + 2)]};
}

// The points of cell c.
std::vector<std::int64_t> cell_points(const VehicleMesh& m, std::size_t c) {
  const std::int64_t begin = c == 0 ? 0 : m.cells.offsets[c - 1], end = m.cells.offsets[c];
  return {m.cells.connectivity.begin() + begin, m.cells.connectivity.begin() + end};
}

// The world positions of the points body b carries: its joints' points and its springs' ends.
std::vector<mb::Vec3> attachments(const mb::MbSystem& s, int b, bool joints_only = false) {
  std::vector<mb::Vec3> out;
  const mb::RigidBody& body = s.bodies[std::size_t(b)];
  for (const mb::Joint& j : s.joints) {
    if (j.i == b) out.push_back(body.point(j.si));
    if (j.j == b) out.push_back(body.point(j.sj));
  }
  if (!joints_only)
    for (const mb::SpringDamper& e : s.springs) {
      if (e.i == b) out.push_back(body.point(e.si));
      if (e.j == b) out.push_back(body.point(e.sj));
    }
  return out;
}

double distance_to(const std::vector<mb::Vec3>& points, const mb::Vec3& x) {
  double best = INFINITY;
  for (const auto& p : points) best = std::min(best, (p - x).norm());
  return best;
}

}  // namespace

TEST_CASE("vehicle vtu: the HMMWV's wheels are cylinders of the tire's radius about the spindles' axes",
          "[vehicle][vtu]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  const mb::MbSystem& s = v.system();
  const VehicleMesh m = vehicle_mesh(v, 32);
  REQUIRE(m.xyz.size() == m.velocity.size());
  REQUIRE(m.body.size() == m.cells.size());
  REQUIRE(m.name_id.size() == m.cells.size());
  const double r0 = spec.tire.unloaded_radius, width = drawn_tire_width(spec);
  CHECK(r0 == Approx(0.4699));
  CHECK(width == Approx(0.254).margin(1e-6));  // the preset's wheel.width, 10 in
  FullVehicleSpec unknown = spec;
  unknown.scm_wheel.width = 0;
  CHECK(drawn_tire_width(unknown) == Approx(0.3175).margin(1e-4));  // 12.5 in: the 37x12.5R16.5's proportions
  // Exactly the four spindles are drawn as wheels, each with 32 side quads and two end caps.
  std::map<int, std::vector<std::size_t>> wheel_cells;
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    if (m.name_id[c] == int(VtuPart::wheel)) wheel_cells[m.body[c]].push_back(c);
  REQUIRE(wheel_cells.size() == 4);
  for (const WishboneSide& w : v.corners()) {
    INFO("wheel of body " << w.spindle << " (" << s.bodies[std::size_t(w.spindle)].name << ")");
    REQUIRE(wheel_cells.count(w.spindle) == 1);
    const auto& cells = wheel_cells[w.spindle];
    int quads = 0, caps = 0;
    std::set<std::int64_t> points;
    for (const std::size_t c : cells) {
      const auto p = cell_points(m, c);
      points.insert(p.begin(), p.end());
      if (m.cells.types[c] == VtuCellType::quad) ++quads;
      if (m.cells.types[c] == VtuCellType::polygon) {
        ++caps;
        CHECK(p.size() == 32);
      }
    }
    CHECK(quads == 32);
    CHECK(caps == 2);
    CHECK(points.size() == 64);
    // Every point at the tire's radius from the spin axis (the spindle's y through its centre), half
    // the width to either side of the wheel's plane.
    const mb::RigidBody& sp = s.bodies[std::size_t(w.spindle)];
    const mb::Vec3 axis = sp.rotation().col(1);
    double worst_radius = 0, worst_side = 0;
    int outer = 0;
    for (const std::int64_t k : points) {
      const mb::Vec3 d = point_of(m, k) - sp.position;
      const double along = d.dot(axis);
      worst_radius = std::max(worst_radius, std::abs((d - along * axis).norm() - r0));
      worst_side = std::max(worst_side, std::abs(std::abs(along) - 0.5 * width));
      outer += along > 0;
    }
    CHECK(worst_radius < 1e-12);
    CHECK(worst_side < 1e-12);
    CHECK(outer == 32);
  }
}

TEST_CASE("vehicle vtu: the HMMWV's links end at their joints' points and the chassis box holds its own",
          "[vehicle][vtu]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  const mb::MbSystem& s = v.system();
  const VehicleMesh m = vehicle_mesh(v);
  std::map<int, int> lines_of;  // body -> its line cells
  std::map<int, std::set<std::int64_t>> ends_of;
  int tie_rods = 0, springs = 0, idlers = 0, boxes = 0;
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    const auto p = cell_points(m, c);
    const int b = m.body[c];
    INFO("cell " << c << ", body " << b << ", name " << kVehicleVtuNames[std::size_t(m.name_id[c])]);
    if (m.cells.types[c] == VtuCellType::hexahedron) {
      ++boxes;
      REQUIRE(b == v.chassis());
      CHECK(m.name_id[c] == int(VtuPart::chassis));
      // Every point the chassis carries lies in the box (its frame), and the box is no bigger than that.
      const mb::RigidBody& ch = s.bodies[std::size_t(b)];
      mb::Vec3 lo = mb::Vec3::Constant(INFINITY), hi = -lo;
      for (const std::int64_t k : p) {
        const mb::Vec3 local = ch.rotation().transpose() * (point_of(m, k) - ch.position);
        lo = lo.cwiseMin(local), hi = hi.cwiseMax(local);
      }
      mb::Vec3 want_lo = mb::Vec3::Zero(), want_hi = mb::Vec3::Zero();
      for (const mb::Vec3& x : attachments(s, b)) {
        const mb::Vec3 local = ch.rotation().transpose() * (x - ch.position);
        want_lo = want_lo.cwiseMin(local), want_hi = want_hi.cwiseMax(local);
      }
      CHECK((lo - want_lo).norm() < 1e-12);
      CHECK((hi - want_hi).norm() < 1e-12);
      CHECK(hi.x() - lo.x() > 3.3);  // the two axles' lower-arm hinges are 3.38 m apart
      continue;
    }
    if (m.cells.types[c] != VtuCellType::line) continue;
    REQUIRE(p.size() == 2);
    const mb::Vec3 a = point_of(m, p[0]), e = point_of(m, p[1]);
    CHECK((a - e).norm() > 1e-3);
    if (b >= 0) {
      // A body's line joins two of the points it carries.
      CHECK(distance_to(attachments(s, b), a) < 1e-12);
      CHECK(distance_to(attachments(s, b), e) < 1e-12);
      ++lines_of[b];
      ends_of[b].insert({p[0], p[1]});
      continue;
    }
    // A joint or a spring: one of them has exactly these ends.
    bool found = false;
    for (const mb::Joint& j : s.joints)
      found =
          found || (j.type == mb::JointType::distance && (s.bodies[std::size_t(j.i)].point(j.si) - a).norm() < 1e-12 &&
                    (s.bodies[std::size_t(j.j)].point(j.sj) - e).norm() < 1e-12);
    for (const mb::SpringDamper& sp : s.springs)
      found = found || ((s.bodies[std::size_t(sp.i)].point(sp.si) - a).norm() < 1e-12 &&
                        (s.bodies[std::size_t(sp.j)].point(sp.sj) - e).norm() < 1e-12);
    CHECK(found);
    tie_rods += m.name_id[c] == int(VtuPart::tie_rod);
    idlers += m.name_id[c] == int(VtuPart::idler);
    springs += m.name_id[c] == int(VtuPart::spring);
  }
  CHECK(boxes == 1);
  CHECK(tie_rods == 4);
  CHECK(idlers == 1);
  CHECK(springs == 8);  // a spring and a shock per corner
  // Each arm is one line, from its hinge on the chassis to its ball joint on the upright, when only
  // its joints are counted; the lower arm also carries the spring's and the shock's ends.
  for (const WishboneSide& w : v.corners()) {
    for (const int b : {w.upright, w.upper_arm, w.lower_arm}) {
      INFO(s.bodies[std::size_t(b)].name);
      // Every joint point of the body ends one of its lines.
      for (const mb::Vec3& x : attachments(s, b, true)) {
        double best = INFINITY;
        for (const std::int64_t k : ends_of[b]) best = std::min(best, (point_of(m, k) - x).norm());
        CHECK(best < 1e-12);
      }
    }
    CHECK(lines_of[w.upper_arm] == 1);
    CHECK(lines_of[w.upright] == 6);  // 4 points: the two ball joints, the bearing, the tie rod's end
  }
  CHECK(lines_of[v.steering().arm] == 1);   // its hinge to its universal joint
  CHECK(lines_of[v.steering().link] == 6);  // the universal joint, the idler, two tie rods
  // Each body is named once, by the index the cells give.
  const auto names = vehicle_body_names(v);
  CHECK(names.size() == s.bodies.size());
  CHECK(names[std::size_t(v.chassis())] == "chassis");
}

TEST_CASE(
    "vehicle vtu: point velocities are the bodies' (a rolling wheel's top at twice the speed), and the file "
    "holds the mesh",
    "[vehicle][vtu]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  set_forward_speed(v, 3.0);
  const VehicleMesh m = vehicle_mesh(v);
  const mb::MbSystem& s = v.system();
  double top = -INFINITY, bottom = INFINITY;
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    for (const std::int64_t k : cell_points(m, c)) {
      const mb::Vec3 u(m.velocity[std::size_t(3 * k)], m.velocity[std::size_t(3 * k + 1)],
                       m.velocity[std::size_t(3 * k + 2)]);
      if (m.name_id[c] == int(VtuPart::wheel)) {
        top = std::max(top, u.x()), bottom = std::min(bottom, u.x());
        const mb::RigidBody& sp = s.bodies[std::size_t(m.body[c])];
        const mb::Vec3 local = sp.rotation().transpose() * (point_of(m, k) - sp.position);
        CHECK((u - sp.point_velocity(local)).norm() < 1e-5);
      } else {
        CHECK((u - mb::Vec3(3, 0, 0)).norm() < 1e-6);  // every other body moves without turning
      }
    }
  CHECK(top == Approx(6.0).epsilon(1e-6));  // the rim's top at twice the speed, its bottom at rest
  CHECK(std::abs(bottom) < 1e-5);

  terracal::test::ScratchDir dir("vehicle_vtu");
  write_vehicle_vtu(dir.path / "v.vtu", v, 1.5);
  const std::string xml = terracal::test::slurp(dir.path / "v.vtu");
  CHECK(xml.find("NumberOfPoints=\"" + std::to_string(m.xyz.size() / 3) + "\" NumberOfCells=\"" +
                 std::to_string(m.cells.size()) + "\"") != std::string::npos);
  CHECK(xml.find("        1.5\n") != std::string::npos);  // TimeValue
  using terracal::test::array_payload;
  CHECK(array_payload<float>(xml, "Points") == std::vector<float>(m.xyz.begin(), m.xyz.end()));
  CHECK(array_payload<float>(xml, "velocity") == m.velocity);
  CHECK(array_payload<float>(xml, "body") == std::vector<float>(m.body.begin(), m.body.end()));
  CHECK(array_payload<float>(xml, "name_id") == std::vector<float>(m.name_id.begin(), m.name_id.end()));
  CHECK(array_payload<std::int64_t>(xml, "connectivity") == m.cells.connectivity);
  CHECK(array_payload<std::int64_t>(xml, "offsets") == m.cells.offsets);
  const auto types = array_payload<std::uint8_t>(xml, "types");
  REQUIRE(types.size() == m.cells.size());
  for (std::size_t c = 0; c < types.size(); ++c) CHECK(types[c] == std::uint8_t(m.cells.types[c]));
  // Written through a temporary: nothing else is left in the folder.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++entries;
  CHECK(entries == 1);
}
