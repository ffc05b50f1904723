// glTF 2.0 binary (.glb) of a run: the mapping, the layout and the sizes are in docs/gltf.md.
//
// The file, in short:
//   nodes    "rootsim" (the scene's one root) -> "plate", "grid", "obstacles", "top view" (camera), "root";
//            "root" carries the dequantisation of the tube (translation and uniform scale, KHR_mesh_quantization)
//            and holds one node per snapshot ("frame NNNN"), scale 1 when shown and 0 when hidden
//   meshes   one per snapshot: three primitives over one vertex list (positions int16, normals int8):
//            "root body", "stripe +d1", "stripe -d1" (materials a Blender user can retarget)
//   indices  the tube's vertices are laid out so that each snapshot's triangles are a prefix of the
//            largest snapshot's: the base disc and the tip cap first (the same for every snapshot),
//            then the wall ring by ring. One index list per material serves every snapshot.
//   animation "growth": snapshot k's node has scale 1 from k / fps to (k + 1) / fps, 0 otherwise (STEP)
// Every number is little-endian; every chunk and buffer view 4-byte aligned; no time stamps.
#include "rootsim/gltf.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <utility>

#include <nlohmann/json.hpp>

#include "rootsim/content_hash.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/image.hpp"
#include "rootsim/json.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/obstacle_mesh.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/tube_rings.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

using V3 = Eigen::Vector3d;
constexpr double kPi = units::pi;

constexpr int S = kGltfStripeFaces, B = kGltfBodyFaces, kSides = kGltfTubeSides, K = kGltfCapRings;
constexpr int kBaseVertices = 1 + kSides;                     // centre and rim of the base disc
constexpr int kCapVertices = K * kSides + 1;                  // cap rings and apex
constexpr int kSideStart = kBaseVertices + kCapVertices;      // first vertex of the wall's ring 0

constexpr double kPlateMarginMm = 1.0;     // plate beyond the root's farthest reach, then whole mm
constexpr double kGridLineMm = 0.03;       // width of a 1 mm grid line
constexpr double kGridMajorLineMm = 0.06;  // width of every 10th line
// lines above the plate, each kind at its own height, so that no two faces are coplanar where lines cross
// (coplanar faces flicker in rasterisers and come out dark in Cycles): along v (constant u) 4 um, along u
// 5 um, the darker 10 mm lines 6 and 7 um
constexpr double kGridLiftMm = 0.004;
constexpr double kGridMajorLiftMm = 0.006;
constexpr double kGridCrossLiftMm = 0.001;  // the lines along u above those along v
constexpr int kMajorEvery = 10;
constexpr double kCameraHeightM = 0.1;     // the top camera above the plate [m]
constexpr float kRoughness = 0.6f;

// the glTF frame: x = u, y = w, z = -v, metres (docs/gltf.md, Axes)
V3 toGltf(const V3& plateMm) { return V3(plateMm.x(), plateMm.z(), -plateMm.y()) * units::mm; }
V3 dirToGltf(const V3& plateDir) { return V3(plateDir.x(), plateDir.z(), -plateDir.y()); }

// the renderer's colours are what its pictures show (sRGB); glTF's baseColorFactor is linear
double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// which material a face of the tube wall between angular samples k and k + 1 belongs to
enum Part { Body = 0, Plus = 1, Minus = 2 };
Part sidePart(int k) {
  if (k < S) return Plus;
  if (k < S + B) return Body;
  if (k < 2 * S + B) return Minus;
  return Body;
}

// angle of sample k from d1 towards d2 [rad]: -h .. h the +d1 stripe, then a body band, pi - h .. pi + h
// the -d1 stripe, then the other body band back to 2 pi - h
double sideAngle(int k, double h) {
  if (k <= S) return -h + 2 * h * k / S;
  if (k <= S + B) return h + (kPi - 2 * h) * (k - S) / B;
  if (k <= 2 * S + B) return kPi - h + 2 * h * (k - S - B) / S;
  return kPi + h + (kPi - 2 * h) * (k - 2 * S - B) / B;
}

// ---- the binary chunk ----

