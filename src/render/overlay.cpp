// overlay texts and rectangles painted onto the read-back picture on the CPU with stb_truetype:
// exact, deterministic, and independent of the GL state (libstb ships the implementation)
#include "overlay.hpp"

#include <stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

namespace rootsim::detail {

namespace {

// next code point of UTF-8 text at i (advances i); malformed bytes decode as U+FFFD
int nextCodepoint(const std::string& s, std::size_t& i) {
  const auto b0 = static_cast<unsigned char>(s[i++]);
  if (b0 < 0x80) return b0;
  int extra = b0 >= 0xF0 ? 3 : b0 >= 0xE0 ? 2 : b0 >= 0xC0 ? 1 : -1;
  if (extra < 0) return 0xFFFD;
  int cp = b0 & (0x3F >> extra);
  for (; extra > 0; --extra) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  }
  return cp;
}

// alpha-blend colour c with coverage a (0..255) over the straight-alpha pixel p
void blend(std::uint8_t* p, const std::array<std::uint8_t, 4>& c, unsigned cover) {
  const unsigned a = cover * c[3] / 255u;
  if (a == 0) return;
  const unsigned dstA = p[3];
  const unsigned outA = a + dstA * (255u - a) / 255u;
  if (outA == 0) return;
  for (int k = 0; k < 3; ++k) {
    const unsigned num = c[static_cast<std::size_t>(k)] * a * 255u + p[k] * dstA * (255u - a);
    p[k] = static_cast<std::uint8_t>(std::min(255u, (num + outA * 127u) / (outA * 255u)));
  }
  p[3] = static_cast<std::uint8_t>(outA);
}

struct Glyph {
  std::vector<unsigned char> bitmap;  // coverage, w x h
  int w = 0, h = 0, x0 = 0, y0 = 0;   // box relative to the pen on the baseline [px]
  float advance = 0;                  // [px]
};

struct Font {
  std::vector<unsigned char> data;
  stbtt_fontinfo info{};
  std::map<std::pair<int, float>, Glyph> glyphs;  // (code point, pixel height)

  const Glyph& glyph(int cp, float sizePx) {
    const auto key = std::make_pair(cp, sizePx);
    auto it = glyphs.find(key);
    if (it != glyphs.end()) return it->second;
    Glyph g;
    const float scale = stbtt_ScaleForPixelHeight(&info, sizePx);
    int adv = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&info, cp, &adv, &lsb);
    g.advance = static_cast<float>(adv) * scale;
    int x1 = 0, y1 = 0;
    stbtt_GetCodepointBitmapBox(&info, cp, scale, scale, &g.x0, &g.y0, &x1, &y1);
    g.w = std::max(0, x1 - g.x0);
    g.h = std::max(0, y1 - g.y0);
    if (g.w > 0 && g.h > 0) {
      g.bitmap.resize(static_cast<std::size_t>(g.w) * g.h);
      stbtt_MakeCodepointBitmap(&info, g.bitmap.data(), g.w, g.h, g.w, scale, scale, cp);
    }
    return glyphs.emplace(key, std::move(g)).first->second;
  }
};

}  // namespace

struct OverlayPainter::Impl {
  std::map<std::string, Font> fonts;
  // the pixels left as they are while drawing (the root's footprint), in image pixels offset by off
  const RootFootprint* keepOut = nullptr;
  int offX = 0, offY = 0;
  bool kept(int x, int y) const { return keepOut && keepOut->covers(x - offX, y - offY); }

  Font& font(const std::string& path) {
    auto it = fonts.find(path);
    if (it != fonts.end()) return it->second;
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw RenderError("overlay font " + path +
                        ": cannot open (install the Debian package fonts-dejavu-core, or set View::fontPath)");
    Font f;
    f.data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    const int off = f.data.empty() ? -1 : stbtt_GetFontOffsetForIndex(f.data.data(), 0);
    if (off < 0 || !stbtt_InitFont(&f.info, f.data.data(), off))
      throw RenderError("overlay font " + path + ": not a TrueType font (stbtt_InitFont failed)");
    // stbtt_fontinfo points into data; moving the vector keeps its heap buffer, so the pointer holds
    return fonts.emplace(path, std::move(f)).first->second;
  }

