// Obstacles on the plate (docs/model.md, Contact and friction) as lit meshes of the render scene: a peg as a
// cylinder standing on the plate, a wall as a box. The model's obstacles are infinitely tall; the pictures
// show them kObstacleHeightRadii root radii high. (A wall's ends are rounded in the model, square here.)
#include "rootsim/obstacle_mesh.hpp"

#include <cmath>
#include <numbers>

namespace rootsim {

namespace {
constexpr int kPegSides = 40;
constexpr float kObstacleColour[3] = {0.56f, 0.62f, 0.72f};  // slate blue-grey, apart from the ivory root

void vertex(RenderScene& rs, double u, double v, double w, double nu, double nv, double nw) {
  TubeVertex t{};
  t.pos[0] = static_cast<float>(u), t.pos[1] = static_cast<float>(v), t.pos[2] = static_cast<float>(w);
  t.normal[0] = static_cast<float>(nu), t.normal[1] = static_cast<float>(nv), t.normal[2] = static_cast<float>(nw);
  t.side[0] = 1.0f;
  for (int c = 0; c < 3; ++c) t.colour[c] = kObstacleColour[c];
  t.striped = 0.0f;
  rs.vertices.push_back(t);
}

// a flat quad a-b-c-d (in order round it) with one normal
void quad(RenderScene& rs, const double a[3], const double b[3], const double c[3], const double d[3],
          const double n[3]) {
  const auto base = static_cast<std::uint32_t>(rs.vertices.size());
  for (const double* p : {a, b, c, d}) vertex(rs, p[0], p[1], p[2], n[0], n[1], n[2]);
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) rs.indices.push_back(base + i);
}

void addPeg(RenderScene& rs, double cu, double cv, double r, double h) {
  // side: smooth normals; top: a fan
  const auto side = static_cast<std::uint32_t>(rs.vertices.size());
  for (int k = 0; k <= kPegSides; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / kPegSides, c = std::cos(phi), s = std::sin(phi);
    vertex(rs, cu + r * c, cv + r * s, 0.0, c, s, 0.0);
    vertex(rs, cu + r * c, cv + r * s, h, c, s, 0.0);
  }
  for (std::uint32_t k = 0; k < kPegSides; ++k)
    for (std::uint32_t i : {0u, 1u, 3u, 0u, 3u, 2u}) rs.indices.push_back(side + 2 * k + i);
  const auto top = static_cast<std::uint32_t>(rs.vertices.size());
  vertex(rs, cu, cv, h, 0, 0, 1);
  for (int k = 0; k <= kPegSides; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / kPegSides;
    vertex(rs, cu + r * std::cos(phi), cv + r * std::sin(phi), h, 0, 0, 1);
  }
  for (std::uint32_t k = 0; k < kPegSides; ++k)
    for (std::uint32_t i : {0u, k + 1, k + 2}) rs.indices.push_back(top + i);
}

void addWall(RenderScene& rs, double u0, double v0, double u1, double v1, double half, double h) {
  const double lu = u1 - u0, lv = v1 - v0, len = std::hypot(lu, lv);
  const double tu = lu / len, tv = lv / len, nu = -tv, nv = tu;  // along and across the wall
  // the four corners at the foot, counter-clockwise: start-left, end-left, end-right, start-right
  const double cu[4] = {u0 + half * nu, u1 + half * nu, u1 - half * nu, u0 - half * nu};
  const double cv[4] = {v0 + half * nv, v1 + half * nv, v1 - half * nv, v0 - half * nv};
  auto at = [&](int k, double w, double out[3]) { out[0] = cu[k], out[1] = cv[k], out[2] = w; };
  const double normals[4][3] = {{nu, nv, 0}, {tu, tv, 0}, {-nu, -nv, 0}, {-tu, -tv, 0}};
  for (int k = 0; k < 4; ++k) {
    double a[3], b[3], c[3], d[3];
    at(k, 0, a), at((k + 1) % 4, 0, b), at((k + 1) % 4, h, c), at(k, h, d);
    quad(rs, a, b, c, d, normals[k]);
  }
  double a[3], b[3], c[3], d[3];
  const double up[3] = {0, 0, 1};
  at(0, h, a), at(1, h, b), at(2, h, c), at(3, h, d);
  quad(rs, a, b, c, d, up);
}
}  // namespace

void addObstacleMeshes(const SceneInfo& info, RenderScene& rs) {
  const double h = kObstacleHeightRadii * info.radius / units::mm;
  for (const SceneInfo::ObstacleShape& o : info.obstacles) {
    if (o.peg) addPeg(rs, o.fromU, o.fromV, o.radiusMm, h);
    else addWall(rs, o.fromU, o.fromV, o.toU, o.toV, o.radiusMm, h);
  }
}

}  // namespace rootsim