struct Bin {
  std::string bytes;
  void u8(std::uint8_t v) { bytes.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) { u8(static_cast<std::uint8_t>(v & 0xff)), u8(static_cast<std::uint8_t>(v >> 8)); }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>((v >> (8 * k)) & 0xff));
  }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void align4() {
    while (bytes.size() % 4) u8(0);
  }
};

// ---- the JSON chunk: nlohmann-json values, laid out compact by jsonText (rootsim's numbers) ----

using J = nlohmann::ordered_json;
J num(double v) { return J(v); }
J num(float v) { return J(static_cast<double>(v)); }
J num(int v) { return J(v); }
J num(std::size_t v) { return J(static_cast<std::uint64_t>(v)); }
J quote(const std::string& s) { return J(s); }
struct Member {
  std::string key;
  J value;
};
using Members = std::vector<Member>;
J arr(const std::vector<J>& items) {
  J a = J::array();
  for (const J& x : items) a.push_back(x);
  return a;
}
J obj(const Members& members) {
  J o = J::object();
  for (const Member& m : members) o[m.key] = m.value;
  return o;
}
Member kv(const std::string& key, J value) { return {key, std::move(value)}; }

// the file's tables: what the JSON lists, built in order
struct Doc {
  Bin bin;
  std::vector<J> views, accessors, meshes, nodes, materials;

  // a buffer view of bytes appended now; target 0: none (animation data)
  int view(const std::string& data, int target, int stride = 0) {
    bin.align4();
    Members m{kv("buffer", num(0)), kv("byteOffset", num(bin.bytes.size())),
                               kv("byteLength", num(data.size()))};
    if (stride) m.push_back(kv("byteStride", num(stride)));
    if (target) m.push_back(kv("target", num(target)));
    bin.bytes += data;
    views.push_back(obj(m));
    return static_cast<int>(views.size()) - 1;
  }
  int accessor(int view, std::size_t offset, int componentType, bool normalized, std::size_t count,
               const char* type, const Members& minMax = {}) {
    Members m{kv("bufferView", num(view))};
    if (offset) m.push_back(kv("byteOffset", num(offset)));
    m.push_back(kv("componentType", num(componentType)));
    if (normalized) m.push_back(kv("normalized", J(true)));
    m.push_back(kv("count", num(count)));
    m.push_back(kv("type", quote(type)));
    m.insert(m.end(), minMax.begin(), minMax.end());
    accessors.push_back(obj(m));
    return static_cast<int>(accessors.size()) - 1;
  }
  int material(const std::string& name, const std::array<float, 3>& srgb, bool doubleSided) {
    std::vector<J> c;
    for (float v : srgb) c.push_back(num(static_cast<float>(srgbToLinear(v))));
    c.push_back(num(1));
    Members m{
        kv("name", quote(name)),
        kv("pbrMetallicRoughness", obj({kv("baseColorFactor", arr(c)), kv("metallicFactor", num(0)),
                                        kv("roughnessFactor", num(kRoughness))}))};
    if (doubleSided) m.push_back(kv("doubleSided", J(true)));
    materials.push_back(obj(m));
    return static_cast<int>(materials.size()) - 1;
  }
};

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kByte = 5120, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// a float mesh (plate, grid, obstacles): positions and normals [glTF axes, m], triangles
struct FloatMesh {
  std::vector<V3> pos, nrm;
  std::vector<std::uint32_t> idx;
  void quad(const V3& a, const V3& b, const V3& c, const V3& d, const V3& n) {  // a-b-c-d counter-clockwise seen from n
    const auto o = static_cast<std::uint32_t>(pos.size());
    for (const V3* p : {&a, &b, &c, &d}) pos.push_back(*p), nrm.push_back(n);
    idx.insert(idx.end(), {o, o + 1, o + 2, o, o + 2, o + 3});
  }
};

