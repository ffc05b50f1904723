// `rootsim analyze FILE.rsml...`: every root of every plant of every file put into plate coordinates
// (docs/experiments.md, "Traced roots"), measured by traits.hpp (the runs' own analysis), written as
// analysis.csv and analysis.json into a rootsim analysis folder (the write rule: written whole, replaced
// only with --force).
#include "rootsim/analyze_traces.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/json.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/rsml.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/trace_growth.hpp"
#include "rootsim/traits.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

constexpr double kRunElementMm = 0.05;   // a run's element length (root.element_length_mm's default) [mm]
constexpr double kDefaultRadiusMm = 0.1; // an Arabidopsis root's radius (root.radius_mm's default) [mm]
constexpr double kInsertionSpanMm = 0.5; // the lateral's and the parent's directions are taken over this [mm]

// a pixel file's resolution: from a pixel 10 cm wide to one of 10 nm (beyond, a wrong unit)
constexpr NumberRange kPxPerMm{0.01, 1e5, false, false, "px/mm"};

double parseNumber(const std::string& text, const std::string& flag) {
  double v = 0;
  const char* b = text.data();
  const char* e = b + text.size();
  const auto r = std::from_chars(b, e, v);
  if (text.empty() || r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
    throw SceneError(flag + ": expected a number, found \"" + text + "\"");
  return v;
}

// downhill and lateral as directions in the file's (x, y) plane: downhill at angle phi from +y towards +x,
// lateral turned so that (lateral, downhill) keep the handedness of (x, y) (docs/experiments.md)
struct Axes {
  double dx = 0, dy = 1;   // downhill
  double lx = 1, ly = 0;   // lateral
};
Axes parseDownhill(const std::string& s, const std::string& flag = "--downhill") {
  double phiDeg = 0;
  if (s == "+y" || s == "y") phiDeg = 0;
  else if (s == "-y") phiDeg = 180;
  else {
    phiDeg = parseNumber(s, flag + " " + s + " (+y, -y or an angle in degrees)");
    if (std::abs(phiDeg) > 360) throw SceneError(flag + " " + s + ": the angle must be within [-360, 360] deg");
  }
  const double p = phiDeg * units::deg;
  Axes a;
  a.dx = std::sin(p);
  a.dy = std::cos(p);
  a.lx = std::cos(p);
  a.ly = -std::sin(p);
  // exact at multiples of 90 degrees
  for (double* v : {&a.dx, &a.dy, &a.lx, &a.ly})
    if (std::abs(*v) < 1e-15) *v = 0.0;
  return a;
}

// a scene key the file states as a property (a hint: a rootsim export's scene, or a tracer's note),
// checked like the key in a scene; NaN when absent. `override` is the flag that replaces it.
double sceneNumber(const rsml::Document& d, const std::string& file, const char* key, const std::string& override) {
  const rsml::Property* p = d.sceneProperty(key);
  if (!p) return kNaN;
  if (const std::string why = sceneNumberProblem(key, p->number); !why.empty())
    throw SceneError(file + ": property " + key + " = " + printable(p->text) + ": the scene key " + why +
                     (override.empty() ? std::string() : "; give " + override + " to set it instead"));
  return p->number;
}

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !(x > 0) || !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// the analysis thresholds: the file's analysis.* keys (a run's), else the model's defaults
AnalysisParams analysisOf(const rsml::Document& d, const std::string& file) {
  AnalysisParams a;
  auto take = [&](const char* key, double& field) {
    const double v = sceneNumber(d, file, key, "");
    if (std::isfinite(v)) field = v;
  };
  take("analysis.skew_threshold_deg", a.skewThresholdDeg);
  take("analysis.coil_turn_deg", a.coilTurnDeg);
  take("analysis.wave_min_amplitude_r", a.waveMinAmplitude);
  take("analysis.skew_min_waves", a.skewMinWaves);
  return a;
}

std::vector<double> parseTimes(const std::string& text, std::size_t files) {
  std::vector<double> t;
  if (text.empty()) return t;
  for (const std::string& cell : splitCommas(text)) {
    const double v = parseNumber(cell, "--times " + text);
    if (v < 0) throw SceneError("--times " + text + ": times must be >= 0 h");
    t.push_back(v);
  }
  if (t.size() != files)
    throw SceneError("--times " + text + ": " + std::to_string(t.size()) + " time(s) for " + std::to_string(files) +
                     " file(s); give one per file");
  return t;
}

// a root's identity across files of one plate: plant and root ids (their positions when a file has none)
std::string rootKey(const rsml::Plant& p, std::size_t pi, const rsml::Root& r, std::size_t ri) {
  return (p.id.empty() ? "#" + std::to_string(pi) : p.id) + "/" + (r.id.empty() ? "#" + std::to_string(ri) : r.id);
}

}  // namespace