  // width [px] and the ascent/descent [px] of one line
  std::tuple<float, float, float> measure(Font& f, const std::string& text, float sizePx) {
    const float scale = stbtt_ScaleForPixelHeight(&f.info, sizePx);
    int asc = 0, desc = 0, gap = 0;
    stbtt_GetFontVMetrics(&f.info, &asc, &desc, &gap);
    float w = 0;
    int prev = 0;
    for (std::size_t i = 0; i < text.size();) {
      const int cp = nextCodepoint(text, i);
      if (prev) w += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&f.info, prev, cp));
      w += f.glyph(cp, sizePx).advance;
      prev = cp;
    }
    return {w, scale * static_cast<float>(asc), -scale * static_cast<float>(desc)};
  }

  void drawText(const OverlayText& t, const std::string& fontPath, Image& img) {
    Font& f = font(fontPath);
    const auto [w, asc, desc] = measure(f, t.text, t.sizePx);
    // top-left of the text box from the anchor
    float x = t.x, y = t.y;
    using A = OverlayText::Anchor;
    if (t.anchor == A::TopRight || t.anchor == A::BottomRight) x -= w;
    if (t.anchor == A::BottomCentre) x -= 0.5f * w;
    if (t.anchor == A::BottomLeft || t.anchor == A::BottomRight || t.anchor == A::BottomCentre) y -= asc + desc;
    const float scale = stbtt_ScaleForPixelHeight(&f.info, t.sizePx);
    // whole-pixel pen positions: crisp glyphs, identical on every frame
    const int baseline = static_cast<int>(std::lround(y + asc));
    float pen = std::round(x);
    int prev = 0;
    for (std::size_t i = 0; i < t.text.size();) {
      const int cp = nextCodepoint(t.text, i);
      if (prev) pen += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&f.info, prev, cp));
      const Glyph& g = f.glyph(cp, t.sizePx);
      const int gx = static_cast<int>(std::lround(pen)) + g.x0, gy = baseline + g.y0;
      for (int r = 0; r < g.h; ++r) {
        const int py = gy + r;
        if (py < 0 || py >= img.height) continue;
        for (int c = 0; c < g.w; ++c) {
          const int px = gx + c;
          if (px < 0 || px >= img.width || kept(px, py)) continue;
          blend(img.at(px, py), t.colour, g.bitmap[static_cast<std::size_t>(r) * g.w + c]);
        }
      }
      pen += g.advance;
      prev = cp;
    }
  }

  std::vector<float> cover;  // coverage of one line over its bounding box (reused)

  // a thick anti-aliased polyline: coverage from the distance to the nearest segment, collected over
  // the whole line first (max), so joints are not blended twice
  void drawLine(const OverlayLine& l, Image& img) {
    if (l.points.empty()) return;
    const bool masked = !l.overRoot;
    const float hw = 0.5f * l.widthPx;
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    for (const auto& p : l.points) {
      x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]);
      x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
    }
    const int bx0 = std::max(0, static_cast<int>(std::floor(x0 - hw - 1)));
    const int by0 = std::max(0, static_cast<int>(std::floor(y0 - hw - 1)));
    const int bx1 = std::min(img.width, static_cast<int>(std::ceil(x1 + hw + 2)));
    const int by1 = std::min(img.height, static_cast<int>(std::ceil(y1 + hw + 2)));
    if (bx0 >= bx1 || by0 >= by1) return;
    const int bw = bx1 - bx0, bh = by1 - by0;
    cover.assign(static_cast<std::size_t>(bw) * bh, 0.0f);
    const std::size_t segs = l.points.size() == 1 ? 1 : l.points.size() - 1;
    for (std::size_t i = 0; i < segs; ++i) {
      const auto& a = l.points[i];
      const auto& b = l.points[std::min(i + 1, l.points.size() - 1)];
      const int sx0 = std::max(bx0, static_cast<int>(std::floor(std::min(a[0], b[0]) - hw - 1)));
      const int sy0 = std::max(by0, static_cast<int>(std::floor(std::min(a[1], b[1]) - hw - 1)));
      const int sx1 = std::min(bx1, static_cast<int>(std::ceil(std::max(a[0], b[0]) + hw + 2)));
      const int sy1 = std::min(by1, static_cast<int>(std::ceil(std::max(a[1], b[1]) + hw + 2)));
      const float dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
      for (int y = sy0; y < sy1; ++y)
        for (int x = sx0; x < sx1; ++x) {
          // pixel centre to the segment
          const float px = static_cast<float>(x) + 0.5f - a[0], py = static_cast<float>(y) + 0.5f - a[1];
          const float t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0f, 1.0f) : 0.0f;
          const float ex = px - t * dx, ey = py - t * dy;
          const float c = std::clamp(hw + 0.5f - std::sqrt(ex * ex + ey * ey), 0.0f, 1.0f);
          float& cv = cover[static_cast<std::size_t>(y - by0) * bw + (x - bx0)];
          cv = std::max(cv, c);
        }
    }
    for (int y = by0; y < by1; ++y)
      for (int x = bx0; x < bx1; ++x) {
        const float c = cover[static_cast<std::size_t>(y - by0) * bw + (x - bx0)];
        if (c > 0 && !(masked && kept(x, y))) blend(img.at(x, y), l.colour, static_cast<unsigned>(std::lround(255.0f * c)));
      }
  }

  void drawRect(const OverlayRect& r, Image& img) const {
    const int x0 = std::max(0, static_cast<int>(std::lround(r.x)));
    const int y0 = std::max(0, static_cast<int>(std::lround(r.y)));
    const int x1 = std::min(img.width, static_cast<int>(std::lround(r.x + r.w)));
    const int y1 = std::min(img.height, static_cast<int>(std::lround(r.y + r.h)));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (!kept(x, y)) blend(img.at(x, y), r.colour, 255);
  }
};

