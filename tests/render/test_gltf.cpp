// the glTF writer (src/app/gltf.cpp) read back: the GLB container, its JSON (a small reader below), the
// tube's vertices against the snapshots (where the stripes are), the animation's switching and the still
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../test_support.hpp"
#include "render_test_util.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/gltf.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/write_rule.hpp"

using rootsim::test::kFloatRoundoff;

using namespace rootsim;
namespace fs = std::filesystem;
using rootsim::test::Result;
using rootsim::test::run;

namespace {

// ---- a JSON reader just big enough for the file's JSON chunk ----
struct J {
  enum Kind { Null, Bool, Num, Str, Arr, Obj } kind = Null;
  double n = 0;
  std::string s;
  std::vector<J> a;
  std::map<std::string, J> o;
  const J& operator[](const std::string& k) const {
    const auto it = o.find(k);
    if (it == o.end()) throw std::runtime_error("JSON: no member " + k);
    return it->second;
  }
  const J& operator[](std::size_t i) const { return a.at(i); }
  bool has(const std::string& k) const { return o.count(k) > 0; }
  std::size_t size() const { return kind == Arr ? a.size() : o.size(); }
  long i() const { return static_cast<long>(n); }
};

struct Reader {
  const std::string& t;
  std::size_t p = 0;
  void ws() {
    while (p < t.size() && std::strchr(" \t\r\n", t[p])) ++p;
  }
  void expect(char c) {
    ws();
    if (p >= t.size() || t[p] != c) throw std::runtime_error(std::string("JSON: expected ") + c + " at " + std::to_string(p));
    ++p;
  }
  std::string str() {
    expect('"');
    std::string s;
    while (t.at(p) != '"') {
      if (t[p] == '\\') {
        ++p;
        if (t.at(p) == 'u') {
          s += static_cast<char>(std::stoi(t.substr(p + 1, 4), nullptr, 16));
          p += 5;
          continue;
        }
      }
      s += t[p++];
    }
    ++p;
    return s;
  }
  J value() {
    ws();
    J v;
    const char c = t.at(p);
    if (c == '{') {
      v.kind = J::Obj;
      ++p;
      ws();
      if (t.at(p) == '}') return ++p, v;
      for (;;) {
        std::string k = str();
        expect(':');
        v.o[k] = value();
        ws();
        if (t.at(p++) == '}') return v;
      }
    }
    if (c == '[') {
      v.kind = J::Arr;
      ++p;
      ws();
      if (t.at(p) == ']') return ++p, v;
      for (;;) {
        v.a.push_back(value());
        ws();
        if (t.at(p++) == ']') return v;
      }
    }
    if (c == '"') {
      v.kind = J::Str;
      v.s = str();
      return v;
    }
    if (t.compare(p, 4, "true") == 0) return p += 4, v.kind = J::Bool, v.n = 1, v;
    if (t.compare(p, 5, "false") == 0) return p += 5, v.kind = J::Bool, v;
    if (t.compare(p, 4, "null") == 0) return p += 4, v;
    std::size_t used = 0;
    v.kind = J::Num;
    v.n = std::stod(t.substr(p, 40), &used);
    p += used;
    return v;
  }
};

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(b.at(at + static_cast<std::size_t>(k)));
  return v;
}

// a GLB split into its JSON and its binary chunk, the container checked on the way
struct Glb {
  J json;
  std::string bin;
};
Glb parseGlb(const std::string& b) {
  REQUIRE(b.size() >= 28);
  CHECK(b.compare(0, 4, "glTF") == 0);
  CHECK(u32(b, 4) == 2u);
  CHECK(u32(b, 8) == b.size());
  const std::uint32_t jsonLen = u32(b, 12);
  CHECK(jsonLen % 4 == 0);
  CHECK(b.compare(16, 4, "JSON") == 0);
  const std::string text = b.substr(20, jsonLen);
  const std::size_t binAt = 20 + jsonLen;
  const std::uint32_t binLen = u32(b, binAt);
  CHECK(binLen % 4 == 0);
  CHECK(b.compare(binAt + 4, 4, std::string("BIN\0", 4)) == 0);
  CHECK(binAt + 8 + binLen == b.size());
  Reader r{text};
  Glb g{r.value(), b.substr(binAt + 8, binLen)};
  CHECK(g.json["buffers"][0]["byteLength"].i() == static_cast<long>(binLen));
  return g;
}