void checkTraceFlags(const AnalyzeOptions& o) {
  if (flagGiven(o.pxPerMm)) checkedNumber(o.flagPrefix + "px-per-mm", o.pxPerMm, kPxPerMm);
  if (flagGiven(o.dsMm)) checkedNumber("--ds-mm", o.dsMm, {0, 10, false, false, "mm (0: the trace's own points)"});
  if (flagGiven(o.excludeTipMm)) checkedNumber("--exclude-tip-mm", o.excludeTipMm, {0, 1000, false, false, "mm"});
  if (flagGiven(o.radiusMm)) checkedNumber("--radius-mm", o.radiusMm, {0, 100, true, false, "mm"});
  parseDownhill(o.downhill, o.flagPrefix + "downhill");
}

TraceFile readTraceFile(const std::string& file, const AnalyzeOptions& o) {
  const Axes ax = parseDownhill(o.downhill, o.flagPrefix + "downhill");
  if (!fs::is_regular_file(file)) throw SceneError(file + ": RSML file not found");
  const rsml::Document doc = rsml::readRsml(file);
  TraceFile tf;
  tf.file = file;
  // units: the reader gives millimetres, or pixels for a pixel file
  double scale = 1.0;  // file units as read -> mm
  if (rsml::isPixelUnit(doc.meta.unit)) {
    if (!flagGiven(o.pxPerMm))
      throw SceneError(file + ":" + std::to_string(std::max(doc.meta.unitLine, 1)) + ": its unit is " + doc.meta.unit +
                       " with no physical scale (no resolution or size in the file); give " + o.flagPrefix + "px-per-mm R");
    scale = 1.0 / o.pxPerMm;
    tf.pixelMm = scale;
  } else if (flagGiven(o.pxPerMm)) {
    throw SceneError(o.flagPrefix + "px-per-mm " + numberText(o.pxPerMm) + ": " + file + " is in " + doc.meta.unit +
                     ", not pixels (its scale is known)");
  } else {
    tf.pixelMm = doc.pixelMm;  // the pixel size the file gives (a resolution, RootSystemTracker's <size>), or 0
  }
  tf.scaleSource = rsml::isPixelUnit(doc.meta.unit) ? o.flagPrefix + "px-per-mm " + numberText(o.pxPerMm)
                   : !rsml::pixelSizeUnit(doc.meta.unit).empty()
                       ? "<unit>" + doc.meta.unit + "</unit> and <size>" + numberText(doc.meta.size) + "</size> in the file"
                       : "<unit>" + doc.meta.unit + "</unit> and <resolution>" + numberText(doc.meta.resolution) + "</resolution> in the file";
  std::size_t roots = 0;
  for (const rsml::Plant& p : doc.plants) roots += p.roots.size();
  if (roots == 0) throw SceneError(file + ":1: no root in the file (no <plant> with a <root>)");
  tf.ours = doc.meta.software == "rootsim";
  tf.dsMm = flagGiven(o.dsMm) ? o.dsMm : (tf.ours ? 0.0 : kRunElementMm);
  const double zone = flagGiven(o.excludeTipMm) ? kNaN : sceneNumber(doc, file, "growth.growth_zone_mm", "--exclude-tip-mm");
  tf.excludeTipMm = flagGiven(o.excludeTipMm) ? o.excludeTipMm : (std::isfinite(zone) ? zone : 0.0);
  tf.set = analysisOf(doc, file);
  tf.timeH = doc.hasTime ? doc.timeH : kNaN;
  const double fileRadius = flagGiven(o.radiusMm) ? kNaN : sceneNumber(doc, file, "root.radius_mm", "--radius-mm");
  if (doc.timeLapse()) {
    // a 2D+t file shows its roots at every observation; as one file, at the last
    tf.observationTimesH = doc.observationTimesH;
    tf.timeH = doc.observationTimesH.back();
  }
  for (std::size_t pi = 0; pi < doc.plants.size(); ++pi) {
    const rsml::Plant& plant = doc.plants[pi];
    // every root of the plant in plate coordinates [mm], with the origin at the plant's first root's base
    double ox = 0, oy = 0;
    if (!plant.roots.empty()) {
      ox = plant.roots.front().x.front();
      oy = plant.roots.front().y.front();
    }
    const std::size_t first = tf.roots.size();
    for (std::size_t ri = 0; ri < plant.roots.size(); ++ri) {
      const rsml::Root& r = plant.roots[ri];
      TracedRoot t;
      t.plant = plant.id;
      t.plantLabel = plant.label;
      t.root = r.id;
      t.rootLabel = r.label;
      t.order = r.order;
      t.line = r.line;
      t.key = rootKey(plant, pi, r, ri);
      t.name = r.id.empty() ? "#" + std::to_string(ri) : r.id;
      if (r.parent >= 0) {
        const rsml::Root& par = plant.roots[static_cast<std::size_t>(r.parent)];
        t.parent = par.id.empty() ? "#" + std::to_string(r.parent) : par.id;
        t.parentIndex = static_cast<int>(first) + r.parent;
      }
      Eigen::Matrix3Xd c(3, static_cast<Eigen::Index>(r.points()));
      for (std::size_t k = 0; k < r.points(); ++k) {
        const double x = (r.x[k] - ox) * scale, y = (r.y[k] - oy) * scale;
        c(0, static_cast<Eigen::Index>(k)) = ax.lx * x + ax.ly * y;
        c(1, static_cast<Eigen::Index>(k)) = ax.dx * x + ax.dy * y;
        c(2, static_cast<Eigen::Index>(k)) = r.hasZ ? r.z[k] * scale : 0.0;
      }
      // the reader's bound on a coordinate, applied again after a pixel file's --px-per-mm scale
      if (scale != 1.0)
        for (Eigen::Index k = 0; k < c.cols(); ++k)
          if (!(c.col(k).cwiseAbs().maxCoeff() <= rsml::kMaxCoordMm))
            throw SceneError(o.flagPrefix + "px-per-mm " + numberText(o.pxPerMm) + ": puts point " + std::to_string(k + 1) + " of root " +
                             t.name + " (" + file + ":" + std::to_string(r.line) + ") " + numberText(c.col(k).cwiseAbs().maxCoeff()) +
                             " mm from the first, beyond " + decimalNumber(rsml::kMaxCoordMm) + " mm (1 km): a wrong resolution?");
      // the points its shape analysis and its distances will resample it into, before they are made
      double length = 0;
      for (Eigen::Index k = 1; k < c.cols(); ++k) length += (c.col(k) - c.col(k - 1)).norm();
      const double step = tf.dsMm > 0 ? std::min(tf.dsMm, kDistanceStepMm) : kDistanceStepMm;
      const bool byFlag = flagGiven(o.dsMm) && o.dsMm > 0 && o.dsMm < kDistanceStepMm;
      checkCount((byFlag ? "--ds-mm " + numberText(o.dsMm) + ": " : std::string()) + file + ":" + std::to_string(r.line) + ": root " +
                     t.name + " (" + numberText(length) + " mm long, resampled every " + numberText(step) + " mm)",
                 length / step, caps::kTracePoints, "points",
                 "caps::kTracePoints: about 100 bytes a point in the shape analysis; docs/outputs.md, Caps");
      t.plateMm = std::move(c);
      t.originMm = Eigen::Vector3d(ax.lx * ox * scale + ax.ly * oy * scale, ax.dx * ox * scale + ax.dy * oy * scale, 0.0);
      t.timeIndex = r.timeIndex;
      // the radius of the peaks' hysteresis
      if (flagGiven(o.radiusMm)) {
        t.radiusMm = o.radiusMm;
        t.radiusSource = "--radius-mm";
      } else if (std::isfinite(fileRadius) && r.order == 0) {
        t.radiusMm = fileRadius;
        t.radiusSource = "root.radius_mm";
      } else if (std::isfinite(median(r.diameterMm))) {
        t.radiusMm = 0.5 * median(r.diameterMm) * scale;
        t.radiusSource = "diameter";
      } else {
        t.radiusMm = kDefaultRadiusMm;
        t.radiusSource = "default";
      }
      tf.roots.push_back(std::move(t));
    }
  }
  return tf;
}

