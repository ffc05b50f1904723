// `rootsim export RUN_DIR`: flags and the run directory checked (SceneError, exit 2), the outputs claimed
// by the write rule, then written, each atomically. docs/rsml.md describes the RSML mapping, docs/gltf.md
// the glTF one.
#include "rootsim/export_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <utility>
#include <vector>

#include "rootsim/checkpoint.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/gltf.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/paraview.hpp"
#include "rootsim/results.hpp"
#include "rootsim/rsml.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "rootsim/write_rule.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

// what export reads of a run directory
struct RunData {
  Scene scene;
  std::vector<Snapshot> snaps;
  std::vector<double> timeH, lengthMm;   // timeseries.csv: growth time [h], rest length L(t) [mm]
  std::optional<RunResult> result;       // result.csv, when the run has one
  std::uint64_t hash = 0;                // FNV-1a of the resolved scene
  std::string name;                      // the run directory's name (the plant's label)
};

RunData readRun(const fs::path& runDir) {
  RunData d;
  const fs::path sceneFile = runDir / "scene.toml";
  if (!fs::is_regular_file(sceneFile)) throw SceneError(sceneFile.string() + ": not found (not a run directory?)");
  d.scene = loadScene(sceneFile.string());
  d.hash = sceneHash(d.scene.resolvedToml);
  d.name = fs::absolute(runDir).lexically_normal().filename().string();
  if (d.name.empty()) d.name = fs::absolute(runDir).lexically_normal().parent_path().filename().string();
  d.snaps = loadSnapshots(runDir);
  const fs::path ts = runDir / "timeseries.csv";
  if (!fs::is_regular_file(ts)) throw SceneError(ts.string() + ": not found (not a run directory?)");
  const CsvColumns cols = readCsvColumns(ts);
  for (std::size_t c = 0; c < cols.names.size(); ++c) {
    if (cols.names[c] == "time_h") d.timeH = cols.values[c];
    if (cols.names[c] == "length_mm") d.lengthMm = cols.values[c];
  }
  if (d.timeH.empty() || d.timeH.size() != d.lengthMm.size())
    throw SceneError(ts.string() + ": no time_h and length_mm rows (not a run's time series?)");
  const fs::path res = runDir / "result.csv";
  if (fs::is_regular_file(res)) {
    try {
      d.result = readResult(res);
    } catch (const RunError& e) {
      throw SceneError(e.what());  // a malformed input file: bad usage, not a failed run
    }
  }
  return d;
}

// the snapshots to export: the final one, the one nearest --at-h, or one every --every-h hours from the
// first snapshot (the requested times beside them)
struct Pick {
  int index;
  double requestedH;
};
std::vector<Pick> pickSnapshots(const std::vector<Snapshot>& snaps, const ExportOptions& o) {
  const std::vector<double> t = snapshotTimes(snaps);
  if (flagGiven(o.atH)) return {Pick{snapshotNear(t, o.atH), o.atH}};
  if (!flagGiven(o.everyH)) return {Pick{static_cast<int>(snaps.size()) - 1, t.back()}};
  const double span = t.back() - t.front();
  checkCount("--every-h " + significantText(o.everyH) + ": a series over the run's " + significantText(span) + " h", span / o.everyH + 1,
             caps::kSeriesFiles, "files", "caps::kSeriesFiles: one file each; docs/outputs.md, Caps");
  std::vector<Pick> picks;
  // k H from the first snapshot while within the run (a rounding margin of 1e-9 H at the end)
  for (long k = 0; t.front() + static_cast<double>(k) * o.everyH <= t.back() + 1e-9 * o.everyH; ++k) {
    const double at = std::min(t.front() + static_cast<double>(k) * o.everyH, t.back());
    const int i = nearestSnapshot(t, at);
    if (!picks.empty() && picks.back().index == i)
      throw SceneError("--every-h " + significantText(o.everyH) + ": shorter than the run's snapshot spacing (" +
                       significantText(at) + " h and " + significantText(picks.back().requestedH) + " h are both nearest the snapshot at " +
                       significantText(t[static_cast<std::size_t>(i)]) + " h)");
    picks.push_back(Pick{i, at});
  }
  return picks;
}

