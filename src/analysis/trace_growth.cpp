// Traced root systems per plant and over time (docs/experiments.md, "Plants" and "Time-lapse"): plants.csv,
// a 2D+t file's roots at each observation, roots matched across dated files by geometry, growth.csv and
// the growth rates of analysis.csv.
#include "rootsim/trace_growth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/traits.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

constexpr double kTipSpanMm = 0.5;         // the tip angle's span: at least this [mm] ...
constexpr double kTipSpanPixels = 10.0;    // ... and at least this many pixels

std::string fileName(const std::string& file) { return fs::path(file).filename().string(); }

// the nearest point of polyline p (2D: lateral, downhill) to q: squared distance and arc length there
struct Nearest {
  double d2 = std::numeric_limits<double>::infinity();
  double arc = 0;
};
Nearest nearestOn(const Eigen::Matrix3Xd& p, const Eigen::Vector2d& q) {
  Nearest best;
  double arc = 0;
  for (Eigen::Index k = 0; k + 1 < p.cols(); ++k) {
    const Eigen::Vector2d a = p.col(k).head<2>(), b = p.col(k + 1).head<2>();
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d2 = (a + s * ab - q).squaredNorm();
    if (d2 < best.d2) best = Nearest{d2, arc + s * std::sqrt(len2)};
    arc += std::sqrt(len2);
  }
  if (p.cols() == 1) best = Nearest{(p.col(0).head<2>() - q).squaredNorm(), 0.0};
  return best;
}

// whether a polyline has length (two distinct points)
bool hasLength(const Eigen::Matrix3Xd& p) { return p.cols() >= 2 && polylineLength(p) > 0; }

}  // namespace

std::vector<std::string> plausibilityWarnings(const TraceFile& tf, const AnalyzeOptions& o) {
  std::vector<std::string> out;
  for (const TracedRoot& r : tf.roots) {
    if (r.order != 0) continue;
    const double len = polylineLength(r.plateMm);
    if (len >= kPlausiblePrimaryMinMm && len <= kPlausiblePrimaryMaxMm) continue;
    const std::string check = tf.scaleSource.rfind("--", 0) == 0 || tf.scaleSource.rfind(o.flagPrefix, 0) == 0
                                  ? "check " + tf.scaleSource
                                  : "check the scale, " + tf.scaleSource + " (a file in pixels takes " + o.flagPrefix + "px-per-mm)";
    out.push_back(tf.file + ":" + std::to_string(r.line) + ": primary root " + r.key + " is " + significantText(len, 4) +
                  " mm long, implausible for a seedling (" + decimalNumber(kPlausiblePrimaryMinMm) + " to " +
                  decimalNumber(kPlausiblePrimaryMaxMm) + " mm): " + check);
  }
  return out;
}

// ---- plants ----

std::vector<PlantRow> plantRows(const TraceFile& tf, double timeH) {
  std::vector<PlantRow> rows;
  for (std::size_t b = 0; b < tf.roots.size(); ++b) {
    const TracedRoot& base = tf.roots[b];
    if (base.parentIndex >= 0) continue;
    // the seedling: the base root and every root descending from it (parents come before their laterals)
    std::vector<bool> in(tf.roots.size(), false);
    in[b] = true;
    for (std::size_t i = b + 1; i < tf.roots.size(); ++i)
      if (tf.roots[i].parentIndex >= 0 && in[static_cast<std::size_t>(tf.roots[i].parentIndex)]) in[i] = true;
    PlantRow row;
    row.file = tf.file;
    row.timeH = timeH;
    row.plant = base.plant;
    row.plantLabel = base.plantLabel;
    row.root = base.name;
    row.primaryLengthMm = polylineLength(base.plateMm);
    double latMin = std::numeric_limits<double>::infinity(), latMax = -latMin, downMin = latMin, downMax = -latMin;
    std::vector<double> insertions;
    for (std::size_t i = 0; i < tf.roots.size(); ++i) {
      if (!in[i]) continue;
      const TracedRoot& r = tf.roots[i];
      const double len = polylineLength(r.plateMm);
      ++row.roots;
      row.totalLengthMm += len;
      if (i != b) {
        ++row.lateralCount;
        row.lateralLengthMm += len;
      }
      if (r.parentIndex == static_cast<int>(b)) {
        ++row.primaryLaterals;
        insertions.push_back(nearestOn(base.plateMm, r.plateMm.col(0).head<2>()).arc);
      }
      for (Eigen::Index k = 0; k < r.plateMm.cols(); ++k) {
        latMin = std::min(latMin, r.plateMm(0, k));
        latMax = std::max(latMax, r.plateMm(0, k));
        downMin = std::min(downMin, r.plateMm(1, k));
        downMax = std::max(downMax, r.plateMm(1, k));
      }
    }
    row.widthMm = latMax - latMin;
    row.depthMm = downMax - downMin;
    if (insertions.size() >= 2) {
      const auto [lo, hi] = std::minmax_element(insertions.begin(), insertions.end());
      row.branchedZoneMm = *hi - *lo;
      row.lateralDensityPerMm = row.branchedZoneMm > 0 ? row.primaryLaterals / row.branchedZoneMm : kNaN;
    } else {
      row.branchedZoneMm = kNaN;
      row.lateralDensityPerMm = kNaN;
    }
    row.lateralsPerPrimaryMm = row.primaryLengthMm > 0 ? row.primaryLaterals / row.primaryLengthMm : kNaN;
    rows.push_back(row);
  }
  return rows;
}

