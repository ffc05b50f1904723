// abstract render scene -> pixels with OSMesa (llvmpipe), offscreen, core profile 4.5.
// Draws into its own 4x multisampled framebuffer, resolves with a blit, reads back with glReadPixels
// (docs/rendering.md, Pitfalls: this works at any size, independent of the OSMesa buffer).
#include "rootsim/gl_renderer.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "overlay.hpp"
#include "shaders.hpp"

namespace rootsim {

namespace {

std::string hex(unsigned v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04X", v);
  return b;
}

// throw if the GL error flag is set after `call`
void checkGl(const char* call) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw RenderError(std::string("GL: ") + call + " failed with error " + hex(e));
}

std::string shaderSource(const std::string& dir, const char* name) {
  if (dir.empty()) {
    const char* src = detail::builtinShader(name);
    if (!src) throw RenderError(std::string("GL: no built-in shader ") + name);
    return src;
  }
  const std::string path = dir + "/" + name;
  std::ifstream in(path);
  if (!in) throw RenderError("GL: cannot read shader " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

GLuint compile(GLenum type, const std::string& src, const char* name) {
  const GLuint s = glCreateShader(type);
  if (!s) throw RenderError(std::string("GL: glCreateShader for ") + name + " returned 0");
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    throw RenderError(std::string("GL: glCompileShader(") + name + ") failed: " + log);
  }
  return s;
}

GLuint link(const std::string& dir, const char* vert, const char* frag) {
  const GLuint vs = compile(GL_VERTEX_SHADER, shaderSource(dir, vert), vert);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, shaderSource(dir, frag), frag);
  const GLuint prog = glCreateProgram();
  glAttachShader(prog, vs);
  glAttachShader(prog, fs);
  glLinkProgram(prog);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(prog, sizeof log, nullptr, log);
    glDeleteProgram(prog);
    throw RenderError(std::string("GL: glLinkProgram(") + vert + ", " + frag + ") failed: " + log);
  }
  return prog;
}

// an OSMesa core-profile context, current on this thread while it lives
class Context {
 public:
  Context() {
    const int attribs[] = {OSMESA_FORMAT,         OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_STENCIL_BITS,   0,           OSMESA_PROFILE,    OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,    OSMESA_CONTEXT_MINOR_VERSION, 5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_)
      throw RenderError("OSMesa: OSMesaCreateContextAttribs(core profile 4.5) returned NULL "
                        "(is libosmesa6 installed; GALLIUM_DRIVER=softpipe only offers 3.3)");
    makeCurrent();
  }
  ~Context() { OSMesaDestroyContext(ctx_); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  void makeCurrent() {
    // the OSMesa buffer is only a binding target: every frame goes to our own framebuffers
    if (!OSMesaMakeCurrent(ctx_, osmesaBuffer_, GL_UNSIGNED_BYTE, 4, 4))
      throw RenderError("OSMesa: OSMesaMakeCurrent failed");
  }

 private:
  OSMesaContext ctx_ = nullptr;
  unsigned char osmesaBuffer_[4 * 4 * 4] = {};
};

}  // namespace

struct GlRenderer::Impl {
  Context ctx;
  RendererOptions opt;
  int width = 0, height = 0, samples = 1;
  GLuint msFbo = 0, msColour = 0, msDepth = 0, resFbo = 0, resColour = 0;
  GLuint plateFbo = 0, plateColour = 0, plateDepth = 0;  // the plate of the last frame (fixed camera)
  std::vector<float> plateKey;                           // what it was drawn with; empty: none
  std::vector<float> lastKey;                            // the plate of the previous frame
  GLuint tubeProg = 0, planeProg = 0, shadowProg = 0, shadeProg = 0;
  GLuint shadowFbo = 0, shadowTex = 0;                   // the shadow map (depth texture)
  int shadowSize = 0;                                    // its side [px]
  GLuint tubeVao = 0, tubeVbo = 0, tubeIbo = 0, planeVao = 0, planeVbo = 0;
  std::vector<std::uint8_t> readback;
  std::vector<float> plateTris;                          // plate triangles (u, v) [mm] of this frame
  detail::OverlayPainter overlays;
  std::string version;