// the file of one time of a series: FILE with "_t<time>h" before its extension, the time zero-padded to
// at least three integer digits and with as many decimals (at least two) as the step needs, so that the
// names sort in time: run.rsml -> run_t000.00h.rsml, run_t000.25h.rsml, ...
std::vector<fs::path> seriesNames(const fs::path& file, const std::vector<Pick>& picks, double everyH) {
  int decimals = 2;
  while (decimals < 9) {
    const double scaled = everyH * std::pow(10.0, decimals);
    if (std::fabs(scaled - std::round(scaled)) <= 1e-6 * scaled) break;
    ++decimals;
  }
  double maxH = 0;
  for (const Pick& p : picks) maxH = std::max(maxH, p.requestedH);
  int intDigits = 3;
  while (maxH >= std::pow(10.0, intDigits)) ++intDigits;
  std::vector<fs::path> out;
  for (const Pick& p : picks) {
    char b[64];
    std::snprintf(b, sizeof b, "_t%0*.*fh", intDigits + 1 + decimals, decimals, p.requestedH);
    fs::path f = file.parent_path() / (file.stem().string() + b + file.extension().string());
    if (!out.empty() && f == out.back())
      throw SceneError("--every-h " + significantText(everyH) + ": two times give the name " + f.string());
    out.push_back(std::move(f));
  }
  return out;
}

// ---- RSML (docs/rsml.md) ----

// node values of element values: the mean of the two neighbouring elements, the end elements' own at
// the two ends
std::vector<double> toNodes(const std::vector<double>& e) {
  const std::size_t n = e.size();
  std::vector<double> v(n + 1);
  v[0] = e[0];
  v[n] = e[n - 1];
  for (std::size_t i = 1; i < n; ++i) v[i] = 0.5 * (e[i - 1] + e[i]);
  return v;
}

// the unit tangent and d1 at a node: the neighbouring elements' d3 and d1 averaged (the node frame of
// shape.csv), d1 made normal to the tangent
// the angle of d1 about the tangent at each node [deg]: materialAngle (node_fields.hpp, the ParaView point
// data's material_angle_deg) of the node frames, unwrapped along the root from node 0 (whose value lies in
// (-180, 180]), so a twisted root's angle keeps counting
std::vector<double> frameAngleDeg(const Snapshot& s, const PlateFrame& pf) {
  std::vector<double> out;
  double prev = 0;
  const std::vector<NodeFrame> frames = nodeFrames(s);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    double phi = materialAngle(frames[i].t, frames[i].d1, pf) / units::deg;
    if (i > 0) phi += 360.0 * std::round((prev - phi) / 360.0);
    out.push_back(phi);
    prev = phi;
  }
  return out;
}

// the centreline's curvature [1/mm] at interior nodes: phi / ((l_a + l_b) / 2), phi the turning angle
// between the two neighbouring segments (of lengths l_a, l_b) over the Voronoi length; 0 at the two
// ends. From the points alone: what a reader of the file can recompute. (The curvature binormal's
// 2 tan(phi/2) differs by phi^3/12 and is infinite for a fold; the angle stays finite.)
std::vector<double> curvaturePerMm(const Snapshot& s) {
  const int n = s.elements();
  std::vector<double> k(static_cast<std::size_t>(n) + 1, 0.0);
  for (int i = 1; i < n; ++i) {
    const Eigen::Vector3d a = (s.x.col(i) - s.x.col(i - 1)) / units::mm, b = (s.x.col(i + 1) - s.x.col(i)) / units::mm;
    const double la = a.norm(), lb = b.norm();
    const double phi = std::atan2(a.cross(b).norm(), a.dot(b));
    k[static_cast<std::size_t>(i)] = phi / (0.5 * (la + lb));
  }
  return k;
}

