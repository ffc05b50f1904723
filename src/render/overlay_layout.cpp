// the root's projected footprint and the layout step that keeps every overlay off it (no GL)
#include "rootsim/overlay_layout.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "overlay.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

RootFootprint::RootFootprint(int width, int height)
    : w_(std::max(width, 1)),
      h_(std::max(height, 1)),
      // about 270 cells along the shorter side: 2 px at 720p, 4 px at 1080p, 8 px at 4K
      cell_(std::max(2, std::min(w_, h_) / 270)),
      cw_((w_ + cell_ - 1) / cell_),
      ch_((h_ + cell_ - 1) / cell_),
      occ_(static_cast<std::size_t>(cw_) * static_cast<std::size_t>(ch_), 0) {}

void RootFootprint::addCapsule(float ax, float ay, float bx, float by, float r) {
  // a cell is taken when the capsule reaches any point of it: its centre within r + half its diagonal
  const float c = static_cast<float>(cell_);
  const float reach = r + haloPx + 0.7072f * c;
  const int i0 = std::max(0, static_cast<int>(std::floor((std::min(ax, bx) - reach) / c)));
  const int i1 = std::min(cw_ - 1, static_cast<int>(std::floor((std::max(ax, bx) + reach) / c)));
  const int j0 = std::max(0, static_cast<int>(std::floor((std::min(ay, by) - reach) / c)));
  const int j1 = std::min(ch_ - 1, static_cast<int>(std::floor((std::max(ay, by) + reach) / c)));
  if (i0 > i1 || j0 > j1) return;
  const float dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const float px = (static_cast<float>(i) + 0.5f) * c - ax, py = (static_cast<float>(j) + 0.5f) * c - ay;
      const float t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0f, 1.0f) : 0.0f;
      const float ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey <= reach * reach) occ_[static_cast<std::size_t>(j) * cw_ + i] = 1;
    }
}

void RootFootprint::add(const Snapshot& snap, const SceneInfo& info, const CameraMatrices& cam, bool whiskers) {
  glm::mat4 V, P;
  std::copy(cam.view.begin(), cam.view.end(), glm::value_ptr(V));
  std::copy(cam.proj.begin(), cam.proj.end(), glm::value_ptr(P));
  const glm::mat4 PV = P * V;
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  // a radius r [mm] at clip depth w spans r * P[1][1] * h / 2 / w pixels (orthographic: w = 1)
  const float pixelsPerMmAtUnitW = P[1][1] * 0.5f * static_cast<float>(h_);
  const long n = snap.x.cols();
  std::vector<std::array<float, 3>> px(static_cast<std::size_t>(n));  // x, y [px], w (<= 0: behind)
  for (long i = 0; i < n; ++i) {
    const Eigen::Vector3d q = pf.toPlateMm(snap.x.col(i));
    const glm::vec4 c = PV * glm::vec4(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), 1.0f);
    if (!(c.w > 0.0f)) {
      px[static_cast<std::size_t>(i)] = {0, 0, 0};
      continue;
    }
    px[static_cast<std::size_t>(i)] = {(0.5f * (c.x / c.w) + 0.5f) * static_cast<float>(w_),
                                       (0.5f - 0.5f * (c.y / c.w)) * static_cast<float>(h_), c.w};
  }
  std::size_t nextStart = 0;
  // whiskers reach 2.4 radii from the axis; the tube itself one radius (the tip cap, the base disc)
  const double reachR = whiskers ? 2.5 : 1.0;
  for (long e = 0; e + 1 < n; ++e) {
    // the element joining two roots of a merged snapshot is not drawn
    while (nextStart < snap.rootStarts.size() && snap.rootStarts[nextStart] < e + 1) ++nextStart;
    if (nextStart < snap.rootStarts.size() && snap.rootStarts[nextStart] == e + 1) continue;
    const auto& a = px[static_cast<std::size_t>(e)];
    const auto& b = px[static_cast<std::size_t>(e + 1)];
    if (!(a[2] > 0) || !(b[2] > 0)) continue;
    const double rMm = reachR * snap.radius[e] / units::mm;
    // the renderer draws a top view's tube at least 1.5 px wide
    const float r = std::max(0.75f, static_cast<float>(rMm) * pixelsPerMmAtUnitW / std::min(a[2], b[2]));
    addCapsule(a[0], a[1], b[0], b[1], r);
  }
}

void RootFootprint::merge(const RootFootprint& other) {
  if (other.w_ != w_ || other.h_ != h_) throw RenderError("root footprint: merging pictures of different sizes");
  for (std::size_t k = 0; k < occ_.size(); ++k) occ_[k] = static_cast<std::uint8_t>(occ_[k] | other.occ_[k]);
}

