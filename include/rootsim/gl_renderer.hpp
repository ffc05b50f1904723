#pragma once
// Abstract render scene -> pixels, offscreen with OSMesa (llvmpipe): no X server or display needed.
// The renderer never sees the simulation state. Same scene, same pixels (llvmpipe is deterministic;
// LP_NUM_THREADS only changes speed).
#include <memory>
#include <string>

#include "rootsim/image.hpp"
#include "rootsim/render_scene.hpp"

namespace rootsim {

struct RendererOptions {
  int samples = 4;          // MSAA samples requested; clamped to GL_MAX_SAMPLES (4 on llvmpipe)
  std::string shaderDir;    // development only: load tube/plane .vert/.frag from here instead of
                            // the copies built into the binary; empty (default): built-in
};

// Owns an OSMesa core-profile 4.5 context, a multisampled framebuffer and the shaders. One thread
// at a time: the context is made current on the thread that calls render().
class GlRenderer {
 public:
  // width, height [px] > 0; throws RenderError if the context or framebuffer cannot be created
  GlRenderer(int width, int height, const RendererOptions& opt = {});
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // draw scene (framebuffers follow scene.width/height), read back, draw the overlays
  Image render(const RenderScene& scene);
  void render(const RenderScene& scene, Image& out);  // reuses out's storage

  int samples() const;              // MSAA samples actually used
  std::string glVersion() const;    // GL_VERSION / GL_RENDERER, for logs

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rootsim