// ---- time ----

Eigen::Matrix3Xd rootAtObservation(const TracedRoot& r, double k) {
  const auto n = static_cast<Eigen::Index>(r.timeIndex.size());
  if (n != r.plateMm.cols() || n == 0 || r.timeIndex.front() > k) return Eigen::Matrix3Xd(3, 0);
  Eigen::Index last = 0;  // the last point reached by k
  while (last + 1 < n && r.timeIndex[static_cast<std::size_t>(last + 1)] <= k) ++last;
  Eigen::Matrix3Xd p(3, last + 1 + (last + 1 < n ? 1 : 0));
  p.leftCols(last + 1) = r.plateMm.leftCols(last + 1);
  if (last + 1 < n) {
    // between two points: where the tip was at k, linearly in coord_t
    const double t0 = r.timeIndex[static_cast<std::size_t>(last)], t1 = r.timeIndex[static_cast<std::size_t>(last + 1)];
    const double f = t1 > t0 ? (k - t0) / (t1 - t0) : 0.0;
    p.col(last + 1) = r.plateMm.col(last) + f * (r.plateMm.col(last + 1) - r.plateMm.col(last));
    if (f <= 0) p.conservativeResize(3, last + 1);
  }
  return p;
}

std::vector<double> pointTimesH(const TraceFile& tf, const TracedRoot& r) {
  std::vector<double> h;
  const std::vector<double>& obs = tf.observationTimesH;
  if (obs.empty() || r.timeIndex.size() != static_cast<std::size_t>(r.plateMm.cols())) return h;
  for (double k : r.timeIndex) {
    const auto lo = static_cast<std::size_t>(std::clamp(std::floor(k), 0.0, static_cast<double>(obs.size() - 1)));
    const std::size_t hi = std::min(lo + 1, obs.size() - 1);
    h.push_back(obs[lo] + (k - static_cast<double>(lo)) * (obs[hi] - obs[lo]));
  }
  return h;
}

Eigen::Matrix3Xd polylineAtTime(const Eigen::Matrix3Xd& p, const std::vector<double>& timesH, double tH) {
  TracedRoot r;
  r.plateMm = p;
  r.timeIndex = timesH;  // any non-decreasing clock: the same interpolation as an observation index
  return rootAtObservation(r, tH);
}

double tipAngleSpanMm(double pixelMm) { return std::max(kTipSpanMm, kTipSpanPixels * pixelMm); }

double tipAngleDeg(const Eigen::Matrix3Xd& p, double pixelMm) {
  const double len = polylineLength(p);
  if (!(len > 0)) return kNaN;
  const double span = std::min(tipAngleSpanMm(pixelMm), 0.5 * len);
  // the point `span` back from the tip along the polyline
  double back = 0;
  Eigen::Vector2d from = p.col(0).head<2>();
  for (Eigen::Index k = p.cols() - 1; k > 0; --k) {
    const Eigen::Vector2d a = p.col(k).head<2>(), b = p.col(k - 1).head<2>();
    const double seg = (b - a).norm();
    if (back + seg >= span) {
      from = a + (b - a) * ((span - back) / seg);
      break;
    }
    back += seg;
  }
  const Eigen::Vector2d d = p.col(p.cols() - 1).head<2>() - from;
  return std::atan2(d(0), d(1)) * 180.0 / std::numbers::pi;
}

double matchSigmaMm(const TraceFile& tf) { return tf.pixelMm > 0 ? tf.pixelMm : kDefaultSigmaMm; }

