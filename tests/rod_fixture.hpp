#pragma once
// the physics fixtures live in physics_support.hpp; this name is kept for bench/bench_relax.cpp
#include "physics_support.hpp"