bool RootFootprint::covers(int x, int y) const {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return false;
  return occ_[static_cast<std::size_t>(y / cell_) * cw_ + x / cell_] != 0;
}

int RootFootprint::hits(float x0, float y0, float x1, float y1) const {
  const float c = static_cast<float>(cell_);
  const int i0 = std::max(0, static_cast<int>(std::floor(x0 / c)));
  const int i1 = std::min(cw_ - 1, static_cast<int>(std::ceil(x1 / c)) - 1);
  const int j0 = std::max(0, static_cast<int>(std::floor(y0 / c)));
  const int j1 = std::min(ch_ - 1, static_cast<int>(std::ceil(y1 / c)) - 1);
  int n = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) n += occ_[static_cast<std::size_t>(j) * cw_ + i];
  return n;
}

bool RootFootprint::empty() const {
  return std::none_of(occ_.begin(), occ_.end(), [](std::uint8_t v) { return v != 0; });
}

std::shared_ptr<const RootFootprint> rootFootprint(const std::vector<Snapshot>& snaps, const SceneInfo& info,
                                                   const View& view, const Framing& framing) {
  auto fp = std::make_shared<RootFootprint>(view.width, view.height);
  const CameraMatrices cam = cameraFor(view, framing);
  for (const Snapshot& s : snaps) fp->add(s, info, cam, view.whiskers);
  return fp;
}

std::array<float, 4> blockBox(const OverlayBlock& b, const std::string& fontPath) {
  std::array<float, 4> box{1e30f, 1e30f, -1e30f, -1e30f};
  auto grow = [&](float x0, float y0, float x1, float y1) {
    box[0] = std::min(box[0], x0), box[1] = std::min(box[1], y0);
    box[2] = std::max(box[2], x1), box[3] = std::max(box[3], y1);
  };
  for (const OverlayRect& r : b.rects) grow(r.x, r.y, r.x + r.w, r.y + r.h);
  for (const OverlayLine& l : b.lines)
    for (const auto& p : l.points) grow(p[0] - 0.5f * l.widthPx - 1, p[1] - 0.5f * l.widthPx - 1, p[0] + 0.5f * l.widthPx + 1, p[1] + 0.5f * l.widthPx + 1);
  for (const OverlayText& t : b.texts) {
    // a line of text is sizePx high (ascent + descent: stb_truetype's pixel height)
    const float w = detail::measureText(fontPath, t.text, t.sizePx), h = t.sizePx;
    float x = t.x, y = t.y;
    using A = OverlayText::Anchor;
    if (t.anchor == A::TopRight || t.anchor == A::BottomRight) x -= w;
    if (t.anchor == A::BottomCentre) x -= 0.5f * w;
    if (t.anchor == A::BottomLeft || t.anchor == A::BottomRight || t.anchor == A::BottomCentre) y -= h;
    grow(x - 1, y - 1, x + w + 1, y + h + 1);
  }
  if (box[0] > box[2]) box = {0, 0, 0, 0};
  return box;
}