// a primitive of a float mesh: its attributes and indices (32-bit: these meshes are small) appended
J floatPrimitive(Doc& doc, const FloatMesh& m, int material) {
  Bin data;
  std::array<float, 3> lo{}, hi{};
  lo.fill(std::numeric_limits<float>::max());
  hi.fill(-std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < m.pos.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const auto p = static_cast<float>(m.pos[i][k]);
      data.f32(p);
      lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], p);
      hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], p);
    }
    for (int k = 0; k < 3; ++k) data.f32(static_cast<float>(m.nrm[i][k]));
  }
  const int v = doc.view(data.bytes, kArrayBuffer, 24);
  const Members minMax{kv("min", arr({num(lo[0]), num(lo[1]), num(lo[2])})), kv("max", arr({num(hi[0]), num(hi[1]), num(hi[2])}))};
  const int pos = doc.accessor(v, 0, kFloat, false, m.pos.size(), "VEC3", minMax);
  const int nrm = doc.accessor(v, 12, kFloat, false, m.pos.size(), "VEC3");
  Bin ib;
  for (std::uint32_t i : m.idx) ib.u32(i);
  const int iv = doc.view(ib.bytes, kElementArrayBuffer);
  const int ia = doc.accessor(iv, 0, kUnsignedInt, false, m.idx.size(), "SCALAR");
  return obj({kv("attributes", obj({kv("POSITION", num(pos)), kv("NORMAL", num(nrm))})), kv("indices", num(ia)),
              kv("material", num(material))});
}

// ---- the tube ----

// a snapshot's tube vertices [glTF axes, m] and unit normals, in the layout of the file's comment:
// base disc (centre, rim), tip cap (K rings, apex), then the wall's rings
void tubeVertices(const std::vector<TubeRing>& rings, double h, std::vector<V3>& pos, std::vector<V3>& nrm) {
  pos.clear(), nrm.clear();
  auto add = [&](const V3& pMm, const V3& n) { pos.push_back(toGltf(pMm)), nrm.push_back(dirToGltf(n)); };
  auto around = [&](const TubeRing& g, int k) {
    const double phi = sideAngle(k, h);
    return V3(std::cos(phi) * g.a + std::sin(phi) * g.b);
  };
  const TubeRing& base = rings.front();
  add(base.c, -base.t);
  for (int k = 0; k < kSides; ++k) add(base.c + base.r * around(base, k), -base.t);
  const TubeRing& tip = rings.back();
  for (int j = 0; j < K; ++j) {
    const double th = 0.5 * kPi * j / K;
    for (int k = 0; k < kSides; ++k) {
      const V3 n = std::cos(th) * around(tip, k) + std::sin(th) * tip.t;
      add(tip.c + tip.r * n, n);
    }
  }
  add(tip.c + tip.r * tip.t, tip.t);
  for (const TubeRing& g : rings)
    for (int k = 0; k < kSides; ++k) add(g.c + g.r * around(g, k), around(g, k));
}

// the triangles of a tube of `rings` rings, one list per material (Body, Plus, Minus): the fixed part
// (base disc, cap) first, then the wall band by band, so a tube of fewer rings uses a prefix of each list
std::array<std::vector<std::uint32_t>, 3> tubeTriangles(int rings) {
  std::array<std::vector<std::uint32_t>, 3> out;
  auto tri = [&](Part p, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    out[static_cast<std::size_t>(p)].insert(out[static_cast<std::size_t>(p)].end(), {a, b, c});
  };
  auto next = [](int k) { return static_cast<std::uint32_t>((k + 1) % kSides); };
  // ring j's sample k, rings starting at vertex `first`
  auto at = [](int first, int j, std::uint32_t k) { return static_cast<std::uint32_t>(first + j * kSides) + k; };
  auto band = [&](int first, int j) {
    for (int k = 0; k < kSides; ++k) {
      const auto kk = static_cast<std::uint32_t>(k);
      const std::uint32_t a = at(first, j, kk), b = at(first, j, next(k)), c = at(first, j + 1, kk), d = at(first, j + 1, next(k));
      tri(sidePart(k), a, b, d);
      tri(sidePart(k), a, d, c);
    }
  };
  for (int k = 0; k < kSides; ++k) tri(Body, 0, 1 + next(k), 1 + static_cast<std::uint32_t>(k));  // faces -t
  for (int j = 0; j + 1 < K; ++j) band(kBaseVertices, j);
  const auto apex = static_cast<std::uint32_t>(kBaseVertices + K * kSides);
  for (int k = 0; k < kSides; ++k)
    tri(sidePart(k), at(kBaseVertices, K - 1, static_cast<std::uint32_t>(k)), at(kBaseVertices, K - 1, next(k)), apex);
  for (int j = 0; j + 1 < rings; ++j) band(kSideStart, j);
  return out;
}

