// The obstacles as lit meshes (src/render/obstacle_mesh.cpp): a peg as a 40-sided cylinder and a wall as
// a box, kObstacleHeightRadii root radii high, checked by their vertices, unit normals and surface areas
// in closed form.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "rootsim/obstacle_mesh.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

using namespace rootsim;

namespace {
Eigen::Vector3d at(const RenderScene& rs, std::uint32_t i) {
  const TubeVertex& v = rs.vertices[i];
  return Eigen::Vector3d(v.pos[0], v.pos[1], v.pos[2]);
}
double area(const RenderScene& rs, std::size_t firstIndex = 0) {
  double a = 0;
  for (std::size_t t = firstIndex; t + 2 < rs.indices.size(); t += 3)
    a += 0.5 * (at(rs, rs.indices[t + 1]) - at(rs, rs.indices[t])).cross(at(rs, rs.indices[t + 2]) - at(rs, rs.indices[t])).norm();
  return a;
}
void checkWellFormed(const RenderScene& rs) {
  CHECK(rs.indices.size() % 3 == 0);
  for (std::uint32_t i : rs.indices) CHECK(i < rs.vertices.size());
  for (const TubeVertex& v : rs.vertices) {
    CHECK(std::abs(std::hypot(v.normal[0], v.normal[1], v.normal[2]) - 1.0) < 1e-6);
    CHECK(v.striped == 0.0f);
  }
}
}  // namespace

TEST_CASE("obstacle mesh: a peg is a cylinder of its radius standing 6 R high, its side and top areas those of a 40-gon prism") {
  SceneInfo info;
  info.radius = 1e-4;  // R = 0.1 mm: 0.6 mm high
  SceneInfo::ObstacleShape peg;
  peg.peg = true;
  peg.fromU = peg.toU = 1.0;
  peg.fromV = peg.toV = -2.0;
  peg.radiusMm = 0.3;
  info.obstacles.push_back(peg);
  RenderScene rs;
  addObstacleMeshes(info, rs);
  checkWellFormed(rs);
  const double h = 0.6, r = 0.3;
  CHECK(rs.indices.size() == 3u * (2 * 40 + 40));
  for (const TubeVertex& v : rs.vertices) {
    const double d = std::hypot(v.pos[0] - 1.0, v.pos[1] + 2.0);
    CHECK((d < 1e-6 || std::abs(d - r) < 1e-6));
    CHECK((std::abs(v.pos[2]) < 1e-7 || std::abs(v.pos[2] - h) < 1e-6));
  }
  const double side = 40 * 2.0 * r * std::sin(std::numbers::pi / 40) * h;
  const double top = 40 * 0.5 * r * r * std::sin(2.0 * std::numbers::pi / 40);
  CHECK(area(rs) == doctest::Approx(side + top).epsilon(1e-5));
}

TEST_CASE("obstacle mesh: a wall is a box of its length and thickness, four sides and a top") {
  SceneInfo info;
  info.radius = 1e-4;
  SceneInfo::ObstacleShape wall;
  wall.peg = false;
  wall.fromU = 0.0;
  wall.fromV = 0.0;
  wall.toU = 1.2;
  wall.toV = 1.6;  // 2 mm long
  wall.radiusMm = 0.1;
  info.obstacles.push_back(wall);
  RenderScene rs;
  addObstacleMeshes(info, rs);
  checkWellFormed(rs);
  CHECK(rs.indices.size() == 3u * 10);
  const double h = 0.6, len = 2.0, thick = 0.2;
  CHECK(area(rs) == doctest::Approx(2 * len * h + 2 * thick * h + len * thick).epsilon(1e-6));
  // every corner is half the thickness from the wall's line, between its ends
  const Eigen::Vector2d t(0.6, 0.8);
  for (const TubeVertex& v : rs.vertices) {
    const Eigen::Vector2d p(v.pos[0], v.pos[1]);
    CHECK(std::abs(std::abs(p.x() * -t.y() + p.y() * t.x()) - 0.1) < 1e-6);
    const double along = p.dot(t);
    CHECK((std::abs(along) < 1e-6 || std::abs(along - len) < 1e-6));
  }
  // no obstacles, no mesh
  RenderScene none;
  addObstacleMeshes(SceneInfo{}, none);
  CHECK(none.vertices.empty());
}
