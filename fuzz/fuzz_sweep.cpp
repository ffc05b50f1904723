// Fuzz harness: sweep files -> loadSweep (include/rootsim/sweep.hpp). The input is written as
// <tmp>/sweeps/fuzz.toml next to a copy of the repository's scenes/ (so "../scenes/x.toml" resolves as
// in sweeps/). Oracles: a refused sweep throws SceneError with a one-line message; an accepted plan has
// at most kMaxSweepPoints points, unique run-directory names that are single path components of at
// most 255 bytes.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "fuzz_check.hpp"
#include "rootsim/sweep.hpp"

namespace fs = std::filesystem;

namespace {
char gDir[] = "/tmp/rootsim-fuzz-sweep-XXXXXX";  // a plain array: still valid in the atexit handler

fs::path workDir() {
  static const bool made = [] {
    if (!::mkdtemp(gDir)) rootsim::fuzz::fail("mkdtemp failed");
    fs::create_directories(fs::path(gDir) / "sweeps");
    fs::copy(fs::path(ROOTSIM_SOURCE_DIR) / "scenes", fs::path(gDir) / "scenes");
    std::atexit([] { std::error_code ec; fs::remove_all(gDir, ec); });
    return true;
  }();
  (void)made;
  return gDir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path file = workDir() / "sweeps" / "fuzz.toml";
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  rootsim::SweepPlan plan;
  try {
    plan = rootsim::loadSweep(file.string());
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::checkMessage(e.what());
    return 0;
  }
  if (plan.points.size() > rootsim::kMaxSweepPoints) rootsim::fuzz::fail("accepted sweep exceeds the point cap");
  std::set<std::string> names;
  for (const auto& p : plan.points) {
    if (p.dirName.empty() || p.dirName.size() > 255 || p.dirName.find('/') != std::string::npos ||
        p.dirName == "." || p.dirName == "..")
      rootsim::fuzz::fail("bad run-directory name: " + p.dirName);
    if (!names.insert(p.dirName).second) rootsim::fuzz::fail("two points share the run directory " + p.dirName);
  }
  return 0;
}