// the number of indices of each material's list that a tube of `rings` rings uses
std::array<std::size_t, 3> tubeIndexCounts(int rings) {
  const std::size_t fixedBody = 3 * kSides + 6 * 2 * B * (K - 1) + 3 * 2 * B;
  const std::size_t fixedStripe = 6 * S * (K - 1) + 3 * S;
  const auto bands = static_cast<std::size_t>(rings - 1);
  return {fixedBody + bands * 6 * 2 * B, fixedStripe + bands * 6 * S, fixedStripe + bands * 6 * S};
}

std::string frameName(int k, const Snapshot& s) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "frame %04d, t = %.2f h", k, s.timeH);
  return buf;
}

}  // namespace

namespace {

// the plate's extent [mm] (u0 .. u1, v0 .. v1): what the plate, its grid and the top camera cover
struct PlateBox {
  double u0 = std::numeric_limits<double>::infinity(), u1 = -std::numeric_limits<double>::infinity();
  double v0 = std::numeric_limits<double>::infinity(), v1 = -std::numeric_limits<double>::infinity();
};

// the file being built: its tables, the scene root's children, each snapshot's node with the file's frame
// it shows, and the plate's extent so far
struct Build {
  Doc doc;
  std::vector<J> top;
  std::vector<std::pair<int, int>> frameNodes;
  PlateBox box;
  // a node appended; its index
  int node(J n) {
    doc.nodes.push_back(std::move(n));
    return static_cast<int>(doc.nodes.size()) - 1;
  }
  // a mesh appended and a node showing it under the scene root
  void topMesh(const std::string& name, const std::vector<J>& prims) {
    doc.meshes.push_back(obj({kv("name", quote(name)), kv("primitives", arr(prims))}));
    top.push_back(num(node(obj({kv("name", quote(name)), kv("mesh", num(static_cast<int>(doc.meshes.size()) - 1))}))));
  }
};

// the roots and the options checked; the file's number of frames
int checkedFrames(const std::vector<RootSeries>& roots, const GltfOptions& options) {
  if (roots.empty()) throw RenderError("glTF: no roots to write");
  if (!(options.stripeHalfWidthDeg > 0.0 && options.stripeHalfWidthDeg < 90.0))
    throw RenderError("glTF: the stripe half width must be in (0, 90) degrees (got " +
                      numberText(options.stripeHalfWidthDeg) + ")");
  int frames = 0;
  for (const RootSeries& r : roots) {
    if (r.snaps.empty()) throw RenderError("glTF: root " + r.name + " has no snapshots to write");
    if (r.firstFrame < 0) throw RenderError("glTF: root " + r.name + " starts before the file's first frame");
    for (const Snapshot& s : r.snaps) checkTubeSnapshot(s, "glTF");
    frames = std::max(frames, r.firstFrame + static_cast<int>(r.snaps.size()));
  }
  return frames;
}

// a root's int16 position grid, shared by all its snapshots: q / 32767 * half + centre (its group node)
struct TubeGrid {
  V3 centre;
  double half = 0;
  int maxRings = 0;  // the largest tube's rings
};

// the tube's reach over all snapshots (every surface point is within r of its ring's centre), its grid;
// the plate's extent grown to hold it
TubeGrid tubeGrid(const RootSeries& root, const PlateFrame& pf, PlateBox& box) {
  const double inf = std::numeric_limits<double>::infinity();
  V3 lo = V3::Constant(inf), hi = V3::Constant(-inf);  // glTF axes [m]
  TubeGrid g;
  for (const Snapshot& s : root.snaps) {
    const std::vector<TubeRing> rings = tubeRings(s, pf);
    g.maxRings = std::max(g.maxRings, static_cast<int>(rings.size()));
    for (const TubeRing& ring : rings) {
      const V3 c = toGltf(ring.c), r = V3::Constant(ring.r * units::mm);
      lo = lo.cwiseMin(c - r), hi = hi.cwiseMax(c + r);
      box.u0 = std::min(box.u0, ring.c.x() - ring.r), box.u1 = std::max(box.u1, ring.c.x() + ring.r);
      box.v0 = std::min(box.v0, ring.c.y() - ring.r), box.v1 = std::max(box.v1, ring.c.y() + ring.r);
    }
  }
  g.centre = 0.5 * (lo + hi);
  g.half = std::max(0.5 * (hi - lo).maxCoeff(), 1e-9);
  return g;
}

// a snapshot's tube vertices quantised on the grid (int16 positions, int8 normals, 12 bytes a vertex);
// their accessors (position, normal)
std::array<int, 2> tubeVertexAccessors(Doc& doc, const std::vector<V3>& pos, const std::vector<V3>& nrm, const TubeGrid& g) {
  Bin vb;
  std::array<int, 3> qlo{32767, 32767, 32767}, qhi{-32767, -32767, -32767};
  for (std::size_t i = 0; i < pos.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const auto q = static_cast<int>(std::clamp(std::lround((pos[i][c] - g.centre[c]) / g.half * 32767.0), -32767L, 32767L));
      vb.u16(static_cast<std::uint16_t>(static_cast<std::int16_t>(q)));
      qlo[static_cast<std::size_t>(c)] = std::min(qlo[static_cast<std::size_t>(c)], q);
      qhi[static_cast<std::size_t>(c)] = std::max(qhi[static_cast<std::size_t>(c)], q);
    }
    vb.u16(0);
    const V3 n = nrm[i].normalized();
    for (int c = 0; c < 3; ++c)
      vb.u8(static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp(std::lround(n[c] * 127.0), -127L, 127L))));
    vb.u8(0);
  }
  const int v = doc.view(vb.bytes, kArrayBuffer, 12);
  const Members minMax{kv("min", arr({num(qlo[0]), num(qlo[1]), num(qlo[2])})), kv("max", arr({num(qhi[0]), num(qhi[1]), num(qhi[2])}))};
  return {doc.accessor(v, 0, kShort, true, pos.size(), "VEC3", minMax), doc.accessor(v, 8, kByte, true, pos.size(), "VEC3")};
}

