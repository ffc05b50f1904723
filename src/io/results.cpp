#include "rootsim/results.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {
#define NUM(name, unit, growth, field) ResultColumn{name, unit, growth, false, &RunResult::field, nullptr}
#define STR(name, growth, field) ResultColumn{name, "", growth, true, nullptr, &RunResult::field}

std::string csvNum(double x) {
  return std::isfinite(x) ? significantText(x, 10) : "";
}

}  // namespace

const std::vector<ResultColumn>& resultColumns() {
  static const std::vector<ResultColumn> c = {
      STR("scene", false, scene),
      STR("status", false, status),
      NUM("steps", "", false, steps),
      NUM("time_h", "h", false, timeH),
      NUM("length_mm", "mm", false, lengthMm),
      NUM("elements", "", false, elements),
      NUM("theta_tip_deg", "deg", false, thetaTipDeg),
      NUM("total_substeps", "", false, totalSubsteps),
      STR("pattern", true, pattern),
      NUM("wavelength_mm", "mm", true, wavelengthMm),
      NUM("amplitude_mm", "mm", true, amplitudeMm),
      NUM("amplitude_half_mm", "mm", true, amplitudeHalfMm),
      NUM("lateral_peaks", "", true, lateralPeaks),
      NUM("skew_deg", "deg", true, skewDeg),
      NUM("max_kappa_per_mm", "1/mm", true, maxKappaPerMm),
      NUM("theta_min_deg", "deg", true, thetaMinDeg),
      NUM("theta_max_deg", "deg", true, thetaMaxDeg),
      NUM("first_snap_or_turning_h", "h", true, snapOrTurningH),
      NUM("alpha_deg", "deg", true, alphaDeg),
      NUM("beta", "", true, beta),
      NUM("gamma", "", true, gamma),
      NUM("r_tau", "", true, rTau),
      STR("sensing", true, sensing),
      NUM("effective_gain", "", true, effectiveGain),
      NUM("T0_h", "h", true, T0h),
      NUM("max_kappa_eq8_per_mm", "1/mm", true, maxKappaEq8PerMm),
      NUM("wavelength_eq9_mm", "mm", true, wavelengthEq9Mm),
      NUM("amplitude_eq10_mm", "mm", true, amplitudeEq10Mm),
      NUM("alpha_s_to_w_eq12_deg", "deg", true, alphaSToWEq12Deg),
      NUM("alpha_w_to_c_eq13_deg", "deg", true, alphaWToCEq13Deg),
      NUM("omega_T0", "", true, omegaT0),
  };
  return c;
}
#undef NUM
#undef STR

double RunResult::number(const std::string& column) const {
  for (const auto& c : resultColumns())
    if (column == c.name) return c.text ? NAN : this->*c.num;
  return NAN;
}

RunResult makeResult(const Model& m, const Simulation& sim, const ShapeAnalysis* a, double snapOrTurningH) {
  const StepRecord& last = sim.last();
  RunResult r;
  r.grows = m.growth.enabled;
  r.scene = m.name;
  r.steps = sim.step();
  r.timeH = last.timeH;
  r.lengthMm = last.length / units::mm;
  r.elements = last.elements;
  r.thetaTipDeg = last.thetaTip / units::deg;
  r.totalSubsteps = static_cast<double>(sim.totalSubsteps());
  if (!r.grows || !a) return r;
  const Theory t = theoryFor(m);
  r.pattern = a->pattern;
  // a wavelength needs two peaks on one side (three turning points), an amplitude two opposite peaks;
  // A is the peak-to-peak excursion (docs/model.md, Observables), half of it beside it
  r.wavelengthMm = a->peaks >= 3 ? a->wavelength / units::mm : NAN;
  r.amplitudeMm = a->peaks >= 2 ? a->amplitude / units::mm : NAN;
  r.amplitudeHalfMm = a->peaks >= 2 ? a->amplitudeHalf / units::mm : NAN;
  r.lateralPeaks = a->peaks;
  r.skewDeg = a->skew / units::deg;
  r.maxKappaPerMm = a->maxKappa * units::mm;
  r.thetaMinDeg = a->thetaMin / units::deg;
  r.thetaMaxDeg = a->thetaMax / units::deg;
  r.snapOrTurningH = snapOrTurningH;
  r.alphaDeg = m.env.plane.alpha / units::deg;
  r.beta = m.tropism.beta;
  r.gamma = m.tropism.gamma;
  r.rTau = m.tropism.rTau;
  r.sensing = m.tropism.sensing == Sensing::Apical ? "apical" : "local";
  r.effectiveGain = t.effectiveGain;
  r.T0h = t.T0 / units::hour;
  r.maxKappaEq8PerMm = t.maxKappa * units::mm;
  r.wavelengthEq9Mm = t.wavelength / units::mm;
  r.amplitudeEq10Mm = t.amplitude / units::mm;
  r.alphaSToWEq12Deg = t.alphaStraightToWave / units::deg;
  r.alphaWToCEq13Deg = t.alphaWaveToCoil / units::deg;
  r.omegaT0 = t.omegaT0;
  return r;
}

std::string resultHeader(bool grows) {
  std::string h;
  for (const auto& c : resultColumns())
    if (grows || !c.growthOnly) h += (h.empty() ? "" : ",") + std::string(c.name);
  return h;
}

std::string resultCsv(const RunResult& r) {
  std::string row;
  bool first = true;
  for (const auto& c : resultColumns()) {
    if (c.growthOnly && !r.grows) continue;
    row += first ? "" : ",";
    first = false;
    row += c.text ? r.*c.str : csvNum(r.*c.num);
  }
  return resultHeader(r.grows) + "\n" + row + "\n";
}

RunResult readResult(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string head, line;
  if (!in || !std::getline(in, head) || !std::getline(in, line)) throw RunError("cannot read " + path.string());
  RunResult r;
  r.grows = head == resultHeader(true);
  if (!r.grows && head != resultHeader(false))
    throw RunError(path.string() + ": not a result.csv of this rootsim (header differs)");
  std::vector<std::string> cells;
  try {
    cells = csvCells(line);
  } catch (const std::invalid_argument& e) {
    throw RunError(path.string() + ":2: " + e.what());
  }
  size_t i = 0;
  for (const auto& c : resultColumns()) {
    if (c.growthOnly && !r.grows) continue;
    const std::string cell = i < cells.size() ? cells[i] : std::string();
    ++i;
    if (c.text) r.*c.str = cell;
    else r.*c.num = cell.empty() ? NAN : std::stod(cell);
  }
  return r;
}

}  // namespace rootsim