// the bytes of accessor k, element i, component c, as a double (normalised integers divided out)
double element(const Glb& g, long k, long i, int c) {
  const J& acc = g.json["accessors"][static_cast<std::size_t>(k)];
  const J& view = g.json["bufferViews"][static_cast<std::size_t>(acc["bufferView"].i())];
  const long type = acc["componentType"].i();
  const int size = type == 5126 || type == 5125 ? 4 : type == 5122 || type == 5123 ? 2 : 1;
  const int comps = acc["type"].s == "VEC3" ? 3 : 1;
  const long stride = view.has("byteStride") ? view["byteStride"].i() : comps * size;
  const long at = view["byteOffset"].i() + (acc.has("byteOffset") ? acc["byteOffset"].i() : 0) + i * stride + c * size;
  REQUIRE(i < acc["count"].i());
  const auto byte = [&](long k2) { return static_cast<unsigned char>(g.bin.at(static_cast<std::size_t>(k2))); };
  if (type == 5126) {
    const std::uint32_t bits = byte(at) | byte(at + 1) << 8 | byte(at + 2) << 16 | static_cast<std::uint32_t>(byte(at + 3)) << 24;
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  }
  if (type == 5125) return byte(at) | byte(at + 1) << 8 | byte(at + 2) << 16 | static_cast<std::uint32_t>(byte(at + 3)) << 24;
  if (type == 5123) return byte(at) | byte(at + 1) << 8;
  if (type == 5122) return static_cast<std::int16_t>(byte(at) | byte(at + 1) << 8) / (acc.has("normalized") ? 32767.0 : 1.0);
  if (type == 5120) return static_cast<std::int8_t>(byte(at)) / (acc.has("normalized") ? 127.0 : 1.0);
  return byte(at);
}

const J* nodeNamed(const Glb& g, const std::string& name) {
  for (const J& n : g.json["nodes"].a)
    if (n.has("name") && n["name"].s == name) return &n;
  return nullptr;
}

// a root in a quarter circle on the plate, d1 on the plate's normal (theta = 90 deg): the +d1 stripe faces
// up (glTF +y), the -d1 stripe down
Snapshot arcRoot(int n, double lengthMm, double timeH) {
  Snapshot s = rtest::straightRod(40.0, n, lengthMm, 0.1, [](double) { return 90 * rtest::kDeg; });
  const PlateFrame pf = PlateFrame::tilted(40.0 * units::deg);
  const double rc = 2.0 * lengthMm / units::pi * 1e-3;  // bend radius [m]
  for (int i = 0; i <= n; ++i) {
    const double phi = 0.5 * units::pi * i / n;
    s.x.col(i) = rc * std::sin(phi) * pf.downhill + rc * (1 - std::cos(phi)) * pf.lateral + 1e-4 * pf.normal;
  }
  for (int e = 0; e < n; ++e) s.d3.col(e) = (s.x.col(e + 1) - s.x.col(e)).normalized();
  s.timeH = timeH;
  s.step = static_cast<int>(timeH * 20);
  return s;
}

}  // namespace