// one root: its index lists, one mesh and one node per snapshot under a group node carrying the grid's
// dequantisation, the group under the scene root
void addRoot(Build& b, const RootSeries& root, const PlateFrame& pf, double h, int frames, bool prefixed,
             const std::array<int, 3>& tubeMaterial) {
  Doc& doc = b.doc;
  const TubeGrid g = tubeGrid(root, pf, b.box);
  const std::size_t maxVertices = static_cast<std::size_t>(kSideStart + g.maxRings * kSides);

  // the index lists of the largest tube, one per material; every snapshot uses a prefix of each
  const bool shortIndices = maxVertices < 65535;  // 65535 is the primitive restart value
  const auto lists = tubeTriangles(g.maxRings);
  std::array<int, 3> indexView{};
  for (std::size_t m = 0; m < 3; ++m) {
    Bin ib;
    for (std::uint32_t i : lists[m]) shortIndices ? ib.u16(static_cast<std::uint16_t>(i)) : ib.u32(i);
    ib.align4();
    indexView[m] = doc.view(ib.bytes, kElementArrayBuffer);
  }

  std::vector<J> children;
  std::vector<V3> pos, nrm;
  for (std::size_t k = 0; k < root.snaps.size(); ++k) {
    const Snapshot& s = root.snaps[k];
    const int f = root.firstFrame + static_cast<int>(k);
    const std::vector<TubeRing> rings = tubeRings(s, pf);
    tubeVertices(rings, h, pos, nrm);
    const auto [pa, na] = tubeVertexAccessors(doc, pos, nrm, g);
    const auto counts = tubeIndexCounts(static_cast<int>(rings.size()));
    std::vector<J> prims;
    for (std::size_t m = 0; m < 3; ++m) {
      const int ia = doc.accessor(indexView[m], 0, shortIndices ? kUnsignedShort : kUnsignedInt, false, counts[m], "SCALAR");
      prims.push_back(obj({kv("attributes", obj({kv("POSITION", num(pa)), kv("NORMAL", num(na))})),
                           kv("indices", num(ia)), kv("material", num(tubeMaterial[m]))}));
    }
    doc.meshes.push_back(obj({kv("name", quote(root.name + " " + frameName(f, s))), kv("primitives", arr(prims))}));
    // a still, or the last snapshot, is shown by viewers that do not play the animation
    const bool shown = f == frames - 1;
    const std::string nodeName = prefixed ? root.name + " " + frameName(f, s) : frameName(f, s);
    const int n = b.node(obj({kv("name", quote(nodeName)), kv("mesh", num(static_cast<int>(doc.meshes.size()) - 1)),
                              kv("scale", shown ? arr({num(1), num(1), num(1)}) : arr({num(0), num(0), num(0)})),
                              kv("extras", obj({kv("step", num(s.step)), kv("time_h", num(s.timeH))}))}));
    b.frameNodes.emplace_back(n, f);
    children.push_back(num(n));
  }
  b.top.push_back(num(b.node(obj({kv("name", quote(root.name)), kv("children", arr(children)),
                                  kv("translation", arr({num(g.centre.x()), num(g.centre.y()), num(g.centre.z())})),
                                  kv("scale", arr({num(g.half), num(g.half), num(g.half)}))}))));
}