RootTraits tracedTraits(const TraceFile& tf, const TracedRoot& t, double dsMm, double excludeTipMm) {
  try {
    return tf.ours ? rootTraits(t.plateMm, dsMm, excludeTipMm, t.radiusMm, tf.set)
                   : traceTraits(t.plateMm, dsMm, excludeTipMm, t.radiusMm, tf.set);
  } catch (const std::invalid_argument&) {
    throw SceneError(tf.file + ":" + std::to_string(t.line) + ": root " + t.name + " has fewer than two distinct points");
  }
}

const TracedRoot& pickRoot(const TraceFile& tf, const std::string& id, const std::string& flag) {
  if (!id.empty()) {
    std::vector<const TracedRoot*> hits;
    for (const TracedRoot& r : tf.roots)
      if (r.root == id || r.name == id || r.key == id) hits.push_back(&r);
    if (hits.size() == 1) return *hits.front();
    std::string ids;
    for (const TracedRoot& r : tf.roots) ids += (ids.empty() ? "" : ", ") + r.key;
    throw SceneError(flag + " " + id + ": " + (hits.empty() ? "no such root" : "several roots have this id; give plant/root") +
                     " in " + tf.file + " (roots: " + ids + ")");
  }
  std::vector<const TracedRoot*> primary;
  for (const TracedRoot& r : tf.roots)
    if (r.order == 0) primary.push_back(&r);
  if (primary.size() == 1) return *primary.front();
  if (primary.empty()) return tf.roots.front();
  std::string ids;
  for (const TracedRoot* r : primary) ids += (ids.empty() ? "" : ", ") + r->key;
  throw SceneError(tf.file + ": " + std::to_string(primary.size()) + " primary roots (" + ids + "); choose one with " + flag + " ID");
}