TEST_CASE("glTF: the container and the tube vertices match the snapshots and the stripes face +-d1") {
  const std::vector<Snapshot> snaps{arcRoot(6, 2.0, 0.0), arcRoot(10, 3.0, 0.5), arcRoot(15, 4.0, 1.0)};
  SceneInfo info = rtest::info(40.0);
  info.obstacles.push_back({true, 3.0, -2.0, 3.0, -2.0, 0.4});
  info.obstacles.push_back({false, -2.0, -1.0, -2.0, -4.0, 0.1});
  const std::string bytes = gltfBinary(snaps, info);
  CHECK(bytes == gltfBinary(snaps, info));  // the same input, the same bytes
  const Glb g = parseGlb(bytes);
  const J& js = g.json;
  CHECK(js["asset"]["version"].s == "2.0");
  CHECK(js["asset"]["generator"].s == outputSignatureText());
  CHECK(js["extensionsRequired"][0].s == "KHR_mesh_quantization");
  // frames, root, plate, grid, obstacles, camera, scene root
  CHECK(js["nodes"].size() == snaps.size() + 6);
  for (const char* name : {"plate", "grid", "obstacles", "top view", "root", "rootsim"}) CHECK_MESSAGE(nodeNamed(g, name), name);
  CHECK(js["materials"].size() == 7);

  const J& root = *nodeNamed(g, "root");
  const double scale = root["scale"][0].n;
  const Eigen::Vector3d t(root["translation"][0].n, root["translation"][1].n, root["translation"][2].n);
  const PlateFrame pf = PlateFrame::tilted(40.0 * units::deg);
  const double cosH = std::cos(38.0 * rtest::kDeg);
  for (std::size_t f = 0; f < snaps.size(); ++f) {
    const Snapshot& s = snaps[f];
    const J& node = js["nodes"][static_cast<std::size_t>(root["children"][f].i())];
    CHECK(node["extras"]["time_h"].n == s.timeH);
    const J& mesh = js["meshes"][static_cast<std::size_t>(node["mesh"].i())];
    REQUIRE(mesh["primitives"].size() == 3);
    const long pos = mesh["primitives"][0]["attributes"]["POSITION"].i(), nrm = mesh["primitives"][0]["attributes"]["NORMAL"].i();
    const long nodes = s.x.cols();
    // base disc 1 + 12, cap 4 x 12 + apex, wall 12 per node
    CHECK(js["accessors"][static_cast<std::size_t>(pos)]["count"].i() == 13 + 49 + 12 * nodes);
    auto vertex = [&](long i) {
      Eigen::Vector3d v;
      for (int c = 0; c < 3; ++c) v[c] = element(g, pos, i, c) * scale + t[c];
      return v;
    };
    // every wall vertex of node j lies R from the node, in glTF axes: (u, w, -v) [m]
    double worst = 0;
    for (long j = 0; j < nodes; ++j) {
      const Eigen::Vector3d p = pf.toPlateMm(s.x.col(j));
      const Eigen::Vector3d c(1e-3 * p.x(), 1e-3 * p.z(), -1e-3 * p.y());
      for (long k = 0; k < 12; ++k) {
        const Eigen::Vector3d d = vertex(62 + 12 * j + k) - c;
        worst = std::max(worst, std::abs(d.norm() - 1e-4));
      }
    }
    CHECK(worst < 1e-6);  // 1 um: int16 over a few mm
    // the primitives' materials and where their faces point: +d1 = plate normal = glTF +y
    const std::vector<std::string> names{"root body", "stripe +d1", "stripe -d1"};
    for (int m = 0; m < 3; ++m) {
      const J& prim = mesh["primitives"][static_cast<std::size_t>(m)];
      CHECK(prim["attributes"]["POSITION"].i() == pos);
      CHECK(js["materials"][static_cast<std::size_t>(prim["material"].i())]["name"].s == names[static_cast<std::size_t>(m)]);
      const long ia = prim["indices"].i(), count = js["accessors"][static_cast<std::size_t>(ia)]["count"].i();
      CHECK(count % 3 == 0);
      double minY = 1, maxY = -1;
      for (long q = 0; q < count; ++q) {
        const auto v = static_cast<long>(element(g, ia, q, 0));
        REQUIRE(v < 62 + 12 * nodes);
        if (v < 62) continue;  // the base disc faces back along the axis, the cap turns to the apex
        const double y = element(g, nrm, v, 1);
        minY = std::min(minY, y), maxY = std::max(maxY, y);
      }
      INFO("material " << names[static_cast<std::size_t>(m)]);
      if (m == 1) CHECK(minY > cosH - 0.02);       // pink: within 38 deg of +d1 (up), to its edges
      if (m == 2) CHECK(maxY < -cosH + 0.02);      // orange: within 38 deg of -d1
      if (m == 0) CHECK(std::max(maxY, -minY) < cosH + 0.02);
      if (m != 0) CHECK(std::abs(m == 1 ? minY - cosH : maxY + cosH) < 0.02);  // edges on the 38 deg lines
    }
  }

  // the plate lies at y = 0 around the root, +y up; the camera looks down on it
  const J& plateMesh = js["meshes"][static_cast<std::size_t>((*nodeNamed(g, "plate"))["mesh"].i())];
  const long pp = plateMesh["primitives"][0]["attributes"]["POSITION"].i();
  CHECK(js["accessors"][static_cast<std::size_t>(pp)]["max"][1].n == 0.0);
  CHECK(js["accessors"][static_cast<std::size_t>(pp)]["min"][1].n == 0.0);
  CHECK(js["cameras"][0]["type"].s == "orthographic");
  CHECK((*nodeNamed(g, "top view"))["translation"][1].n > 0.01);
}