std::vector<int> matchRoots(const TraceFile& earlier, const TraceFile& later) {
  const double sigma = std::max(matchSigmaMm(earlier), matchSigmaMm(later));
  const double tolRms = kMatchSigmas * std::sqrt(2.0) * sigma;  // two tracings' noise
  const double tolMax = 2.0 * tolRms;
  std::vector<int> match(later.roots.size(), -1);
  std::vector<bool> taken(earlier.roots.size(), false);
  int maxOrder = 0;
  for (const TracedRoot& r : later.roots) maxOrder = std::max(maxOrder, r.order);
  for (int order = 0; order <= maxOrder; ++order) {
    struct Pair {
      double cost;
      std::size_t b, a;
    };
    std::vector<Pair> pairs;
    for (std::size_t b = 0; b < later.roots.size(); ++b) {
      const TracedRoot& rb = later.roots[b];
      if (rb.order != order) continue;
      const Eigen::Matrix3Xd pb = rb.plateMm.colwise() + rb.originMm;
      const double lenB = polylineLength(pb);
      for (std::size_t a = 0; a < earlier.roots.size(); ++a) {
        const TracedRoot& ra = earlier.roots[a];
        if (ra.order != order || taken[a]) continue;
        // laterals: on the parent matched
        if (order > 0 && (rb.parentIndex < 0 || ra.parentIndex < 0 ||
                          match[static_cast<std::size_t>(rb.parentIndex)] != ra.parentIndex))
          continue;
        const Eigen::Matrix3Xd pa = ra.plateMm.colwise() + ra.originMm;
        if (polylineLength(pa) > lenB + tolMax) continue;  // a root does not shrink
        const Nearest base = nearestOn(pb, pa.col(0).head<2>());
        if (base.arc > tolMax || std::sqrt(base.d2) > tolMax) continue;  // along the later one's base
        double sum = 0, worst = 0;
        for (Eigen::Index k = 0; k < pa.cols(); ++k) {
          const double d2 = nearestOn(pb, pa.col(k).head<2>()).d2;
          sum += d2;
          worst = std::max(worst, d2);
        }
        const double rms = std::sqrt(sum / static_cast<double>(pa.cols()));
        if (rms <= tolRms && std::sqrt(worst) <= tolMax) pairs.push_back(Pair{rms, b, a});
      }
    }
    // one-to-one: the closest pairs first; equal distances in document order (later, then earlier)
    std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.cost < y.cost; });
    for (const Pair& p : pairs) {
      if (match[p.b] >= 0 || taken[p.a]) continue;
      match[p.b] = static_cast<int>(p.a);
      taken[p.a] = true;
    }
  }
  return match;
}

namespace {

// a root's row of growth.csv at timeH: p its polyline then (plate coordinates [mm])
GrowthRow growthRowOf(const TraceFile& tf, const TracedRoot& r, const Eigen::Matrix3Xd& p, double timeH,
                      const std::string& track) {
  GrowthRow g;
  g.file = tf.file;
  g.plant = r.plant;
  g.root = r.name;
  g.track = track;
  g.timeH = timeH;
  g.lengthMm = polylineLength(p);
  g.tipLateralMm = p(0, p.cols() - 1);
  g.tipDownhillMm = p(1, p.cols() - 1);
  g.thetaTipDeg = tipAngleDeg(p, tf.pixelMm);
  return g;
}

// growth rows of a 2D+t file: each root at every observation it had reached
std::vector<GrowthRow> timeLapseRows(const TraceFile& tf) {
  std::vector<GrowthRow> rows;
  for (const TracedRoot& r : tf.roots)
    for (std::size_t k = 0; k < tf.observationTimesH.size(); ++k) {
      const Eigen::Matrix3Xd p = rootAtObservation(r, static_cast<double>(k));
      if (hasLength(p)) rows.push_back(growthRowOf(tf, r, p, tf.observationTimesH[k], fileName(tf.file) + ":" + r.key));
    }
  return rows;
}

}  // namespace

