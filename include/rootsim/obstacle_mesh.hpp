#pragma once
// The obstacles of a scene as lit meshes: the renderer's scene (buildRenderScene adds them) and the glTF
// writer (src/app/gltf.cpp, which reads back the vertices and triangles) share them.
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the obstacles' height above the plate in pictures and models, in root radii (the model's obstacles are
// infinitely tall): 6 R, 0.6 mm for R = 0.1 mm
inline constexpr double kObstacleHeightRadii = 6.0;

// obstacles of info as plain-coloured meshes appended to rs.vertices / rs.indices: pegs as cylinders,
// walls as boxes, in plate coordinates [mm]
void addObstacleMeshes(const SceneInfo& info, RenderScene& rs);

}  // namespace rootsim