TEST_CASE("glTF: the animation shows exactly snapshot k from k / 24 s to (k + 1) / 24 s and a still has none") {
  const std::vector<Snapshot> snaps{arcRoot(4, 1.0, 0.0), arcRoot(5, 1.5, 0.5), arcRoot(6, 2.0, 1.0), arcRoot(8, 2.5, 1.5)};
  const Glb g = parseGlb(gltfBinary(snaps, rtest::info(40.0)));
  const J& anim = g.json["animations"][0];
  REQUIRE(anim["channels"].size() == snaps.size());
  const J& root = *nodeNamed(g, "root");
  // the scale of frame node f at time t, sampled as STEP does (before the first key: the first value)
  auto scaleAt = [&](std::size_t f, double t) {
    for (const J& ch : anim["channels"].a) {
      if (ch["target"]["node"].i() != root["children"][f].i()) continue;
      CHECK(ch["target"]["path"].s == "scale");
      const J& smp = anim["samplers"][static_cast<std::size_t>(ch["sampler"].i())];
      CHECK(smp["interpolation"].s == "STEP");
      const long in = smp["input"].i(), out = smp["output"].i();
      const long keys = g.json["accessors"][static_cast<std::size_t>(in)]["count"].i();
      long k = 0;
      while (k + 1 < keys && element(g, in, k + 1, 0) <= t) ++k;
      return element(g, out, k, 0);
    }
    FAIL("no channel for frame " << f);
    return -1.0;
  };
  for (std::size_t k = 0; k < snaps.size(); ++k)
    for (double dt : {0.0, 0.5 / 24}) {
      const double t = static_cast<float>(k / 24.0) + dt;  // the keys are float32 times
      for (std::size_t f = 0; f < snaps.size(); ++f) {
        INFO("t = " << t << " s, frame " << f);
        CHECK(scaleAt(f, t) == (f == k ? 1.0 : 0.0));
      }
    }
  // without the animation (a viewer that does not play it): the last snapshot
  for (std::size_t f = 0; f < snaps.size(); ++f)
    CHECK(g.json["nodes"][static_cast<std::size_t>(root["children"][f].i())]["scale"][0].n == (f + 1 == snaps.size() ? 1.0 : 0.0));

  const Glb still = parseGlb(gltfBinary({snaps[2]}, rtest::info(40.0)));
  CHECK_FALSE(still.json.has("animations"));
  CHECK(still.json["nodes"][static_cast<std::size_t>((*nodeNamed(still, "root"))["children"][0].i())]["scale"][0].n == 1.0);
  SceneInfo free = rtest::info(40.0);
  free.plate = false;  // a free organ: no plate, no grid
  const Glb organ = parseGlb(gltfBinary({snaps[2]}, free));
  CHECK(nodeNamed(organ, "plate") == nullptr);
  CHECK(nodeNamed(organ, "grid") == nullptr);
}