// rest arc length from the base at each node [mm]: each element's length over its stretch lambda, which
// the radius gives (radius = R / sqrt(lambda))
std::vector<double> restArcMm(const Snapshot& s, double restRadius) {
  std::vector<double> S(static_cast<std::size_t>(s.elements()) + 1, 0.0);
  for (int e = 0; e < s.elements(); ++e) {
    const double r = s.radius[e] / restRadius;
    S[static_cast<std::size_t>(e) + 1] = S[static_cast<std::size_t>(e)] + (s.x.col(e + 1) - s.x.col(e)).norm() / units::mm * r * r;
  }
  return S;
}

// the age of the material at each node [h]: the time since it left the growth zone. Material at rest
// arc length S left it when the root's rest length L(t) reached S + Lgz (t from timeseries.csv's
// time_h and length_mm, linearly interpolated); still in the zone: 0; mature already at the first row:
// the time since that row (a lower bound)
std::vector<double> ageH(const std::vector<double>& S, double zoneMm, double nowH, const RunData& d) {
  std::vector<double> age;
  for (double si : S) {
    const double need = si + zoneMm;
    double left = NAN;
    if (need <= d.lengthMm.front()) {
      left = d.timeH.front();
    } else {
      for (std::size_t r = 1; r < d.lengthMm.size() && d.timeH[r] <= nowH + 1e-12; ++r)
        if (d.lengthMm[r] >= need) {
          const double l0 = d.lengthMm[r - 1], l1 = d.lengthMm[r];
          const double f = l1 > l0 ? (need - l0) / (l1 - l0) : 1.0;
          left = d.timeH[r - 1] + f * (d.timeH[r] - d.timeH[r - 1]);
          break;
        }
    }
    age.push_back(std::isnan(left) ? 0.0 : std::max(0.0, nowH - left));
  }
  return age;
}

// scene values in TOML syntax; a plain string without its quotes
std::string sceneText(const std::string& toml) {
  if (toml.size() >= 2 && toml.front() == '"' && toml.back() == '"' && toml.find('\\') == std::string::npos)
    return toml.substr(1, toml.size() - 2);
  return toml;
}

rsml::Property numberProperty(const std::string& name, double v) {
  rsml::Property p;
  p.name = name;
  p.number = v;
  return p;
}
rsml::Property textProperty(const std::string& name, const std::string& text) {
  rsml::Property p;
  p.name = name;
  p.text = text;
  p.number = NAN;
  return p;
}

// result.csv's columns that describe the root rather than the run's bookkeeping
bool exportedResultColumn(const std::string& name) {
  for (const char* skip : {"scene", "status", "steps", "time_h", "length_mm", "elements", "total_substeps"})
    if (name == skip) return false;
  return true;
}