// the plate's extent grown to the options' plate rectangle and the obstacles, then a margin, whole mm
void finishPlateBox(PlateBox& box, const SceneInfo& info, const GltfOptions& options) {
  if (options.plateRectMm) {
    const auto& r = *options.plateRectMm;
    box.u0 = std::min(box.u0, r[0]), box.v0 = std::min(box.v0, r[1]), box.u1 = std::max(box.u1, r[2]), box.v1 = std::max(box.v1, r[3]);
  }
  for (const SceneInfo::ObstacleShape& o : info.obstacles) {
    box.u0 = std::min({box.u0, o.fromU - o.radiusMm, o.toU - o.radiusMm}), box.u1 = std::max({box.u1, o.fromU + o.radiusMm, o.toU + o.radiusMm});
    box.v0 = std::min({box.v0, o.fromV - o.radiusMm, o.toV - o.radiusMm}), box.v1 = std::max({box.v1, o.fromV + o.radiusMm, o.toV + o.radiusMm});
  }
  box.u0 = std::floor(box.u0 - kPlateMarginMm), box.u1 = std::ceil(box.u1 + kPlateMarginMm);
  box.v0 = std::floor(box.v0 - kPlateMarginMm), box.v1 = std::ceil(box.v1 + kPlateMarginMm);
}

// a point of the plate (u, v, w) [mm] in the glTF frame
V3 plateGltf(double u, double v, double w) { return toGltf(V3(u, v, w)); }

// the plate and its grid (whole millimetres, darker every 10 mm) over the plate's extent
void addPlate(Build& b) {
  const RenderScene::Plate plateLook;
  const PlateBox& x = b.box;
  const V3 up(0, 1, 0);
  FloatMesh plate;
  plate.quad(plateGltf(x.u0, x.v0, 0), plateGltf(x.u1, x.v0, 0), plateGltf(x.u1, x.v1, 0), plateGltf(x.u0, x.v1, 0), up);
  const int mat = b.doc.material("plate", plateLook.colour, false);
  b.topMesh("plate", {floatPrimitive(b.doc, plate, mat)});
  FloatMesh minor, major;
  for (int u = static_cast<int>(x.u0); u <= static_cast<int>(x.u1); ++u) {
    const bool isMajor = u % kMajorEvery == 0;
    const double hw = 0.5 * (isMajor ? kGridMajorLineMm : kGridLineMm), w = isMajor ? kGridMajorLiftMm : kGridLiftMm;
    (isMajor ? major : minor).quad(plateGltf(u - hw, x.v0, w), plateGltf(u + hw, x.v0, w), plateGltf(u + hw, x.v1, w), plateGltf(u - hw, x.v1, w), up);
  }
  for (int v = static_cast<int>(x.v0); v <= static_cast<int>(x.v1); ++v) {
    const bool isMajor = v % kMajorEvery == 0;
    const double hw = 0.5 * (isMajor ? kGridMajorLineMm : kGridLineMm);
    const double w = (isMajor ? kGridMajorLiftMm : kGridLiftMm) + kGridCrossLiftMm;
    (isMajor ? major : minor).quad(plateGltf(x.u0, v - hw, w), plateGltf(x.u1, v - hw, w), plateGltf(x.u1, v + hw, w), plateGltf(x.u0, v + hw, w), up);
  }
  std::vector<J> prims{floatPrimitive(b.doc, minor, b.doc.material("grid 1 mm", plateLook.line, false))};
  if (!major.pos.empty()) prims.push_back(floatPrimitive(b.doc, major, b.doc.material("grid 10 mm", plateLook.major, false)));
  b.topMesh("grid", prims);
}

