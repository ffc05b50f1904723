# Most of a first build is the compiler parsing and instantiating the same headers (Eigen, the standard
# library, doctest) again in every file. Two remedies, each with an option (docs/performance.md, "First
# build"):
#   ROOTSIM_PCH    precompiled headers of Eigen, the standard library and doctest for the test executables
#   ROOTSIM_UNITY  unity builds: a target's files compiled in batches of ROOTSIM_UNITY_BATCH, one
#                  compiler run per batch (the libraries and the Python module). Files of a batch
#                  share one translation unit, so an internal (anonymous-namespace or static) name is
#                  defined once in its library: two files needing one share a header; a using-directive
#                  at namespace scope reaches the later files of its batch.
# Both off (-DROOTSIM_PCH=OFF -DROOTSIM_UNITY=OFF) compile every file alone, as an editor's clangd does:
# a file that lacks an #include shows up there.
# ROOTSIM_PCH is off by default: through the precompiled header gcc 12 inlines libstdc++'s string
# concatenation where its -Warray-bounds misreads it (a false report that -Werror turns into a failure)
option(ROOTSIM_PCH "precompiled headers (Eigen, the standard library, doctest)" OFF)
option(ROOTSIM_UNITY "unity builds: each target's files compiled in batches" ON)
set(ROOTSIM_UNITY_BATCH 8 CACHE STRING "source files per unity batch (ROOTSIM_UNITY)")

# the headers most of rootsim's files include; only Eigen and the standard library (the physics library
# rootsim_core includes no GL, file-format or CLI header, so neither does its precompiled header)
set(ROOTSIM_PCH_HEADERS
  <algorithm> <array> <cmath> <cstdint> <cstdio> <cstring> <filesystem> <fstream> <functional> <limits>
  <map> <memory> <numbers> <optional> <sstream> <stdexcept> <string> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry>)

# rootsim_compile_speed(<target> [TEST]): the target's precompiled header and unity batches. TEST (a
# doctest executable): doctest in the precompiled header, and no unity batches (test files keep their own
# helpers under the same names: run, slurp, scratch). A target compiled in fewer than 5 translation units
# gets no precompiled header: compiling the header costs about as much as parsing it in 4 files (so the
# libraries, in unity batches, have none). Call it after the target's last target_sources().
function(rootsim_compile_speed target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "TEST" "" "")
  get_target_property(sources ${target} SOURCES)
  list(FILTER sources INCLUDE REGEX "\\.cpp$")
  list(LENGTH sources n)
  set(unity ${ROOTSIM_UNITY})
  if(ARG_TEST)
    set(unity OFF)
  endif()
  if(unity)
    math(EXPR units "(${n} + ${ROOTSIM_UNITY_BATCH} - 1) / ${ROOTSIM_UNITY_BATCH}")
  else()
    set(units ${n})
  endif()
  if(ROOTSIM_PCH AND units GREATER_EQUAL 5)
    set(headers ${ROOTSIM_PCH_HEADERS})
    if(ARG_TEST)
      list(APPEND headers <doctest/doctest.h>)
    endif()
    target_precompile_headers(${target} PRIVATE ${headers})
    # clang stamps a precompiled header with its inputs' times: without the stamp ccache can reuse it
    # (ccache also needs sloppiness = pch_defines,time_macros; docs/performance.md, "First build")
    if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
      target_compile_options(${target} PRIVATE "SHELL:-Xclang -fno-pch-timestamp")
    endif()
  endif()
  if(unity)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH
                                               UNITY_BUILD_BATCH_SIZE ${ROOTSIM_UNITY_BATCH})
    # gcc's -Wsubobject-linkage flags a header's class holding a type of a .cpp's anonymous namespace (a
    # pimpl's Impl) unless that .cpp is the file being compiled, which in a batch it is not; each .cpp
    # is still compiled once, into one object, so the types cannot differ between translation units
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
    endif()
  endif()
endfunction()