namespace {

// the row's noise-aware cells and the field's traits: lambda and A are empty, with the reason, where the
// shape analysis found too few peaks to measure them (docs/experiments.md, "Noise")
void fillNoiseTraits(RootRow& row, const RootTraits& t) {
  row.noiseMm = t.noiseMm;
  row.smoothingMm = t.smoothingMm;
  row.peakThresholdMm = t.shape.hysteresis / units::mm;
  row.wavesNote = t.wavesNote;
  if (t.shape.peaks < 3) row.wavelengthMm = kNaN;
  if (t.shape.peaks < 2) row.amplitudeMm = row.amplitudeHalfMm = kNaN;
  row.straightness = t.straightness;
  row.hgi = t.hgi;
  row.vgi = t.vgi;
  row.thetaTipDeg = t.thetaTipDeg;
  row.bowMm = t.bowMm;
  row.bendDeg = t.bendDeg;
  row.curveMm = t.curveMm;
  row.peakNodes = t.shape.peakNodes;
  row.matureLast = t.matureLast;
}

}  // namespace

std::vector<double> traceTimes(const AnalyzeOptions& o) {
  if (o.files.empty()) throw SceneError("analyze: give at least one RSML file");
  checkTraceFlags(o);
  return parseTimes(o.times, o.files.size());
}