TEST_CASE("glTF: no snapshots or a bad stripe width or a broken snapshot are refused") {
  CHECK_THROWS_AS(gltfBinary({}, rtest::info(40.0)), RenderError);
  GltfOptions o;
  o.stripeHalfWidthDeg = 90.0;
  CHECK_THROWS_AS(gltfBinary({arcRoot(4, 1.0, 0.0)}, rtest::info(40.0), o), RenderError);
  Snapshot bad = arcRoot(4, 1.0, 0.0);
  bad.x(0, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(gltfBinary({bad}, rtest::info(40.0)), RenderError);
}

TEST_CASE("glTF: rootsim export --gltf writes every snapshot animated or one with --at-h and bad outputs exit 2") {
  const fs::path d = rtest::scratch("gltf_export");
  const std::string rd = (d / "run").string();
  // 11 snapshots: steps 0, 4, ..., 40 (0, 0.2, ..., 2 h)
  const Result ran = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                         "/scenes/fig2b_waving.toml --set growth.steps=40 --set output.every_steps=4 --quiet --out " + rd);
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  auto read = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  auto listing = [&]() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(rd)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  const std::vector<std::string> before = listing();
  const fs::path glb = d / "run.glb";
  const Result all = run("export " + rd + " --gltf " + glb.string());
  REQUIRE_MESSAGE(all.code == 0, all.out);
  const std::string bytes = read(glb);
  const Glb g = parseGlb(bytes);
  CHECK((*nodeNamed(g, "root"))["children"].size() == 11);
  CHECK(g.json["animations"][0]["channels"].size() == 11);
  CHECK(whyNotSigned(glb, OutputFormat::Glb).empty());
  CHECK(listing() == before);  // the run directory receives nothing

  // again without --force: refused, the file untouched; with --force and --at-h: one snapshot
  const Result again = run("export " + rd + " --gltf " + glb.string());
  CHECK(again.code == 2);
  CHECK(again.out.find("--force") != std::string::npos);
  CHECK(read(glb) == bytes);
  const Result still = run("export " + rd + " --gltf " + glb.string() + " --force --at-h 1.05");
  REQUIRE_MESSAGE(still.code == 0, still.out);
  const Glb one = parseGlb(read(glb));
  CHECK((*nodeNamed(one, "root"))["children"].size() == 1);
  CHECK_FALSE(one.json.has("animations"));
  CHECK(one.json["nodes"][static_cast<std::size_t>((*nodeNamed(one, "root"))["children"][0].i())]["extras"]["time_h"].n ==
        doctest::Approx(1.0).epsilon(1e-9));

  // a user's file is never replaced, not even with --force; a name without .glb and a missing folder exit 2
  const fs::path mine = d / "mine.glb";
  std::ofstream(mine) << "my own file";
  const Result foreign = run("export " + rd + " --gltf " + mine.string() + " --force");
  CHECK(foreign.code == 2);
  CHECK(read(mine) == "my own file");
  const Result text = run("export " + rd + " --gltf " + (d / "run.gltf").string());
  CHECK(text.code == 2);
  CHECK(text.out.find(".glb") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "run.gltf"));
  const Result nowhere = run("export " + rd + " --gltf " + (d / "no" / "run.glb").string());
  CHECK(nowhere.code == 2);
  fs::remove_all(d);
}

