#pragma once
// glTF 2.0 of a run, as one binary .glb file (docs/gltf.md): the root as a tube whose +d1 and -d1 stripes
// are faces of their own (materials "stripe +d1", "stripe -d1", "root body"), the plate with its 1 mm grid,
// the obstacles, an orthographic top camera, and one mesh per snapshot switched on and off by a STEP
// animation of its node's scale. Metres, +Y up: plate (u, v, w) [mm] -> glTF (u, w, -v) / 1000.
// The bytes only: the caller claims and writes the file (src/app/export_run.cpp).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the animation's rate: snapshot k of the file is shown from k / kGltfFramesPerSecond seconds on
// (Blender's and most players' default of 24 frames per second: one snapshot per frame)
inline constexpr double kGltfFramesPerSecond = 24.0;

// the tube's angular samples: each stripe (+-stripeHalfWidth around +-d1) and each body band between
// them is cut into 3 faces, so the stripes' edges are vertex columns (12 around the tube)
inline constexpr int kGltfStripeFaces = 3;
inline constexpr int kGltfBodyFaces = 3;
inline constexpr int kGltfTubeSides = 2 * (kGltfStripeFaces + kGltfBodyFaces);
// rings of the hemispherical tip cap before its apex
inline constexpr int kGltfCapRings = 4;

struct GltfOptions {
  // half the angular width of each stripe around +-d1 [deg], in (0, 90): the renderer's
  double stripeHalfWidthDeg = View{}.stripeHalfWidthDeg;
  // a plate's rectangle in the top view's plate coordinates [mm] (u0, v0, u1, v1): the plate mesh covers
  // it as well as the roots' reach (a plate run's whole plate); none: the roots' reach only
  std::optional<std::array<double, 4>> plateRectMm;
};


// the GLB file's bytes for snaps (one snapshot: a still, no animation) on the plate of info; the same
// input gives the same bytes. Throws RenderError on an empty list, a snapshot with inconsistent shapes
// or non-finite values, or a bad stripe width.
std::string gltfBinary(const std::vector<Snapshot>& snaps, const SceneInfo& info, const GltfOptions& options = {});
// a plate's GLB: one group node and one striped mesh per snapshot of each root, the file's frames those of
// the longest root (each root shown from its firstFrame on), the plate, its grid and the obstacles once.
// The same checks as above, and a root with no snapshots or starting before the first frame is refused.
std::string gltfPlateBinary(const std::vector<RootSeries>& roots, const SceneInfo& info, const GltfOptions& options = {});

}  // namespace rootsim