std::vector<RootRow> fileRows(const TraceFile& tf, double timeH) {
  std::vector<RootRow> rows;
  {
    for (const TracedRoot& r : tf.roots) {
      RootRow row;
      row.file = tf.file;
      row.timeH = timeH;
      row.plant = r.plant;
      row.plantLabel = r.plantLabel;
      row.root = r.root;
      row.rootLabel = r.rootLabel;
      row.parent = r.parent;
      row.order = r.order;
      row.points = static_cast<int>(r.plateMm.cols());
      row.radiusSource = r.radiusSource;
      const RootTraits t = tracedTraits(tf, r, tf.dsMm, tf.excludeTipMm);
      row.lengthMm = t.lengthMm;
      row.chordMm = t.chordMm;
      row.tortuosity = t.tortuosity;
      row.skewDeg = t.skewDeg;
      row.insertionDeg = r.parentIndex >= 0
                             ? insertionAngleDeg(tf.roots[static_cast<std::size_t>(r.parentIndex)].plateMm, r.plateMm, kInsertionSpanMm)
                             : kNaN;
      row.pattern = t.shape.pattern;
      row.wavelengthMm = t.shape.wavelength / units::mm;
      row.amplitudeMm = t.shape.amplitude / units::mm;
      row.amplitudeHalfMm = t.shape.amplitudeHalf / units::mm;
      row.lateralPeaks = t.shape.peaks;
      row.waves = t.shape.waves;
      row.skewWavesDeg = t.shape.skew / units::deg;
      row.maxKappaPerMm = t.shape.maxKappa * units::mm;
      row.thetaMinDeg = t.shape.thetaMin / units::deg;
      row.thetaMaxDeg = t.shape.thetaMax / units::deg;
      row.dsMm = tf.dsMm;
      row.excludeTipMm = tf.excludeTipMm;
      row.radiusMm = r.radiusMm;
      row.growthRateMmPerH = kNaN;  // trace_growth.cpp: from the time-lapse or the matched root before
      fillNoiseTraits(row, t);
      row.traceMm = r.plateMm;
      rows.push_back(row);
    }
  }
  return rows;
}

std::vector<RootRow> analyzeTraces(const AnalyzeOptions& o) { return analyzeAll(o).roots; }