std::string hex16(std::uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

rsml::Document rsmlOf(const RunData& d, const Snapshot& s, int sequenceIndex) {
  const Model& m = d.scene.model;
  const PlateFrame pf = m.env.plane.frame();
  rsml::Document doc;
  const std::string key = d.name + "-" + hex16(d.hash);
  doc.comment = std::string(outputSignatureText()) + ": rootsim export of run " + d.name + ", growth step " +
                std::to_string(s.step) + " at " + numberText(s.timeH) + " h (docs/rsml.md)";
  doc.meta.version = "1";
  // RSML requires a date; a run has none of its own, and the same run must give the same bytes
  doc.meta.lastModified = "1970-01-01T00:00:00";
  doc.meta.software = "rootsim";
  doc.meta.fileKey = key + "-t" + numberText(s.timeH) + "h";
  if (sequenceIndex >= 0) {
    doc.meta.sequenceLabel = key;
    doc.meta.sequenceIndex = sequenceIndex;
    doc.meta.unified = true;  // the one root keeps its id through the series
  }
  auto def = [&](const std::string& label, const std::string& type, const std::string& unit) {
    doc.meta.definitions.push_back(rsml::Definition{label, type, unit});
  };
  def("diameter", "real", "mm");
  def("frame_angle", "real", "deg");
  def("curvature", "real", "1/mm");
  def("age", "real", "h");
  def("time_h", "real", "h");
  def("step", "integer", "");
  def("length_mm", "real", "mm");
  // the snapshot, then every key of the resolved scene (named with their units)
  doc.sceneProperties.push_back(numberProperty("time_h", s.timeH));
  doc.sceneProperties.push_back(numberProperty("step", s.step));
  doc.sceneProperties.push_back(textProperty("software_version", kVersion));
  for (const SceneValue& v : sceneValues(m, d.scene.output)) {
    if (v.key.find('[') != std::string::npos) continue;  // obstacles: below, as obstacle_K.key
    doc.sceneProperties.push_back(textProperty(v.key, sceneText(v.text)));
  }
  for (const SceneValue& v : sceneValues(m, d.scene.output))
    if (const auto open = v.key.find('['); open != std::string::npos) {
      std::string name = v.key;
      name.replace(open, 1, "_");
      name.erase(name.find(']'), 1);
      doc.sceneProperties.push_back(textProperty(name, sceneText(v.text)));
    }

  rsml::Plant plant;
  plant.id = "1";
  plant.label = d.name;
  rsml::Root r;
  r.id = "1";
  r.label = "primary";
  r.hasZ = true;
  for (int i = 0; i < s.x.cols(); ++i) {
    const Eigen::Vector3d p = pf.coords(s.x.col(i)) / units::mm;
    r.x.push_back(p.x());
    r.y.push_back(p.y());
    r.z.push_back(p.z());
  }
  std::vector<double> diameter;
  for (int e = 0; e < s.elements(); ++e) diameter.push_back(2.0 * s.radius[e] / units::mm);
  const std::vector<double> S = restArcMm(s, m.rod.radius);
  r.functions.push_back(rsml::Function{"diameter", "polyline", toNodes(diameter), {}});
  r.functions.push_back(rsml::Function{"frame_angle", "polyline", frameAngleDeg(s, pf), {}});
  r.functions.push_back(rsml::Function{"curvature", "polyline", curvaturePerMm(s), {}});
  r.functions.push_back(rsml::Function{"age", "polyline", ageH(S, m.growth.zoneLength / units::mm, s.timeH, d), {}});
  r.diameterMm = r.functions[0].samples;
  r.properties.push_back(numberProperty("length_mm", S.back()));
  if (d.result) {
    for (const ResultColumn& c : resultColumns()) {
      if (!exportedResultColumn(c.name) || (c.growthOnly && !d.result->grows)) continue;
      if (c.text) {
        r.properties.push_back(textProperty(c.name, (*d.result).*c.str));
      } else {
        r.properties.push_back(numberProperty(c.name, (*d.result).*c.num));
        def(c.name, "real", c.unit);
      }
      if (c.text) def(c.name, "string", "");
    }
  }
  plant.roots.push_back(std::move(r));
  doc.plants.push_back(std::move(plant));
  return doc;
}

// a plate's RSML (docs/plate.md): one plant per seedling, its lateral roots nested in it, every root in
// plate coordinates from the plate's origin; each root as rsmlOf writes it. pick: the snapshot of the
// seedlings (a lateral root has the plate's last snapshots only; one that had not emerged is left out)
rsml::Document plateRsmlOf(const Scene& plate, const std::vector<PlateRoot>& roots, const std::vector<RunData>& data,
                           std::size_t pick, int sequenceIndex) {
  rsml::Document doc;
  std::size_t count = 0;
  for (const RunData& d : data) count = std::max(count, d.snaps.size());
  std::vector<std::pair<int, int>> where(roots.size(), {-1, -1});  // root -> (plant, index in the plant)
  for (std::size_t r = 0; r < roots.size(); ++r) {
    const PlateRoot& pr = roots[r];
    const RunData& d = data[r];
    if (pick + d.snaps.size() < count) continue;  // not emerged yet
    rsml::Document one = rsmlOf(d, d.snaps[pick + d.snaps.size() - count], sequenceIndex);
    rsml::Root root = std::move(one.plants.front().roots.front());
    root.label = pr.parent.empty() ? "primary" : "lateral";
    for (double& x : root.x) x += pr.seedling.position.x() / units::mm;
    for (double& y : root.y) y += pr.seedling.position.y() / units::mm;
    if (doc.plants.empty()) {
      doc = std::move(one);
      doc.plants.clear();
      // the plate's keys (each plant's own are its overrides)
      doc.sceneProperties.erase(doc.sceneProperties.begin() + 3, doc.sceneProperties.end());
      for (const SceneValue& v : sceneValues(plate.plate.base, plate.output))
        if (v.key.find('[') == std::string::npos) doc.sceneProperties.push_back(textProperty(v.key, sceneText(v.text)));
      doc.comment += " (a plate, plate coordinates from the plate's origin)";
    }
    if (pr.parent.empty()) {
      rsml::Plant plant;
      plant.id = std::to_string(doc.plants.size() + 1);
      plant.label = pr.name;
      plant.properties.push_back(textProperty("genotype", pr.seedling.genotype));
      std::string overrides;
      for (const std::string& o : pr.seedling.overrides) overrides += (overrides.empty() ? "" : ";") + o;
      plant.properties.push_back(textProperty("overrides", overrides));
      root.id = plant.id + ".1";
      plant.roots.push_back(std::move(root));
      where[r] = {static_cast<int>(doc.plants.size()), 0};
      doc.plants.push_back(std::move(plant));
      continue;
    }
    std::size_t p = 0;
    while (p < roots.size() && roots[p].name != pr.parent) ++p;
    if (p == roots.size() || where[p].first < 0) continue;
    rsml::Plant& plant = doc.plants[static_cast<std::size_t>(where[p].first)];
    root.parent = where[p].second;
    root.order = plant.roots[static_cast<std::size_t>(root.parent)].order + 1;
    root.id = plant.id + "." + std::to_string(plant.roots.size() + 1);
    root.properties.push_back(textProperty("name", pr.name));
    where[r] = {where[p].first, static_cast<int>(plant.roots.size())};
    plant.roots.push_back(std::move(root));
  }
  return doc;
}

}  // namespace