// the obstacles: the renderer's meshes of them, in the glTF frame
void addObstacles(Build& b, const SceneInfo& info) {
  RenderScene scratch;
  addObstacleMeshes(info, scratch);
  FloatMesh m;
  for (const TubeVertex& tv : scratch.vertices) {
    m.pos.push_back(toGltf(V3(tv.pos[0], tv.pos[1], tv.pos[2])));
    m.nrm.push_back(dirToGltf(V3(tv.normal[0], tv.normal[1], tv.normal[2])));
  }
  m.idx = scratch.indices;
  const TubeVertex& first = scratch.vertices.front();
  const int mat = b.doc.material("obstacle", {first.colour[0], first.colour[1], first.colour[2]}, true);
  b.topMesh("obstacles", {floatPrimitive(b.doc, m, mat)});
}

// the top view: an orthographic camera above the plate's centre looking down -y, uphill (-z) up the
// picture: its node turned -90 degrees about x. The camera's JSON
J addTopCamera(Build& b) {
  const PlateBox& x = b.box;
  const V3 plateCentre = plateGltf(0.5 * (x.u0 + x.u1), 0.5 * (x.v0 + x.v1), 0);
  const double xmag = 0.5 * (x.u1 - x.u0) * units::mm, ymag = 0.5 * (x.v1 - x.v0) * units::mm;
  const J camera =
      obj({kv("name", quote("top view")), kv("type", quote("orthographic")),
           kv("orthographic", obj({kv("xmag", num(xmag)), kv("ymag", num(ymag)), kv("znear", num(0.01 * kCameraHeightM)),
                                   kv("zfar", num(2.0 * kCameraHeightM))}))});
  const double s2 = std::sqrt(0.5);
  b.top.push_back(num(b.node(obj({kv("name", quote("top view")), kv("camera", num(0)),
                                  kv("rotation", arr({num(-s2), num(0), num(0), num(s2)})),
                                  kv("translation", arr({num(plateCentre.x()), num(kCameraHeightM), num(plateCentre.z())}))}))));
  return camera;
}

// the animation: the node of the file's frame f has scale 1 on [f, f + 1) / fps and 0 elsewhere (STEP);
// each sampler reads a slice of one time list and one value list [0, 1, 0]. None for a single frame
Members animation(Build& b, int frames) {
  Members animations;
  if (frames <= 1) return animations;
  Doc& doc = b.doc;
  Bin times, values;
  for (int f = 0; f < frames; ++f) times.f32(static_cast<float>(f / kGltfFramesPerSecond));
  for (float v : {0.0f, 1.0f, 0.0f})
    for (int k = 0; k < 3; ++k) values.f32(v);
  const int tv = doc.view(times.bytes, 0), vv = doc.view(values.bytes, 0);
  std::vector<J> samplers, channels;
  for (const auto& [node, f] : b.frameNodes) {
    const int first = std::max(0, f - 1), last = std::min(frames - 1, f + 1);
    const auto t0 = static_cast<float>(first / kGltfFramesPerSecond), t1 = static_cast<float>(last / kGltfFramesPerSecond);
    const int in = doc.accessor(tv, static_cast<std::size_t>(first) * 4, kFloat, false, static_cast<std::size_t>(last - first + 1),
                                "SCALAR", {kv("min", arr({num(t0)})), kv("max", arr({num(t1)}))});
    // values from [0, 1, 0]: the first frame starts at its 1, the last ends at its 1
    const std::size_t valueOffset = f == 0 ? 12 : 0;
    const int out = doc.accessor(vv, valueOffset, kFloat, false, static_cast<std::size_t>(last - first + 1), "VEC3");
    samplers.push_back(obj({kv("input", num(in)), kv("output", num(out)), kv("interpolation", quote("STEP"))}));
    channels.push_back(obj({kv("sampler", num(static_cast<int>(samplers.size()) - 1)),
                            kv("target", obj({kv("node", num(node)), kv("path", quote("scale"))}))}));
  }
  animations.push_back(kv("animations", arr({obj({kv("name", quote("growth")), kv("channels", arr(channels)),
                                          kv("samplers", arr(samplers))})})));
  return animations;
}