namespace {

bool overlaps(const std::array<float, 4>& a, const std::array<float, 4>& b) {
  return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

// top-left corners for a bw x bh box: along each edge of the picture (17 stops), then the same on rings
// further in, nearest the preferred corner (px, py) first
std::vector<std::array<float, 2>> candidates(float bw, float bh, int W, int H, float m, float px, float py) {
  std::vector<std::array<float, 3>> c;  // x, y, cost
  const float w = static_cast<float>(W), h = static_cast<float>(H);
  const float ring = std::max(4.0f, 0.5f * std::min(bw, bh) + m);
  c.push_back({px, py, 0.0f});
  for (int k = 0; k < 8; ++k) {
    const float in = m + static_cast<float>(k) * ring;
    const float xl = in, xr = w - in - bw, yt = in, yb = h - in - bh;
    if (xr < xl || yb < yt) break;
    for (int s = 0; s <= 16; ++s) {
      const float f = static_cast<float>(s) / 16.0f;
      const float x = xl + f * (xr - xl), y = yt + f * (yb - yt);
      for (const auto& p : {std::array<float, 2>{x, yt}, {x, yb}, {xl, y}, {xr, y}}) {
        // edges before rings: a ring costs as much as moving a quarter of the picture along an edge
        const float d = std::hypot(p[0] - px, p[1] - py) + static_cast<float>(k) * 0.25f * std::max(w, h);
        c.push_back({p[0], p[1], d});
      }
    }
  }
  std::stable_sort(c.begin(), c.end(), [](const auto& a, const auto& b) { return a[2] < b[2]; });
  std::vector<std::array<float, 2>> out;
  out.reserve(c.size());
  // the preferred place as it is (cost 0, first); the others on whole pixels, so text stays crisp
  for (const auto& p : c) out.push_back(p[2] == 0.0f ? std::array<float, 2>{p[0], p[1]} : std::array<float, 2>{std::round(p[0]), std::round(p[1])});
  return out;
}

}  // namespace

std::vector<PlacedBlock> layoutBoxes(const std::vector<std::array<float, 4>>& boxes, const RootFootprint& fp,
                                     const std::vector<std::array<float, 4>>& keepClear, int width, int height,
                                     float marginPx, const std::vector<float>& minScales) {
  std::vector<std::array<float, 4>> taken = keepClear;
  std::vector<PlacedBlock> out;
  const float gap = 0.25f * marginPx;  // between two overlays
  for (std::size_t bi = 0; bi < boxes.size(); ++bi) {
    const auto& box = boxes[bi];
    const float minScale = bi < minScales.size() ? minScales[bi] : 0.64f;
    PlacedBlock best;
    bool placed = false;
    const float w0 = box[2] - box[0], h0 = box[3] - box[1];
    if (!(w0 > 0) || !(h0 > 0)) {
      out.push_back(best);
      continue;
    }
    // the least covered place at the smallest scale, for a block that finds no free place
    int leastHits = -1;
    PlacedBlock least;
    for (float scale = 1.0f; scale >= minScale - 1e-6f && !placed; scale *= 0.8f) {
      const float bw = w0 * scale, bh = h0 * scale;
      // the preferred corner: the box shrunk towards the side of the picture it sits at
      const float cx = 0.5f * (box[0] + box[2]), cy = 0.5f * (box[1] + box[3]);
      const float px = cx < 0.5f * static_cast<float>(width) ? box[0] : box[2] - bw;
      const float py = cy < 0.5f * static_cast<float>(height) ? box[1] : box[3] - bh;
      for (const auto& p : candidates(bw, bh, width, height, marginPx, px, py)) {
        const std::array<float, 4> r{p[0], p[1], p[0] + bw, p[1] + bh};
        if (r[0] < 0 || r[1] < 0 || r[2] > static_cast<float>(width) || r[3] > static_cast<float>(height)) continue;
        const std::array<float, 4> padded{r[0] - gap, r[1] - gap, r[2] + gap, r[3] + gap};
        if (std::any_of(taken.begin(), taken.end(), [&](const auto& t) { return overlaps(padded, t); })) continue;
        const int hits = fp.hits(r[0], r[1], r[2], r[3]);
        if (hits > 0) {
          if (leastHits < 0 || hits < leastHits) {
            leastHits = hits;
            least.scale = scale, least.dx = p[0] - box[0], least.dy = p[1] - box[1];
          }
          continue;
        }
        best.scale = scale;
        best.dx = p[0] - box[0];
        best.dy = p[1] - box[1];
        taken.push_back(r);
        placed = true;
        break;
      }
    }
    if (!placed) {
      // on the root whatever its place: where it covers least, on a translucent backing, under the root
      best = leastHits >= 0 ? least : PlacedBlock{};
      best.free = false;
      const float x0 = box[0] + best.dx, y0 = box[1] + best.dy;
      taken.push_back({x0, y0, x0 + best.scale * w0, y0 + best.scale * h0});
    }
    out.push_back(best);
  }
  return out;
}

void applyPlacement(OverlayBlock& b, const std::array<float, 4>& box, const PlacedBlock& p) {
  const float s = p.scale, ox = box[0], oy = box[1];
  auto mx = [&](float x) { return ox + s * (x - ox) + p.dx; };
  auto my = [&](float y) { return oy + s * (y - oy) + p.dy; };
  for (OverlayRect& r : b.rects) {
    if (s == 1.0f) {
      r.x += p.dx, r.y += p.dy;
      continue;
    }
    r.x = std::round(mx(r.x)), r.y = std::round(my(r.y));
    r.w = std::max(1.0f, std::round(s * r.w)), r.h = std::max(1.0f, std::round(s * r.h));
  }
  for (OverlayLine& l : b.lines) {
    for (auto& q : l.points) q = {mx(q[0]), my(q[1])};
    l.widthPx = std::max(1.0f, s * l.widthPx);
  }
  for (OverlayText& t : b.texts) {
    t.x = mx(t.x), t.y = my(t.y);
    if (s != 1.0f) t.sizePx = std::round(s * t.sizePx);
  }
  if (!p.free) {
    // a translucent backing with a margin, under the block's items
    const std::array<float, 4> bb{mx(box[0]), my(box[1]), mx(box[2]), my(box[3])};
    const float m = 3;
    b.rects.insert(b.rects.begin(), OverlayRect{bb[0] - m, bb[1] - m, bb[2] - bb[0] + 2 * m, bb[3] - bb[1] + 2 * m, {255, 255, 255, 170}});
  }
}

}  // namespace rootsim