namespace {

struct Column {
  const char* name;
  const char* unit;
  std::string (*text)(const RootRow&);
  double (*number)(const RootRow&);
};

// the columns of analysis.csv and the keys of analysis.json, one table (docs/experiments.md)
const std::vector<Column>& columns() {
  static const std::vector<Column> c = {
      {"file", "", [](const RootRow& r) { return r.file; }, nullptr},
      {"time_h", "h", nullptr, [](const RootRow& r) { return r.timeH; }},
      {"plant", "", [](const RootRow& r) { return r.plant; }, nullptr},
      {"plant_label", "", [](const RootRow& r) { return r.plantLabel; }, nullptr},
      {"root", "", [](const RootRow& r) { return r.root; }, nullptr},
      {"root_label", "", [](const RootRow& r) { return r.rootLabel; }, nullptr},
      {"parent", "", [](const RootRow& r) { return r.parent; }, nullptr},
      {"order", "", nullptr, [](const RootRow& r) { return double(r.order); }},
      {"points", "", nullptr, [](const RootRow& r) { return double(r.points); }},
      {"length_mm", "mm", nullptr, [](const RootRow& r) { return r.lengthMm; }},
      {"chord_mm", "mm", nullptr, [](const RootRow& r) { return r.chordMm; }},
      {"tortuosity", "", nullptr, [](const RootRow& r) { return r.tortuosity; }},
      {"skew_base_tip_deg", "deg", nullptr, [](const RootRow& r) { return r.skewDeg; }},
      {"insertion_deg", "deg", nullptr, [](const RootRow& r) { return r.insertionDeg; }},
      {"pattern", "", [](const RootRow& r) { return r.pattern; }, nullptr},
      {"wavelength_mm", "mm", nullptr, [](const RootRow& r) { return r.wavelengthMm; }},
      {"amplitude_mm", "mm", nullptr, [](const RootRow& r) { return r.amplitudeMm; }},
      {"amplitude_half_mm", "mm", nullptr, [](const RootRow& r) { return r.amplitudeHalfMm; }},
      {"lateral_peaks", "", nullptr, [](const RootRow& r) { return double(r.lateralPeaks); }},
      {"waves", "", nullptr, [](const RootRow& r) { return r.waves; }},
      {"skew_deg", "deg", nullptr, [](const RootRow& r) { return r.skewWavesDeg; }},
      {"max_kappa_per_mm", "1/mm", nullptr, [](const RootRow& r) { return r.maxKappaPerMm; }},
      {"theta_min_deg", "deg", nullptr, [](const RootRow& r) { return r.thetaMinDeg; }},
      {"theta_max_deg", "deg", nullptr, [](const RootRow& r) { return r.thetaMaxDeg; }},
      {"waves_note", "", [](const RootRow& r) { return r.wavesNote; }, nullptr},
      {"noise_mm", "mm", nullptr, [](const RootRow& r) { return r.noiseMm; }},
      {"smoothing_mm", "mm", nullptr, [](const RootRow& r) { return r.smoothingMm; }},
      {"peak_threshold_mm", "mm", nullptr, [](const RootRow& r) { return r.peakThresholdMm; }},
      {"theta_tip_deg", "deg", nullptr, [](const RootRow& r) { return r.thetaTipDeg; }},
      {"straightness", "", nullptr, [](const RootRow& r) { return r.straightness; }},
      {"hgi", "", nullptr, [](const RootRow& r) { return r.hgi; }},
      {"vgi", "", nullptr, [](const RootRow& r) { return r.vgi; }},
      {"bow_mm", "mm", nullptr, [](const RootRow& r) { return r.bowMm; }},
      {"bend_deg", "deg", nullptr, [](const RootRow& r) { return r.bendDeg; }},
      {"growth_rate_mm_per_h", "mm/h", nullptr, [](const RootRow& r) { return r.growthRateMmPerH; }},
      {"ds_mm", "mm", nullptr, [](const RootRow& r) { return r.dsMm; }},
      {"exclude_tip_mm", "mm", nullptr, [](const RootRow& r) { return r.excludeTipMm; }},
      {"radius_mm", "mm", nullptr, [](const RootRow& r) { return r.radiusMm; }},
      {"radius_source", "", [](const RootRow& r) { return r.radiusSource; }, nullptr},
  };
  return c;
}

}  // namespace

std::vector<RowField> rowFields(const RootRow& r) {
  std::vector<RowField> f;
  for (const Column& c : columns())
    f.push_back(RowField{c.name, c.unit, c.text != nullptr, c.text ? c.text(r) : std::string(), c.text ? kNaN : c.number(r)});
  return f;
}

