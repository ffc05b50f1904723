#pragma once
// The units rootsim talks to users in, as factors to SI (the only units inside the physics):
//   SI = value * units::mm;   value = SI / units::mm.
// Scene keys, CSV columns and pictures use millimetres, hours, degrees and MPa (docs/cli.md); nothing
// else writes 1e-3, 3600 or pi/180.
#include <numbers>

namespace rootsim::units {

inline constexpr double mm = 1e-3;                       // [m]
inline constexpr double hour = 3600.0;                   // [s]
inline constexpr double deg = std::numbers::pi / 180.0;  // [rad]
inline constexpr double mpa = 1e6;                       // [Pa]
inline constexpr double pi = std::numbers::pi;

}  // namespace rootsim::units
