// Fuzz harness: scene text plus --set overrides -> parseScene (include/rootsim/scene.hpp).
// Input layout: the scene's TOML text, then zero or more '\0'-separated overrides ("section.key=value").
// Oracles: a refused scene throws SceneError with a one-line message; an accepted scene's resolved text
// parses again to the same resolved text (what every run directory's scene.toml relies on) and asks
// for a bounded amount of work (the element caps of the schema).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "rootsim/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t z = in.find('\0', start);
    parts.push_back(in.substr(start, z == std::string::npos ? std::string::npos : z - start));
    if (z == std::string::npos || parts.size() > 16) break;
    start = z + 1;
  }
  const std::string scene = parts.front();
  const std::vector<std::string> overrides(parts.begin() + 1, parts.end());
  rootsim::Scene sc;
  try {
    sc = rootsim::parseScene(scene, "fuzz.toml", overrides);
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::checkMessage(e.what());
    return 0;
  }
  rootsim::Scene again;
  try {
    again = rootsim::parseScene(sc.resolvedToml, "fuzz.toml");
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::fail(std::string("the resolved scene of an accepted scene is refused: ") + e.what() + "\n" +
                        sc.resolvedToml);
  }
  if (again.resolvedToml != sc.resolvedToml)
    rootsim::fuzz::fail("resolved scene does not round-trip:\n" + sc.resolvedToml + "\n---\n" + again.resolvedToml);
  const double h = sc.model.initial.elementLength, L0 = sc.model.initial.length;
  if (!(L0 / h <= rootsim::kMaxElements)) rootsim::fuzz::fail("accepted scene exceeds the initial element cap");
  return 0;
}