TEST_CASE("glTF: a plate's roots are one group and one striped tube per snapshot each, shown from their first frame") {
  // root a: three snapshots from the file's frame 0; root b: two, from frame 1 (a lateral that emerged),
  // 5 mm across the plate
  const PlateFrame pf = PlateFrame::tilted(40.0 * units::deg);
  std::vector<RootSeries> roots{{"a", {arcRoot(6, 2.0, 0.0), arcRoot(10, 3.0, 0.5), arcRoot(15, 4.0, 1.0)}, 0},
                                {"b", {arcRoot(4, 1.0, 0.5), arcRoot(6, 1.5, 1.0)}, 1}};
  for (Snapshot& s : roots[1].snaps) s.x.colwise() += 5e-3 * pf.lateral;
  GltfOptions o;
  o.plateRectMm = std::array<double, 4>{-1.0, -30.0, 40.0, 0.0};
  const std::string bytes = gltfPlateBinary(roots, rtest::info(40.0), o);
  CHECK(bytes == gltfPlateBinary(roots, rtest::info(40.0), o));
  const Glb g = parseGlb(bytes);
  const J& js = g.json;
  // 5 frames, 2 groups, plate, grid, camera, scene root
  CHECK(js["nodes"].size() == 5 + 2 + 4);
  CHECK(js["materials"].size() == 6);  // the three tube materials shared by every root, plate, 2 grid
  for (const RootSeries& r : roots) {
    const J* group = nodeNamed(g, r.name);
    REQUIRE_MESSAGE(group, r.name);
    REQUIRE((*group)["children"].size() == r.snaps.size());
    const double scale = (*group)["scale"][0].n;
    const Eigen::Vector3d t((*group)["translation"][0].n, (*group)["translation"][1].n, (*group)["translation"][2].n);
    for (std::size_t k = 0; k < r.snaps.size(); ++k) {
      const J& node = js["nodes"][static_cast<std::size_t>((*group)["children"][k].i())];
      // named after its root and the file's frame
      char want[64];
      std::snprintf(want, sizeof want, "%s frame %04d, t = %.2f h", r.name.c_str(), r.firstFrame + static_cast<int>(k), r.snaps[k].timeH);
      CHECK(node["name"].s == want);
      const J& mesh = js["meshes"][static_cast<std::size_t>(node["mesh"].i())];
      REQUIRE(mesh["primitives"].size() == 3);
      const long pos = mesh["primitives"][0]["attributes"]["POSITION"].i();
      // every wall vertex of node j lies R from its own root's node, in glTF axes (u, w, -v) [m]
      double worst = 0;
      for (long j = 0; j < r.snaps[k].x.cols(); ++j) {
        const Eigen::Vector3d p = pf.toPlateMm(r.snaps[k].x.col(j));
        const Eigen::Vector3d c(1e-3 * p.x(), 1e-3 * p.z(), -1e-3 * p.y());
        for (long q = 0; q < 12; ++q) {
          Eigen::Vector3d v;
          for (int cc = 0; cc < 3; ++cc) v[cc] = element(g, pos, 62 + 12 * j + q, cc) * scale + t[cc];
          worst = std::max(worst, std::abs((v - c).norm() - 1e-4));
        }
      }
      CHECK(worst < 1e-6);
    }
  }
  // the animation: at the file's frame f, a's snapshot f and b's f - 1 (from frame 1 on), nothing else
  const J& anim = js["animations"][0];
  REQUIRE(anim["channels"].size() == 5);
  auto scaleOf = [&](long node, double t) {
    for (const J& ch : anim["channels"].a) {
      if (ch["target"]["node"].i() != node) continue;
      const J& smp = anim["samplers"][static_cast<std::size_t>(ch["sampler"].i())];
      const long in = smp["input"].i(), out = smp["output"].i();
      const long keys = js["accessors"][static_cast<std::size_t>(in)]["count"].i();
      long k = 0;
      while (k + 1 < keys && element(g, in, k + 1, 0) <= t) ++k;
      return element(g, out, k, 0);
    }
    FAIL("no channel for node " << node);
    return -1.0;
  };
  for (int f = 0; f < 3; ++f) {
    const double t = static_cast<float>(f / 24.0) + 0.25 / 24;
    for (const RootSeries& r : roots)
      for (std::size_t k = 0; k < r.snaps.size(); ++k) {
        INFO("frame " << f << ", root " << r.name << " snapshot " << k);
        CHECK(scaleOf((*nodeNamed(g, r.name))["children"][k].i(), t) == (r.firstFrame + static_cast<int>(k) == f ? 1.0 : 0.0));
      }
  }
  // the plate covers the plate's rectangle: u from -1 mm (less its margin) to 40 mm, v from -30 mm to 0
  const J& plateMesh = js["meshes"][static_cast<std::size_t>((*nodeNamed(g, "plate"))["mesh"].i())];
  const J& pa = js["accessors"][static_cast<std::size_t>(plateMesh["primitives"][0]["attributes"]["POSITION"].i())];
  ROOTSIM_CHECK_CLOSE(pa["min"][0].n, -2e-3, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(pa["max"][0].n, 41e-3, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(pa["max"][2].n, 31e-3, kFloatRoundoff);  // glTF z = -v
  // a root without snapshots or starting before the file is refused
  CHECK_THROWS_AS(gltfPlateBinary(std::vector<RootSeries>{{"a", {}, 0}}, rtest::info(40.0)), RenderError);
  CHECK_THROWS_AS(gltfPlateBinary(std::vector<RootSeries>{{"a", {arcRoot(4, 1.0, 0.0)}, -1}}, rtest::info(40.0)), RenderError);
}