OverlayPainter::OverlayPainter() : impl_(std::make_unique<Impl>()) {}
OverlayPainter::~OverlayPainter() = default;

void OverlayPainter::draw(const RenderScene& scene, Image& img) {
  draw(scene.rects, scene.lines, scene.texts, scene.fontPath, img, scene.keepOut.get());
}

void OverlayPainter::draw(const std::vector<OverlayRect>& rects, const std::vector<OverlayLine>& lines,
                          const std::vector<OverlayText>& texts, const std::string& fontPath, Image& img,
                          const RootFootprint* keepOut, int offX, int offY) {
  impl_->keepOut = keepOut, impl_->offX = offX, impl_->offY = offY;
  for (const OverlayRect& r : rects) impl_->drawRect(r, img);
  for (const OverlayLine& l : lines) impl_->drawLine(l, img);
  for (const OverlayText& t : texts) impl_->drawText(t, fontPath, img);
  impl_->keepOut = nullptr;
}

float OverlayPainter::textWidth(const std::string& fontPath, const std::string& text, float sizePx) {
  return std::get<0>(impl_->measure(impl_->font(fontPath), text, sizePx));
}

float measureText(const std::string& fontPath, const std::string& text, float sizePx) {
  static std::mutex mutex;
  static OverlayPainter painter;
  const std::lock_guard<std::mutex> lock(mutex);
  try {
    return painter.textWidth(fontPath, text, sizePx);
  } catch (const RenderError&) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < text.size();) nextCodepoint(text, i), ++n;
    return 0.6f * sizePx * static_cast<float>(n);
  }
}

}  // namespace rootsim::detail
