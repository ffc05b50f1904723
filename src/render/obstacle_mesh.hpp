#pragma once
// internal: the obstacles of a render scene (buildRenderScene adds them)
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// obstacles of info as plain-coloured meshes: pegs as cylinders, walls as boxes
void addObstacleMeshes(const SceneInfo& info, RenderScene& rs);

}  // namespace rootsim