// the GLB file: its JSON chunk (the document, signed) and its BIN chunk
std::string glbFile(Doc& doc, const SceneInfo& info, const J& camera, const Members& animations, int sceneRoot) {
  doc.bin.align4();
  Members members{
      // the generator is rootsim's signature; extras hold the BIN chunk's SHA-256, so that the write rule
      // (write_rule.hpp) replaces the file only while its geometry is as written
      kv("asset", obj({kv("version", quote("2.0")), kv("generator", quote(outputSignatureText())),
                       kv("extras", obj({kv("rootsim_bin_sha256", quote(sha256Hex(doc.bin.bytes)))}))})),
      kv("extensionsUsed", arr({quote("KHR_mesh_quantization")})),
      kv("extensionsRequired", arr({quote("KHR_mesh_quantization")})),
      kv("scene", num(0)),
      kv("scenes", arr({obj({kv("name", quote(info.title.empty() ? "rootsim" : info.title)), kv("nodes", arr({num(sceneRoot)}))})})),
      kv("nodes", arr(doc.nodes)),
      kv("meshes", arr(doc.meshes)),
      kv("materials", arr(doc.materials)),
      kv("cameras", arr({camera})),
      kv("accessors", arr(doc.accessors)),
      kv("bufferViews", arr(doc.views)),
      kv("buffers", arr({obj({kv("byteLength", num(doc.bin.bytes.size()))})}))};
  members.insert(members.end(), animations.begin(), animations.end());
  std::string json = jsonText(obj(members), -1);
  while (json.size() % 4) json += ' ';

  const std::size_t total = 12 + 8 + json.size() + 8 + doc.bin.bytes.size();
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw RenderError("glTF: the file would be " + std::to_string(total) + " bytes, more than a GLB can hold (4 GiB)");
  Bin glb;
  glb.u32(0x46546C67);  // "glTF"
  glb.u32(2);
  glb.u32(static_cast<std::uint32_t>(total));
  glb.u32(static_cast<std::uint32_t>(json.size()));
  glb.u32(0x4E4F534A);  // "JSON"
  glb.bytes += json;
  glb.u32(static_cast<std::uint32_t>(doc.bin.bytes.size()));
  glb.u32(0x004E4942);  // "BIN\0"
  glb.bytes += doc.bin.bytes;
  return glb.bytes;
}

// the file of roots; prefixed: each snapshot's node named after its root ("NAME frame NNNN, ..."), as a
// plate's are (a single root's are "frame NNNN, ...", under the group "root")
std::string gltfOf(const std::vector<RootSeries>& roots, const SceneInfo& info, const GltfOptions& options, bool prefixed) {
  const int frames = checkedFrames(roots, options);
  const double h = options.stripeHalfWidthDeg * units::deg;
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  Build b;
  const RenderScene::Material look;
  const int matBody = b.doc.material("root body", look.body, false);
  const int matPlus = b.doc.material("stripe +d1", look.plus, false);
  const int matMinus = b.doc.material("stripe -d1", look.minus, false);
  for (const RootSeries& root : roots) addRoot(b, root, pf, h, frames, prefixed, {matBody, matPlus, matMinus});
  finishPlateBox(b.box, info, options);
  if (info.plate) addPlate(b);
  if (!info.obstacles.empty()) addObstacles(b, info);
  const J camera = addTopCamera(b);
  const Members animations = animation(b, frames);
  const int sceneRoot = b.node(obj({kv("name", quote("rootsim")), kv("children", arr(b.top))}));
  return glbFile(b.doc, info, camera, animations, sceneRoot);
}

}  // namespace

std::string gltfBinary(const std::vector<Snapshot>& snaps, const SceneInfo& info, const GltfOptions& options) {
  if (snaps.empty()) throw RenderError("glTF: no snapshots to write");
  return gltfOf({RootSeries{"root", snaps, 0}}, info, options, false);
}

std::string gltfPlateBinary(const std::vector<RootSeries>& roots, const SceneInfo& info, const GltfOptions& options) {
  return gltfOf(roots, info, options, true);
}

}  // namespace rootsim
