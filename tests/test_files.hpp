#pragma once
// the process and file helpers live in test_support.hpp; this name is kept for tests/render
#include "test_support.hpp"
