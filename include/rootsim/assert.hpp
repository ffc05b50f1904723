#pragma once
// Programmer errors at the physics API edges (a workspace of the wrong size, a rod of fewer than two
// elements handed to a solver): ROOTSIM_ASSERT(condition, "what must hold") aborts with the file, line,
// condition and message. On in Debug and RelWithDebInfo builds (CMake defines ROOTSIM_ASSERTS there),
// compiled out in Release. User input is never checked this way: the scene schema validates it with
// errors that name the key (SceneError).
#include <cstdio>
#include <cstdlib>

#if defined(ROOTSIM_ASSERTS)
#define ROOTSIM_ASSERT(cond, msg)                                                                         \
  do {                                                                                                    \
    if (!(cond)) {                                                                                        \
      std::fprintf(stderr, "%s:%d: rootsim internal error: %s (%s)\n", __FILE__, __LINE__, msg, #cond); \
      std::abort();                                                                                       \
    }                                                                                                     \
  } while (false)
#else
#define ROOTSIM_ASSERT(cond, msg) \
  do {                            \
    (void)sizeof(cond);           \
  } while (false)
#endif