  explicit Impl(const RendererOptions& o) : opt(o) {
    const char* ver = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const char* ren = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (!ver)
      throw RenderError("GL: glGetString(GL_VERSION) is NULL: no usable context (is libGL linked "
                        "besides libOSMesa?)");
    version = std::string(ver) + " / " + (ren ? ren : "?");
    GLint maxSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    samples = std::clamp(opt.samples, 1, std::max(1, static_cast<int>(maxSamples)));

    tubeProg = link(opt.shaderDir, "tube.vert", "tube.frag");
    planeProg = link(opt.shaderDir, "plane.vert", "plane.frag");
    shadowProg = link(opt.shaderDir, "shadow.vert", "shadow.frag");
    shadeProg = link(opt.shaderDir, "plane.vert", "shade.frag");

    glGenVertexArrays(1, &tubeVao);
    glGenBuffers(1, &tubeVbo);
    glGenBuffers(1, &tubeIbo);
    if (!tubeVao || !tubeVbo || !tubeIbo) throw RenderError("GL: glGenVertexArrays/glGenBuffers returned 0");
    glBindVertexArray(tubeVao);
    glBindBuffer(GL_ARRAY_BUFFER, tubeVbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, tubeIbo);
    const auto stride = static_cast<GLsizei>(sizeof(TubeVertex));
    auto attrib = [&](GLuint loc, GLint n, std::size_t off) {
      glEnableVertexAttribArray(loc);
      glVertexAttribPointer(loc, n, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(off));
    };
    attrib(0, 3, offsetof(TubeVertex, pos));
    attrib(1, 3, offsetof(TubeVertex, normal));
    attrib(2, 2, offsetof(TubeVertex, side));
    attrib(3, 3, offsetof(TubeVertex, colour));
    attrib(4, 1, offsetof(TubeVertex, striped));

    glGenVertexArrays(1, &planeVao);
    glGenBuffers(1, &planeVbo);
    glBindVertexArray(planeVao);
    glBindBuffer(GL_ARRAY_BUFFER, planeVbo);
    glBufferData(GL_ARRAY_BUFFER, 8 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glBindVertexArray(0);
    checkGl("vertex array setup");
  }

  ~Impl() {
    ctx.makeCurrent();
    freeTargets();
    glDeleteBuffers(1, &tubeVbo);
    glDeleteBuffers(1, &tubeIbo);
    glDeleteBuffers(1, &planeVbo);
    glDeleteVertexArrays(1, &tubeVao);
    glDeleteVertexArrays(1, &planeVao);
    glDeleteProgram(tubeProg);
    glDeleteProgram(planeProg);
    glDeleteProgram(shadowProg);
    glDeleteProgram(shadeProg);
    if (shadowFbo) glDeleteFramebuffers(1, &shadowFbo);
    if (shadowTex) glDeleteTextures(1, &shadowTex);
  }

  // a depth texture of side px, compared in the shader (sampler2DShadow), lit outside its border
  void ensureShadowMap(int px) {
    if (shadowFbo && shadowSize == px) return;
    if (shadowFbo) glDeleteFramebuffers(1, &shadowFbo);
    if (shadowTex) glDeleteTextures(1, &shadowTex);
    glGenTextures(1, &shadowTex);
    glBindTexture(GL_TEXTURE_2D, shadowTex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, px, px, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float border[4] = {1, 1, 1, 1};
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glGenFramebuffers(1, &shadowFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTex, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    const GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) throw RenderError("GL: glCheckFramebufferStatus(shadow map) = " + hex(st));
    checkGl("shadow map setup");
    shadowSize = px;
  }

  // the root's depth from the key light into the shadow map (tube buffers already uploaded)
  void drawShadowMap(const RenderScene& s) {
    ensureShadowMap(s.shadowMapPx);
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
    glViewport(0, 0, shadowSize, shadowSize);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(shadowProg);
    glUniformMatrix4fv(glGetUniformLocation(shadowProg, "uLightViewProj"), 1, GL_FALSE, s.lightViewProj.data());
    glBindVertexArray(tubeVao);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.indices.size()), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    checkGl("draw shadow map");
    glViewport(0, 0, width, height);
  }

  void freeTargets() {
    if (msFbo) glDeleteFramebuffers(1, &msFbo);
    if (resFbo) glDeleteFramebuffers(1, &resFbo);
    if (plateFbo) glDeleteFramebuffers(1, &plateFbo);
    GLuint rbs[] = {msColour, msDepth, resColour, plateColour, plateDepth};
    glDeleteRenderbuffers(5, rbs);
    msFbo = resFbo = msColour = msDepth = resColour = plateFbo = plateColour = plateDepth = 0;
    plateKey.clear();
  }

  // everything the plate's pixels depend on: same key, same pixels
  static std::vector<float> keyOf(const RenderScene& s) {
    const auto& p = s.plate;
    std::vector<float> k{static_cast<float>(s.width), static_cast<float>(s.height), p.u0, p.v0, p.u1, p.v1,
                         p.gridMm, static_cast<float>(p.majorEvery), p.lineWidthPx};
    k.insert(k.end(), s.viewMatrix.begin(), s.viewMatrix.end());
    k.insert(k.end(), s.projMatrix.begin(), s.projMatrix.end());
    k.insert(k.end(), s.background.begin(), s.background.end());
    for (const auto* c : {&p.colour, &p.line, &p.major}) k.insert(k.end(), c->begin(), c->end());
    return k;
  }

  // a multisampled copy of the cleared buffers with the plate drawn, for the frames that follow
  void storePlate(const std::vector<float>& key) {
    if (!plateFbo) {
      glGenFramebuffers(1, &plateFbo);
      glGenRenderbuffers(1, &plateColour);
      glGenRenderbuffers(1, &plateDepth);
      glBindRenderbuffer(GL_RENDERBUFFER, plateColour);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
      glBindRenderbuffer(GL_RENDERBUFFER, plateDepth);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
      glBindFramebuffer(GL_FRAMEBUFFER, plateFbo);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, plateColour);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, plateDepth);
      const GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
      if (st != GL_FRAMEBUFFER_COMPLETE) throw RenderError("GL: glCheckFramebufferStatus(plate cache) = " + hex(st));
    }
    copyBuffers(msFbo, plateFbo);
    checkGl("store the plate (glBlitFramebuffer)");
    plateKey = key;
  }

  void copyBuffers(GLuint from, GLuint to) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT,
                      GL_NEAREST);
  }

  // (re)create the multisampled and the resolve framebuffers at w x h
  void resize(int w, int h) {
    if (w == width && h == height && msFbo) return;
    if (w <= 0 || h <= 0)
      throw RenderError("GL renderer: size must be positive (got " + std::to_string(w) + "x" + std::to_string(h) + ")");
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (w > maxSize || h > maxSize)
      throw RenderError("GL renderer: " + std::to_string(w) + "x" + std::to_string(h) +
                        " exceeds GL_MAX_RENDERBUFFER_SIZE " + std::to_string(maxSize));
    freeTargets();
    glGenFramebuffers(1, &msFbo);
    glGenRenderbuffers(1, &msColour);
    glGenRenderbuffers(1, &msDepth);
    glBindRenderbuffer(GL_RENDERBUFFER, msColour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, msDepth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    checkGl("glRenderbufferStorageMultisample");
    glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msDepth);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
      throw RenderError("GL: glCheckFramebufferStatus(multisampled, " + std::to_string(samples) +
                        " samples) = " + hex(st));

    glGenFramebuffers(1, &resFbo);
    glGenRenderbuffers(1, &resColour);
    glBindRenderbuffer(GL_RENDERBUFFER, resColour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, resFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resColour);
    st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) throw RenderError("GL: glCheckFramebufferStatus(resolve) = " + hex(st));
    checkGl("framebuffer setup");
    width = w;
    height = h;
  }

  void draw(const RenderScene& s) {
    // the root's vertices, for the shadow pass and the colour pass
    if (!s.indices.empty()) {
      glBindVertexArray(tubeVao);
      glBindBuffer(GL_ARRAY_BUFFER, tubeVbo);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.vertices.size() * sizeof(TubeVertex)),
                   s.vertices.data(), GL_STREAM_DRAW);
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.indices.size() * sizeof(std::uint32_t)),
                   s.indices.data(), GL_STREAM_DRAW);
      glBindVertexArray(0);
      checkGl("upload tube");
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    const bool shadows = s.shadows && s.plate.visible && !s.indices.empty();
    if (shadows) drawShadowMap(s);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_MULTISAMPLE);

    // a movie keeps its camera, so its plate is the same on every frame: copy the stored one (a
    // third of the drawing time at 1080p) instead of clearing and drawing it again
    const std::vector<float> key = s.plate.visible ? keyOf(s) : std::vector<float>{};
    const bool cached = s.plate.visible && key == plateKey;
    const std::vector<float> previous = std::move(lastKey);
    lastKey = key;
    if (cached) {
      copyBuffers(plateFbo, msFbo);
      checkGl("restore the plate (glBlitFramebuffer)");
    } else {
      // the top view's plate covers the picture: clear to its colour and shade only the grid lines
      const bool topPlate = s.plate.visible && s.pxPerMm > 0;
      const auto& bg = s.background;
      const auto& pc = s.plate.colour;
      glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
      if (topPlate)
        glClearColor(pc[0], pc[1], pc[2], 1.0f);
      else
        glClearColor(bg[0], bg[1], bg[2], bg[3]);
      glClearDepth(1.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }

    // the plate first, pushed back a little so the root's contact line wins the depth test
    if (s.plate.visible && !cached) {
      const auto& p = s.plate;
      // triangles in plate (u, v): in perspective the whole plate; in the top view only strips of a
      // few pixels around each grid line (the plate colour is the clear colour, and the shader's
      // line coverage is zero further than a pixel from a line): a tenth of the plate's fragments
      // when the camera moves (follow) and the plate cannot be copied
      plateTris.clear();
      auto rect = [&](float a0, float b0, float a1, float b1) {
        plateTris.insert(plateTris.end(), {a0, b0, a1, b0, a0, b1, a1, b0, a1, b1, a0, b1});
      };
      if (s.pxPerMm > 0) {
        const float half = static_cast<float>((0.5 * p.lineWidthPx + 2.0) / s.pxPerMm);
        const double g = p.gridMm;
        for (double k = std::ceil((p.u0 - half) / g); k * g <= p.u1 + half; k += 1.0)
          rect(static_cast<float>(k * g) - half, p.v0, static_cast<float>(k * g) + half, p.v1);
        for (double k = std::ceil((p.v0 - half) / g); k * g <= p.v1 + half; k += 1.0)
          rect(p.u0, static_cast<float>(k * g) - half, p.u1, static_cast<float>(k * g) + half);
      } else {
        rect(p.u0, p.v0, p.u1, p.v1);
      }
      glUseProgram(planeProg);
      glUniformMatrix4fv(glGetUniformLocation(planeProg, "uView"), 1, GL_FALSE, s.viewMatrix.data());
      glUniformMatrix4fv(glGetUniformLocation(planeProg, "uProj"), 1, GL_FALSE, s.projMatrix.data());
      glUniform1f(glGetUniformLocation(planeProg, "uGrid"), p.gridMm);
      glUniform1i(glGetUniformLocation(planeProg, "uMajorEvery"), std::max(1, p.majorEvery));
      glUniform1f(glGetUniformLocation(planeProg, "uLineWidth"), p.lineWidthPx);
      glUniform3fv(glGetUniformLocation(planeProg, "uColour"), 1, p.colour.data());
      glUniform3fv(glGetUniformLocation(planeProg, "uLine"), 1, p.line.data());
      glUniform3fv(glGetUniformLocation(planeProg, "uMajor"), 1, p.major.data());
      glBindVertexArray(planeVao);
      glBindBuffer(GL_ARRAY_BUFFER, planeVbo);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(plateTris.size() * sizeof(float)), plateTris.data(),
                   GL_STREAM_DRAW);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.0f, 1.0f);
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(plateTris.size() / 2));
      glDisable(GL_POLYGON_OFFSET_FILL);
      checkGl("draw plate");
      // keep a copy only once the camera has stood still for a frame: a moving camera (follow)
      // would pay for the copy on every frame and never use it
      if (key == previous) storePlate(key);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, msFbo);

    // the shadow: the plate under the map's footprint multiplied by the lit fraction, before the root
    // is drawn over it (no depth test: it lies in the plate)
    if (shadows) {
      glUseProgram(shadeProg);
      glUniformMatrix4fv(glGetUniformLocation(shadeProg, "uView"), 1, GL_FALSE, s.viewMatrix.data());
      glUniformMatrix4fv(glGetUniformLocation(shadeProg, "uProj"), 1, GL_FALSE, s.projMatrix.data());
      glUniformMatrix4fv(glGetUniformLocation(shadeProg, "uLightViewProj"), 1, GL_FALSE, s.lightViewProj.data());
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, shadowTex);
      glUniform1i(glGetUniformLocation(shadeProg, "uShadowMap"), 0);
      glBindVertexArray(planeVao);
      glBindBuffer(GL_ARRAY_BUFFER, planeVbo);
      glBufferData(GL_ARRAY_BUFFER, sizeof(float) * 8, s.shadowQuad.data(), GL_STREAM_DRAW);
      glDisable(GL_DEPTH_TEST);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ZERO, GL_SRC_COLOR);
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
      glDisable(GL_BLEND);
      glEnable(GL_DEPTH_TEST);
      checkGl("draw shadow");
    }

    if (!s.indices.empty()) {
      const auto& m = s.material;
      glUseProgram(tubeProg);
      glUniformMatrix4fv(glGetUniformLocation(tubeProg, "uView"), 1, GL_FALSE, s.viewMatrix.data());
      glUniformMatrix4fv(glGetUniformLocation(tubeProg, "uProj"), 1, GL_FALSE, s.projMatrix.data());
      glUniform3fv(glGetUniformLocation(tubeProg, "uLight"), 1, s.lightDir.data());
      glUniform1i(glGetUniformLocation(tubeProg, "uOrtho"), s.pxPerMm > 0 ? 1 : 0);
      glUniform3fv(glGetUniformLocation(tubeProg, "uBody"), 1, m.body.data());
      glUniform3fv(glGetUniformLocation(tubeProg, "uPlus"), 1, m.plus.data());
      glUniform3fv(glGetUniformLocation(tubeProg, "uMinus"), 1, m.minus.data());
      glUniform1f(glGetUniformLocation(tubeProg, "uStripeCos"), m.stripeCos);
      glUniform4f(glGetUniformLocation(tubeProg, "uLighting"), m.ambient, m.diffuse, m.specular, m.shininess);
      glUniform1i(glGetUniformLocation(tubeProg, "uShadows"), shadows ? 1 : 0);
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, shadows ? shadowTex : 0);
      glUniform1i(glGetUniformLocation(tubeProg, "uShadowMap"), 0);
      if (shadows) {
        glUniformMatrix4fv(glGetUniformLocation(tubeProg, "uLightViewProj"), 1, GL_FALSE, s.lightViewProj.data());
        glUniform3fv(glGetUniformLocation(tubeProg, "uLightPlate"), 1, s.lightPlate.data());
        glUniform1f(glGetUniformLocation(tubeProg, "uShadowTexel"), s.shadowTexelMm);
      }
      glBindVertexArray(tubeVao);
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.indices.size()), GL_UNSIGNED_INT, nullptr);
      checkGl("draw tube");
    }
    glBindVertexArray(0);

    // resolve the samples, then read back
    glBindFramebuffer(GL_READ_FRAMEBUFFER, msFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resFbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    checkGl("glBlitFramebuffer (MSAA resolve)");
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resFbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    readback.resize(static_cast<std::size_t>(4) * width * height);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, readback.data());
    checkGl("glReadPixels");
  }
};

