// Fuzz harness: an RSML file -> parseRsml (include/rootsim/rsml.hpp), what a later `analyze` or `fit`
// reads of other tools' files. Oracles: a refused file throws SceneError with a one-line message naming
// "rsml:LINE:"; an accepted file gives roots of at least two finite points within kMaxCoordMm, parents
// before their laterals (order one more than the parent's), polyline functions with one sample per
// point, diameters with one value per point or none; what the writer makes of it reads back to the same
// points, bit for bit.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_check.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/rsml.hpp"

namespace {

using rootsim::fuzz::fail;
namespace rsml = rootsim::rsml;

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void checkDocument(const rsml::Document& d) {
  for (const rsml::Plant& p : d.plants)
    for (std::size_t i = 0; i < p.roots.size(); ++i) {
      const rsml::Root& r = p.roots[i];
      if (r.points() < 2) fail("accepted root with fewer than two points");
      if (r.y.size() != r.points() || r.z.size() != r.points()) fail("accepted root with uneven coordinates");
      for (std::size_t k = 0; k < r.points(); ++k)
        for (double v : {r.x[k], r.y[k], r.z[k]})
          if (!std::isfinite(v) || std::fabs(v) > rsml::kMaxCoordMm) fail("accepted point beyond the bounds");
      if (r.parent >= static_cast<int>(i)) fail("a lateral before its parent");
      if (r.parent < 0 ? r.order != 0 : r.order != p.roots[static_cast<std::size_t>(r.parent)].order + 1)
        fail("a root's order is not its parent's + 1");
      for (const rsml::Function& f : r.functions)
        if (f.domain == "polyline" && f.samples.size() != r.points()) fail("accepted polyline function of another length");
      if (!r.diameterMm.empty() && r.diameterMm.size() != r.points()) fail("diameter of another length");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rsml::Document d;
  try {
    d = rsml::parseRsml(text, "rsml");
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::checkMessage(e.what());
    if (std::strncmp(e.what(), "rsml:", 5) != 0) fail(std::string("error without the file:line: ") + e.what());
    return 0;
  }
  checkDocument(d);
  std::string written;
  try {
    written = rsml::writeRsml(d);
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::checkMessage(e.what());  // a name or character RSML cannot hold
    return 0;
  }
  rsml::Document back;
  try {
    back = rsml::parseRsml(written, "written");
  } catch (const rootsim::SceneError& e) {
    fail(std::string("the writer's file is refused: ") + e.what());
  }
  if (back.plants.size() != d.plants.size()) fail("written file: plants differ");
  for (std::size_t p = 0; p < d.plants.size(); ++p) {
    if (back.plants[p].roots.size() != d.plants[p].roots.size()) fail("written file: roots differ");
    for (std::size_t i = 0; i < d.plants[p].roots.size(); ++i) {
      const rsml::Root& a = d.plants[p].roots[i];
      const rsml::Root& b = back.plants[p].roots[i];
      if (a.points() != b.points() || a.parent != b.parent) fail("written file: a root differs");
      for (std::size_t k = 0; k < a.points(); ++k)
        if (!same(a.x[k], b.x[k]) || !same(a.y[k], b.y[k]) || (a.hasZ && !same(a.z[k], b.z[k])))
          fail("written file: a point differs");
    }
  }
  return 0;
}