namespace {

std::string analysisCsv(const std::vector<RootRow>& rows) {
  std::string out;
  for (const Column& c : columns()) out += std::string(out.empty() ? "" : ",") + c.name;
  out += "\n";
  for (const RootRow& r : rows) {
    bool first = true;
    for (const Column& c : columns()) {
      if (!first) out += ",";
      first = false;
      if (c.text) out += csvField(c.text(r));
      else if (std::isfinite(c.number(r))) out += numberText(c.number(r));
      // NaN and infinities: an empty cell
    }
    out += "\n";
  }
  return out;
}

// curves.csv: each root's points as the file gives them (kind "trace") and the curve it was measured on
// (kind "measured": smoothed for a trace), with the measured curve's mature part and counted peaks
std::string curvesCsv(const std::vector<RootRow>& rows) {
  std::string out = "file,plant,root,kind,point,lateral_mm,downhill_mm,mature,peak\n";
  for (const RootRow& r : rows) {
    const std::string head = csvField(r.file) + "," + csvField(r.plant) + "," + csvField(r.root) + ",";
    for (int i = 0; i < r.traceMm.cols(); ++i)
      out += head + "trace," + std::to_string(i) + "," + numberText(r.traceMm(0, i)) + "," + numberText(r.traceMm(1, i)) + ",,\n";
    std::size_t next = 0;
    for (int i = 0; i < r.curveMm.cols(); ++i) {
      const bool peak = next < r.peakNodes.size() && r.peakNodes[next] == i;
      if (peak) ++next;
      out += head + "measured," + std::to_string(i) + "," + numberText(r.curveMm(0, i)) + "," + numberText(r.curveMm(1, i)) + "," +
             (i <= r.matureLast ? "1" : "0") + "," + (peak ? "1" : "0") + "\n";
    }
  }
  return out;
}

std::string analysisJson(const std::vector<RootRow>& rows) {
  std::vector<Json> items;
  for (const RootRow& r : rows) {
    Json j;
    for (const Column& c : columns()) {
      if (c.text) j.str(c.name, c.text(r));
      else j.num(c.name, c.number(r));
    }
    items.push_back(j);
  }
  Json units;
  for (const Column& c : columns())
    if (*c.unit) units.str(c.name, c.unit);
  Json top;
  top.str("software", outputSignatureText()).object("units", units).array("roots", items);
  return top.dump() + "\n";
}

// a table of fields as CSV (the header from `header`: a row's names), numbers as numberText, NaN empty
std::string fieldsCsv(const std::vector<RowField>& header, const std::vector<std::vector<RowField>>& rows) {
  std::string out;
  for (const RowField& f : header) out += std::string(out.empty() ? "" : ",") + f.name;
  out += "\n";
  for (const std::vector<RowField>& row : rows) {
    bool first = true;
    for (const RowField& f : row) {
      if (!first) out += ",";
      first = false;
      if (f.isText) out += csvField(f.text);
      else if (std::isfinite(f.number)) out += numberText(f.number);
    }
    out += "\n";
  }
  return out;
}

std::string fieldsJson(const std::string& key, const std::vector<RowField>& header, const std::vector<std::vector<RowField>>& rows) {
  std::vector<Json> items;
  for (const std::vector<RowField>& row : rows) {
    Json j;
    for (const RowField& f : row) {
      if (f.isText) j.str(f.name, f.text);
      else j.num(f.name, f.number);
    }
    items.push_back(j);
  }
  Json units;
  for (const RowField& f : header)
    if (*f.unit) units.str(f.name, f.unit);
  Json top;
  top.str("software", outputSignatureText()).object("units", units).array(key, items);
  return top.dump() + "\n";
}

// plants.csv/.json and growth.csv/.json (trace_growth.hpp): written for every analysis, a header alone
// when there is no plant or no time
void writeSeriesFiles(const fs::path& dir, const Analysis& a) {
  std::vector<std::vector<RowField>> plants, growth;
  for (const PlantRow& p : a.plants) plants.push_back(plantFields(p));
  for (const GrowthRow& g : a.growth) growth.push_back(growthFields(g));
  const std::vector<RowField> plantHeader = plantFields(PlantRow{}), growthHeader = growthFields(GrowthRow{});
  writeFileAtomic(dir / "plants.csv", fieldsCsv(plantHeader, plants));
  writeFileAtomic(dir / "plants.json", fieldsJson("plants", plantHeader, plants));
  writeFileAtomic(dir / "growth.csv", fieldsCsv(growthHeader, growth));
  writeFileAtomic(dir / "growth.json", fieldsJson("growth", growthHeader, growth));
}

std::string summaryLine(const RootRow& r) {
  char b[640];
  auto f = [](double v) { return std::isfinite(v) ? v : 0.0; };
  char waves[256];
  if (std::isfinite(r.wavelengthMm))
    std::snprintf(waves, sizeof waves, "lambda %.3g mm, A %.3g mm", r.wavelengthMm, r.amplitudeMm);
  else if (std::isfinite(r.amplitudeMm))
    std::snprintf(waves, sizeof waves, "A %.3g mm (%s)", r.amplitudeMm, r.wavesNote.c_str());
  else
    std::snprintf(waves, sizeof waves, "lambda, A: %s", r.wavesNote.c_str());
  char noise[48] = "noise unknown (fewer than 9 points)";
  if (std::isfinite(r.noiseMm)) std::snprintf(noise, sizeof noise, "noise %.2g mm", r.noiseMm);
  std::snprintf(b, sizeof b, "%s %s/%s%s: %s, length %.3g mm, skew %.3g deg (base-tip), tortuosity %.4g, %s, %d peaks, %s",
                fs::path(r.file).filename().c_str(), r.plant.empty() ? "-" : r.plant.c_str(),
                r.root.empty() ? "-" : r.root.c_str(), r.order > 0 ? (" (order " + std::to_string(r.order) + ")").c_str() : "",
                r.pattern.c_str(), r.lengthMm, r.skewDeg, f(r.tortuosity), waves, r.lateralPeaks, noise);
  return b;
}

}  // namespace