Analysis analyzeAll(const AnalyzeOptions& o) {
  const std::vector<double> times = traceTimes(o);
  Analysis out;
  std::vector<TraceFile> files;
  std::vector<double> fileTimes;
  std::vector<std::size_t> firstRow;  // each file's first row in out.roots
  for (std::size_t fi = 0; fi < o.files.size(); ++fi) {
    TraceFile tf = readTraceFile(o.files[fi], o);
    if (!times.empty() && !tf.observationTimesH.empty())
      throw SceneError(o.flagPrefix + "times " + o.times + ": " + tf.file +
                       " is a time-lapse (RSML 2D+t: its <observation-hours> give its times); give it without --times");
    const double timeH = !times.empty() ? times[fi] : tf.timeH;
    for (std::string& w : plausibilityWarnings(tf, o)) out.warnings.push_back(std::move(w));
    firstRow.push_back(out.roots.size());
    for (RootRow& r : fileRows(tf, timeH)) out.roots.push_back(std::move(r));
    for (PlantRow& p : plantRows(tf, timeH)) out.plants.push_back(std::move(p));
    files.push_back(std::move(tf));
    fileTimes.push_back(timeH);
  }
  // a 2D+t file: every root at every observation; the rate over the last interval it grew in
  for (std::size_t fi = 0; fi < files.size(); ++fi) {
    const TraceFile& tf = files[fi];
    if (tf.observationTimesH.empty()) continue;
    const std::vector<GrowthRow> g = timeLapseRows(tf);
    for (std::size_t i = 0; i < tf.roots.size(); ++i) {
      const std::string track = fileName(tf.file) + ":" + tf.roots[i].key;
      const GrowthRow* last = nullptr;
      const GrowthRow* before = nullptr;
      for (const GrowthRow& row : g)
        if (row.track == track) {
          before = last;
          last = &row;
        }
      if (before) out.roots[firstRow[fi] + i].growthRateMmPerH = (last->lengthMm - before->lengthMm) / (last->timeH - before->timeH);
    }
    out.growth.insert(out.growth.end(), g.begin(), g.end());
  }
  // dated files: in time order, each root matched to the root it extends in the file before
  std::vector<std::size_t> dated;
  for (std::size_t fi = 0; fi < files.size(); ++fi)
    if (files[fi].observationTimesH.empty() && std::isfinite(fileTimes[fi])) dated.push_back(fi);
  std::stable_sort(dated.begin(), dated.end(), [&](std::size_t a, std::size_t b) { return fileTimes[a] < fileTimes[b]; });
  std::map<std::pair<std::size_t, std::size_t>, std::string> tracks;  // (file, root) -> track
  std::vector<GrowthRow> series;
  for (std::size_t n = 0; n < dated.size(); ++n) {
    const std::size_t fi = dated[n];
    const TraceFile& tf = files[fi];
    std::vector<int> match(tf.roots.size(), -1);
    std::size_t prev = files.size();
    if (n > 0) {
      prev = dated[n - 1];
      if (fileTimes[prev] == fileTimes[fi])
        throw SceneError(tf.file + " and " + files[prev].file + " have the same time, " + numberText(fileTimes[fi]) +
                         " h: give each file of a series its own time (" + o.flagPrefix + "times)");
      match = matchRoots(files[prev], tf);
    }
    for (std::size_t i = 0; i < tf.roots.size(); ++i) {
      const TracedRoot& r = tf.roots[i];
      std::string track = fileName(tf.file) + ":" + r.key;
      if (match[i] >= 0) {
        const auto j = static_cast<std::size_t>(match[i]);
        track = tracks[{prev, j}];
        RootRow& row = out.roots[firstRow[fi] + i];
        row.growthRateMmPerH = (row.lengthMm - out.roots[firstRow[prev] + j].lengthMm) / (fileTimes[fi] - fileTimes[prev]);
      }
      tracks[{fi, i}] = track;
      series.push_back(growthRowOf(tf, r, r.plateMm, fileTimes[fi], track));
    }
  }
  out.growth.insert(out.growth.end(), series.begin(), series.end());
  return out;
}

std::vector<RowField> plantFields(const PlantRow& r) {
  auto t = [](const char* name, const std::string& v) { return RowField{name, "", true, v, kNaN}; };
  auto n = [](const char* name, const char* unit, double v) { return RowField{name, unit, false, std::string(), v}; };
  return {t("file", r.file),
          n("time_h", "h", r.timeH),
          t("plant", r.plant),
          t("plant_label", r.plantLabel),
          t("root", r.root),
          n("roots", "", r.roots),
          n("primary_length_mm", "mm", r.primaryLengthMm),
          n("total_length_mm", "mm", r.totalLengthMm),
          n("lateral_length_mm", "mm", r.lateralLengthMm),
          n("lateral_count", "", r.lateralCount),
          n("primary_laterals", "", r.primaryLaterals),
          n("branched_zone_mm", "mm", r.branchedZoneMm),
          n("lateral_density_per_mm", "1/mm", r.lateralDensityPerMm),
          n("laterals_per_primary_mm", "1/mm", r.lateralsPerPrimaryMm),
          n("depth_mm", "mm", r.depthMm),
          n("width_mm", "mm", r.widthMm)};
}

std::vector<RowField> growthFields(const GrowthRow& r) {
  auto t = [](const char* name, const std::string& v) { return RowField{name, "", true, v, kNaN}; };
  auto n = [](const char* name, const char* unit, double v) { return RowField{name, unit, false, std::string(), v}; };
  return {t("file", r.file),
          t("plant", r.plant),
          t("root", r.root),
          n("time_h", "h", r.timeH),
          n("length_mm", "mm", r.lengthMm),
          n("tip_lateral_mm", "mm", r.tipLateralMm),
          n("tip_downhill_mm", "mm", r.tipDownhillMm),
          n("theta_tip_deg", "deg", r.thetaTipDeg),
          t("track", r.track)};
}

}  // namespace rootsim::app
