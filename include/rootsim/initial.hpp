#pragma once
// Initial state (docs/model.md, Frames and signs): straight, lying on the plane, pointing downhill.
#include <cstdint>

#include "rootsim/environment.hpp"

namespace rootsim {

struct InitialShape {
  double length = 1.1e-3;         // L0 [m]
  double elementLength = 5e-5;    // target element length h [m]; n = ceil(L0 / h), at least 2
  double perturbation = 1e-6;     // lateral node displacement amplitude / R (seeded; docs/model.md,
                                  // Environment)
  std::uint64_t seed = 1;         // seed of the perturbation
  double angle = 0.0;             // initial direction from downhill, in the plate [rad], positive towards
                                  // +lateral like theta: root.initial_angle_deg, a seedling's angle_deg
                                  // (docs/plate.md)
  double startTime = 0.0;         // growth time of the initial state [s]: a lateral root's emergence on
                                  // a plate (its times are the plate's); not a scene key
};

// base of the centreline at R n, axis along the downhill direction, d1 = x, d2 = n, d3 = downhill
// (turned by shape.angle about n: d3 = cos a downhill + sin a x, d1 = d2 x d3);
// nodes 2.. are displaced laterally by perturbation * R * u, u uniform in [-1, 1] from a splitmix64
// stream of the seed (bit-identical on every platform)
RodState makeInitialRod(const RodParams& p, const Plane& plane, const InitialShape& shape);

// deterministic uniform number in [-1, 1) from a 64-bit state (splitmix64)
double splitmixUniform(std::uint64_t& state);
// a standard normal number from two uniforms of the stream (Box-Muller, the cosine branch)
double splitmixNormal(std::uint64_t& state);

}  // namespace rootsim