int analyzeCommand(const AnalyzeOptions& o, Analysis* result) {
  // the output folder's name is checked before anything is read
  const std::string outText =
      o.out.empty() ? (fs::path("analysis") / fs::path(o.files.empty() ? std::string("analysis") : o.files.front()).stem()).string() : o.out;
  const fs::path out = checkOutputName(outText, "--out");
  // locked before any work (the StagedFolder below takes it again)
  const OutputLock lock = lockOutput(out, "--out");
  WriteRule rule;
  rule.force = o.force;
  for (const std::string& f : o.files) rule.inputs.push_back(WriteInput{f, {}, true});
  rule.inputs.push_back(workingFolder());
  claimFolder(out, analysisFolder(), rule, "--out", true);
  const Analysis all = analyzeAll(o);
  const std::vector<RootRow>& rows = all.roots;
  for (const std::string& w : all.warnings) std::fprintf(stderr, "rootsim: warning: %s\n", w.c_str());
  StagedFolder folder(out, analysisFolder(), rule, "--out");
  writeFileAtomic(folder.work() / "analysis.csv", analysisCsv(rows));
  writeFileAtomic(folder.work() / "curves.csv", curvesCsv(rows));
  writeFileAtomic(folder.work() / "analysis.json", analysisJson(rows));
  writeSeriesFiles(folder.work(), all);
  folder.commit();
  if (o.printLines)
    for (const RootRow& r : rows) std::printf("%s\n", summaryLine(r).c_str());
  if (!o.quiet)
    std::fprintf(stderr, "wrote %s (analysis.csv, analysis.json, curves.csv: %zu roots; plants.csv: %zu plants; growth.csv: %zu rows)\n",
                 out.c_str(), rows.size(), all.plants.size(), all.growth.size());
  if (result != nullptr) *result = all;
  return 0;
}

}  // namespace rootsim::app
