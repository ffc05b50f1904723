#pragma once
// The pictures of `rootsim compare` and `rootsim fit` (docs/experiments.md): a traced root over a simulated
// one on the plate, and a fit's objective over two free parameters. Each is written as PDF, SVG and PNG
// (saveFigure).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/model.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the trace (plate coordinates [mm]: lateral, downhill; aligned at the simulated root's seed) over the
// simulated root (a snapshot of a run of model m, drawn as the figure panels draw roots: tube, +-d1
// stripes, the plate's 1 mm grid, obstacles), and beside it both roots' lateral position along downhill.
// title: the figure's title; caption: a line under it (distances, chi-square)
void saveComparePanel(const Model& m, const Snapshot& sim, const Eigen::Matrix3Xd& traceMm, const std::string& title,
                      const std::string& caption, const std::string& pathWithoutExtension);
// a group's traces (a plate's seedlings, traceNames a label each, in plate coordinates from each one's
// base [mm]) over its simulated roots: one snapshot for all, or one per trace (the same order: each
// seedling's own run, drawn dashed in its trace's colour in B); saveComparePanel is this with one of each
void saveGroupComparePanel(const Model& m, const std::vector<Snapshot>& sims, const std::vector<Eigen::Matrix3Xd>& tracesMm,
                           const std::vector<std::string>& traceNames, const std::string& title, const std::string& caption,
                           const std::string& pathWithoutExtension);
// a fit by group's answer for one free key: per group its value with a +-sigma bar (a flat key: the value
// alone, marked "flat") and each seedling's own value as a dot beside it
struct GroupKeyValue {
  std::string group;
  double value = 0, sigma = 0;     // sigma NaN: flat
  std::vector<double> seedlings;   // each seedling's own value
};
// one panel per key (keys[i], its box lo[i]..hi[i], perKey[i] a value per group), written as PDF, SVG, PNG
void saveGroupKeysPanel(const std::vector<std::string>& keys, const std::vector<double>& lo, const std::vector<double>& hi,
                        const std::vector<std::vector<GroupKeyValue>>& perKey, const std::string& title,
                        const std::string& dotsLabel, const std::string& pathWithoutExtension);
// a plate's comparison: A the simulated plate (every root's snapshot, in plate coordinates from the
// plate's origin [mm]), B the traced plate (every traced root, moved onto the plate by the pairing) in
// the same window; names: a label per simulated root (same order) drawn at its seed, traceNames the same
// per traced root ("" for none)
void savePlateComparePanel(const Model& m, const std::vector<Snapshot>& sims, const std::vector<std::string>& names,
                           const std::vector<Eigen::Matrix3Xd>& tracesMm, const std::vector<std::string>& traceNames,
                           const std::string& title, const std::string& caption, const std::string& path);

// a fit's objective over two free parameters: every run coloured by its chi-square above the lowest (the
// start design's grid as cells), the fit, and the 1-sigma ellipse of the covariance when there is one
// (cov null: none); beside it (zoomX, zoomY > 0) the same around the fit, +- zoomX and +- zoomY, the
// window shifted and cut to lie inside the box (no second panel when it would be the whole box)
struct LandscapePoint {
  double x = 0, y = 0, chi2 = 0;
  bool design = false;  // a cell of the start design's grid (else an optimiser's or the stencil's point)
};
Figure landscapeFigure(const std::vector<LandscapePoint>& pts, const std::string& xKey, const std::string& yKey,
                       double xLo, double xHi, double yLo, double yHi, int gridLevels, double bestX, double bestY,
                       const Eigen::Matrix2d* cov, double zoomX, double zoomY, const std::string& title);
// the same saved as path + .pdf, .svg and .png
void saveLandscapePanel(const std::vector<LandscapePoint>& pts, const std::string& xKey, const std::string& yKey,
                        double xLo, double xHi, double yLo, double yHi, int gridLevels, double bestX, double bestY,
                        const Eigen::Matrix2d* cov, double zoomX, double zoomY, const std::string& title,
                        const std::string& pathWithoutExtension);

}  // namespace rootsim