GlRenderer::GlRenderer(int width, int height, const RendererOptions& opt) {
  if (width <= 0 || height <= 0)
    throw RenderError("GL renderer: size must be positive (got " + std::to_string(width) + "x" +
                      std::to_string(height) + ")");
  impl_ = std::make_unique<Impl>(opt);
  impl_->resize(width, height);
}

GlRenderer::~GlRenderer() = default;

Image GlRenderer::render(const RenderScene& scene) {
  Image img;
  render(scene, img);
  return img;
}

void GlRenderer::render(const RenderScene& scene, Image& out) {
  Impl& m = *impl_;
  m.ctx.makeCurrent();
  m.resize(scene.width, scene.height);
  m.draw(scene);

  // GL rows are bottom first: flip into the top-first image
  const int w = m.width, h = m.height;
  out.width = w;
  out.height = h;
  out.rgba.resize(static_cast<std::size_t>(4) * w * h);
  const std::size_t row = static_cast<std::size_t>(4) * w;
  for (int y = 0; y < h; ++y)
    std::memcpy(out.rgba.data() + row * y, m.readback.data() + row * (h - 1 - y), row);

  // on a transparent background the resolved edge colours are premultiplied by their coverage
  // (cleared to 0, 0, 0, 0): return straight alpha
  if (scene.background[3] < 1.0f)
    for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
      const unsigned a = out.rgba[i + 3];
      if (a == 0 || a == 255) continue;
      for (int c = 0; c < 3; ++c)
        out.rgba[i + c] = static_cast<std::uint8_t>(std::min(255u, (out.rgba[i + c] * 255u + a / 2) / a));
    }

  m.overlays.draw(scene, out);
}

int GlRenderer::samples() const { return impl_->samples; }
std::string GlRenderer::glVersion() const { return impl_->version; }

}  // namespace rootsim
