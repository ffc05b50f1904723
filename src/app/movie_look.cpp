// the look of a movie: its flags checked, then applied to a job (the plots read from timeseries.csv)
#include "rootsim/movie_look.hpp"

#include <cstdio>
#include <set>

#include "flags.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/trajectory.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

// the plot keys: timeseries.csv column, axis title, unit, SI prefix
struct PlotKey {
  const char* key;
  const char* column;
  const char* name;
  const char* unit;
  bool si;
};
constexpr PlotKey kPlotKeys[] = {
    {"theta_tip", "theta_tip_deg", "\xCE\xB8 tip", "\xC2\xB0", false},
    {"Eb", "Eb", "E_b (growth zone)", "J", true},
    {"Et", "Et", "E_t (growth zone)", "J", true},
    {"Wr", "Wr", "writhe Wr (growth zone)", "", false},
    {"Tw", "Tw", "twist Tw (growth zone)", "turns", false},
};


}  // namespace

MovieLook parseLook(const LookOptions& o) {
  MovieLook l;
  if (o.camera == "fit")
    l.camera = CameraMode::Fit;
  else if (o.camera == "follow")
    l.camera = CameraMode::Follow;
  else
    throw SceneError("--camera " + o.camera + ": expected fit or follow");
  checkedNumber("--field-mm", o.fieldMm, {0, 1e4, true, false, "mm"});
  l.fieldMm = o.fieldMm;
  // run --movie's default look is the fit view with a follow inset: there --field-mm alone sizes the inset
  const bool impliedInset = o.insetByDefault && o.fieldGiven && !o.cameraGiven && !o.inset;
  if (o.fieldGiven && l.camera != CameraMode::Follow && !o.inset && !impliedInset)
    throw SceneError("--field-mm " + significantText(o.fieldMm) + ": sizes the follow window; add --camera follow or --inset");
  if (o.inset && l.camera == CameraMode::Follow)
    throw SceneError("--inset: puts a follow window into the fit view; use it with --camera fit");
  l.inset = o.inset || impliedInset;
  l.colourBy = parseColourBy(o.colorBy);
  if (!o.plot.empty()) {
    std::set<std::string> seen;
    for (const std::string& k : splitCommas(o.plot)) {
      bool known = false;
      for (const PlotKey& p : kPlotKeys) known = known || k == p.key;
      if (!known) throw SceneError("--plot " + o.plot + ": unknown key '" + k + "' (expected any of theta_tip,Eb,Et,Wr,Tw)");
      if (!seen.insert(k).second) throw SceneError("--plot " + o.plot + ": '" + k + "' given twice");
      l.plots.push_back(k);
    }
  }
  l.shadows = o.shadows;
  l.defaultCamera = !o.cameraGiven && !l.inset;
  return l;
}

void checkFieldAgainstPlate(const MovieLook& look, double plateMm) {
  if (look.camera == CameraMode::Follow || look.inset)
    if (look.fieldMm > plateMm)
      throw SceneError("--field-mm " + significantText(look.fieldMm) + ": larger than the plate (" + significantText(plateMm) +
                       " mm wide in the fit view)");
}

void applyLook(const MovieLook& look, const fs::path& runDir, const std::vector<Snapshot>& snaps, MovieJob& job) {
  job.camera = look.camera;
  job.fieldMm = look.fieldMm;
  job.inset = look.inset;
  job.view.colourBy = look.colourBy;
  job.view.shadows = look.shadows;
  const Snapshot& last = snaps.back();
  if (look.colourBy == ColourField::Kappa0 && last.kappa0.size() == 0)
    throw SceneError("--color-by kappa0: " + trajectoryPath(runDir).string() +
                     " has no kappa0_per_mm column (written by an older rootsim; run the scene again)");
  if (look.colourBy == ColourField::Contact && last.plateForce.size() == 0)
    throw SceneError("--color-by contact: " + trajectoryPath(runDir).string() +
                     " has no plate_force_n column (written by an older rootsim; run the scene again)");
  if (look.plots.empty()) return;
  const fs::path ts = runDir / "timeseries.csv";
  if (!fs::is_regular_file(ts)) throw SceneError(ts.string() + ": not found (needed by --plot)");
  const CsvColumns cols = readCsvColumns(ts);
  auto column = [&](const std::string& name) -> const std::vector<double>* {
    for (std::size_t c = 0; c < cols.names.size(); ++c)
      if (cols.names[c] == name) return &cols.values[c];
    return nullptr;
  };
  const std::vector<double>* time = column("time_h");
  if (!time) throw SceneError(ts.string() + ": no time_h column");
  for (const std::string& k : look.plots) {
    for (const PlotKey& p : kPlotKeys) {
      if (k != p.key) continue;
      const std::vector<double>* c = column(p.column);
      if (!c) throw SceneError("--plot " + k + ": " + ts.string() + " has no column " + p.column);
      PlotSeries s;
      s.name = p.name;
      s.unit = p.unit;
      s.siPrefix = p.si;
      s.timeH = *time;
      s.value = *c;
      if (s.timeH.empty()) throw SceneError(ts.string() + ": no rows to plot");
      job.plots.push_back(std::move(s));
    }
  }
}

}  // namespace rootsim::app