int exportRunCommand(const ExportOptions& o, std::vector<fs::path>* written) {
  // every input check first: a bad flag exits 2 before anything is read or written
  const fs::path runDir(o.runDir);
  if (o.rsml.empty() && o.gltf.empty() && o.paraview.empty())
    throw SceneError("export: no output asked for; give --rsml FILE (or --gltf FILE.glb, --paraview DIR)");
  if (flagGiven(o.atH) && flagGiven(o.everyH))
    throw SceneError("--at-h " + significantText(o.atH) + ": give --at-h or --every-h, not both");
  if (flagGiven(o.atH)) checkedNumber("--at-h", o.atH, kGrowthHours);
  if (flagGiven(o.everyH)) checkedNumber("--every-h", o.everyH, {0, kGrowthHours.hi, true, false, "h"});
  if (const std::string why = whyUnfinished(runDir); !why.empty()) throw SceneError(o.runDir + ": " + why);
  if (!fs::is_directory(runDir)) throw SceneError(o.runDir + ": run directory not found");
  // a plate's run: every root (RSML: one plant per seedling; glTF and ParaView: one striped tube per root)
  const bool plate = isPlateRun(runDir);
  Scene plateScene;
  std::vector<PlateRoot> plateRootList;
  std::vector<RunData> roots;
  if (plate) {
    plateScene = loadScene((runDir / "scene.toml").string());
    plateRootList = plateRoots(runDir);
    for (const PlateRoot& r : plateRootList) roots.push_back(readRun(r.dir));
  }
  const RunData data = plate ? roots.front() : readRun(runDir);
  const std::vector<Pick> picks = pickSnapshots(data.snaps, o);
  const bool series = flagGiven(o.everyH);

  // the write rule: the run directory is read and receives nothing; each file is locked, then checked
  WriteRule rule;
  rule.force = o.force;
  rule.inputs = {WriteInput{runDir, {}}, workingFolder()};
  std::vector<OutputLock> locks;
  std::vector<fs::path> rsmlFiles;
  if (!o.rsml.empty()) {
    const fs::path file = checkOutputName(o.rsml, "--rsml");
    rsmlFiles = series ? seriesNames(file, picks, o.everyH) : std::vector<fs::path>{file};
    for (const fs::path& f : rsmlFiles) {
      checkOutputName(f.string(), "--rsml");
      const fs::path dir = fs::absolute(f).parent_path();
      if (!fs::is_directory(dir)) throw SceneError("--rsml " + f.string() + ": folder " + dir.string() + " not found");
      locks.push_back(lockOutput(f, "--rsml"));
      claimFile(f, rule, "--rsml", OutputFormat::Rsml);
      // the file is staged as FILE.tmp (written all or none, below): a FILE.tmp already there is not ours
      fs::path tmp = f;
      tmp += ".tmp";
      std::error_code ec;
      if (fs::exists(fs::symlink_status(tmp, ec)))
        throw SceneError("--rsml " + f.string() + ": " + tmp.string() +
                         " is in the way (rootsim stages the file there); move it or delete it");
    }
  }

  // --gltf FILE.glb: one file; the run's every snapshot as an animation, the one nearest --at-h as a
  // still, or the --every-h snapshots as an animation (docs/gltf.md)
  fs::path gltfFile;
  if (!o.gltf.empty()) {
    gltfFile = checkOutputName(o.gltf, "--gltf");
    if (gltfFile.extension() != ".glb")
      throw SceneError("--gltf " + o.gltf + ": the file name must end in .glb (binary glTF 2.0)");
    const fs::path dir = fs::absolute(gltfFile).parent_path();
    if (!fs::is_directory(dir)) throw SceneError("--gltf " + o.gltf + ": folder " + dir.string() + " not found");
    for (const fs::path& f : rsmlFiles)
      if (fs::absolute(f).lexically_normal() == fs::absolute(gltfFile).lexically_normal())
        throw SceneError("--gltf " + o.gltf + ": the same file as --rsml");
    locks.push_back(lockOutput(gltfFile, "--gltf"));
    claimFile(gltfFile, rule, "--gltf", OutputFormat::Glb);
  }
  // --paraview DIR: a folder of its own kind, written whole (DIR.partial, then renamed); every snapshot, or
  // those --at-h / --every-h pick (docs/paraview.md)
  std::optional<StagedFolder> paraview;
  if (!o.paraview.empty()) {
    const fs::path dir = checkOutputName(o.paraview, "--paraview");
    const fs::path at = fs::absolute(dir).lexically_normal();
    for (const fs::path& f : rsmlFiles)
      if (fs::absolute(f).lexically_normal() == at) throw SceneError("--paraview " + o.paraview + ": the same path as --rsml");
    if (!gltfFile.empty() && fs::absolute(gltfFile).lexically_normal() == at)
      throw SceneError("--paraview " + o.paraview + ": the same path as --gltf");
    paraview.emplace(dir, paraviewFolder(), rule, "--paraview");
  }

  // every check passed: write. The RSML files (an --every-h series, or one file) are written all or none:
  // each into FILE.tmp first, renamed into place only once every one is whole; a failure (a full disk)
  // removes the .tmp files and leaves the earlier files as they were
  std::vector<fs::path> staged;
  try {
    for (std::size_t k = 0; k < rsmlFiles.size(); ++k) {
      const Snapshot& s = data.snaps[static_cast<std::size_t>(picks[k].index)];
      const int seq = series ? static_cast<int>(k) : -1;
      fs::path tmp = rsmlFiles[k];
      tmp += ".tmp";
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw RunError("cannot open " + tmp.string() + " for writing: " + std::strerror(errno));
      staged.push_back(tmp);
      out << rsml::writeRsml(plate ? plateRsmlOf(plateScene, plateRootList, roots, static_cast<std::size_t>(picks[k].index), seq)
                                   : rsmlOf(data, s, seq));
      out.close();
      if (!out) throw RunError("cannot write " + tmp.string() + ": " + std::strerror(errno));
    }
  } catch (const std::exception& e) {
    std::error_code ec;
    for (const fs::path& t : staged) fs::remove(t, ec);
    throw RunError(std::string(e.what()) + " (--rsml: none of the " + std::to_string(rsmlFiles.size()) +
                   " file(s) written; the earlier ones are unchanged)");
  }
  for (std::size_t k = 0; k < rsmlFiles.size(); ++k) {
    fs::rename(staged[k], rsmlFiles[k]);
    const Snapshot& s = data.snaps[static_cast<std::size_t>(picks[k].index)];
    if (written) written->push_back(rsmlFiles[k]);
    if (!o.quiet) std::fprintf(stderr, "wrote %s (growth step %d, %g h)\n", rsmlFiles[k].c_str(), s.step, s.timeH);
  }
  // the snapshots glTF and ParaView show: every one, or those --at-h / --every-h pick
  std::vector<int> shown;
  if (!gltfFile.empty() || paraview) {
    if (flagGiven(o.atH) || series)
      for (const Pick& p : picks) shown.push_back(p.index);
    else
      for (int k = 0; k < static_cast<int>(data.snaps.size()); ++k) shown.push_back(k);
  }
  std::vector<Snapshot> snaps;
  for (int k : shown) snaps.push_back(data.snaps[static_cast<std::size_t>(k)]);
  // a plate's roots in the plate's lab frame: each root's snapshots among the shown ones (a lateral root
  // has the plate's last snapshots only: its k-th is the plate's count - size + k)
  std::vector<RootSeries> plateSeries;
  std::vector<double> plateTimes;
  SceneInfo info = sceneInfoOf(plate ? plateScene.model : data.scene.model);
  GltfOptions gltfOptions;
  if (plate && !shown.empty()) {
    for (int k : shown) plateTimes.push_back(data.snaps[static_cast<std::size_t>(k)].timeH);
    const PlateFrame pf = plateScene.model.env.plane.frame();
    std::size_t count = 0;
    for (const RunData& d : roots) count = std::max(count, d.snaps.size());
    for (std::size_t r = 0; r < roots.size(); ++r) {
      RootSeries one;
      one.name = plateRootList[r].name;
      const Vec3 offset = plateOffset(pf, plateRootList[r]);
      const std::size_t lead = count - roots[r].snaps.size();
      for (std::size_t j = 0; j < shown.size(); ++j) {
        const auto k = static_cast<std::size_t>(shown[j]);
        if (k < lead) continue;
        if (one.snaps.empty()) one.firstFrame = static_cast<int>(j);
        one.snaps.push_back(roots[r].snaps[k - lead]);
        one.snaps.back().x.colwise() += offset;
      }
      if (!one.snaps.empty()) plateSeries.push_back(std::move(one));  // not emerged by the last shown snapshot
    }
    // the whole plate: (u, v) = (lateral, -downhill) over [0, width] x [-length, 0], as render's plate view
    const double w = plateScene.plate.params.width / units::mm, l = plateScene.plate.params.length / units::mm;
    gltfOptions.plateRectMm = std::array<double, 4>{0.0, -l, w, 0.0};
  }
  if (!gltfFile.empty()) {
    writeFileAtomic(gltfFile, plate ? gltfPlateBinary(plateSeries, info, gltfOptions) : gltfBinary(snaps, info));
    if (written) written->push_back(gltfFile);
    if (!o.quiet)
      std::fprintf(stderr, "wrote %s (%zu snapshot%s, %g h to %g h%s)\n", gltfFile.c_str(), snaps.size(),
                   snaps.size() == 1 ? "" : "s", snaps.front().timeH, snaps.back().timeH,
                   plate ? (", " + std::to_string(plateSeries.size()) + " roots").c_str() : "");
  }
  if (paraview) {
    if (plate)
      writeParaviewPlateFiles(paraview->work(), plateSeries, plateTimes, info, paraview->final());
    else
      writeParaviewFiles(paraview->work(), snaps, info, paraview->final());
    paraview->commit();
    if (written) written->push_back(paraview->final());
    if (!o.quiet)
      std::fprintf(stderr, "wrote %s (%zu snapshot%s; open with: paraview --script=%s)\n", paraview->final().c_str(),
                   snaps.size(), snaps.size() == 1 ? "" : "s", (paraview->final() / "open_in_paraview.py").c_str());
  }
  return 0;
}

}  // namespace rootsim::app
