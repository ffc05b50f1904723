// support of the physics tests (not a test file): a counting global allocator for rootsim_tests, read by
// the allocation tests (test_relax_dynamic.cpp, test_relax_newton.cpp, test_simulation.cpp) through
// rootsim::test::gAllocs (physics_support.hpp)
#include <atomic>
#include <cstdlib>
#include <new>

namespace rootsim::test {
std::atomic<long> gAllocs{0};  // declared in physics_support.hpp
}

void* operator new(std::size_t n) {
  ++rootsim::test::gAllocs;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// the nothrow forms too (std::get_temporary_buffer, used by std::inplace_merge, allocates with them): every
// form that the delete above frees must come from malloc, or a sanitizer's own nothrow new would be freed here
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  ++rootsim::test::gAllocs;
  return std::malloc(n ? n : 1);
}
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
