#pragma once
// The cases of the figure panels: one simulated root each (its parameters and length), the context a
// panel runs in, and the claims it reports; how a case becomes a run (its directory and its model).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rootsim/figure.hpp"
#include "rootsim/model.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::fig {

// one simulated root of a panel
struct Case {
  double alpha = 40, beta = 0.1, gamma = 0.1, rTau = 0;
  bool free = false;        // free organ: no plate, no adhesion
  double lengthMm = 10;     // grown to this length
  bool apical = false;      // apical gravisensing (docs/model.md, Growth) instead of local
};

// one claim of the paper with its theory value, the paper's value and the measured value
struct Claim {
  std::string what, theory, paper, measured, tolerance;
  bool agrees;
  std::string note = "";  // what was found when it does not agree (printed under the table)
};

struct Ctx {
  const FigureOptions& opt;
  const std::function<void(const std::string&)>& log;
  std::vector<Claim>* claims;
  std::filesystem::path runs() const { return std::filesystem::path(opt.out) / "runs"; }
  double h() const { return opt.quick ? 0.1 : 0.05; }   // element length [mm]
  double dt() const { return opt.quick ? 0.1 : 0.05; }  // growth step [h]
  // the phase diagrams' step in alpha [deg]: the tolerance of every transition-angle claim
  double alphaStep() const { return opt.quick ? 15 : 5; }
  // how the panels are written (resolution, physical size, titles)
  SaveOptions save() const { return SaveOptions{opt.dpi, opt.widthMm, opt.titles}; }
};

// the run directory of a case inside ctx's runs folder (the same case, the same directory: resumable)
std::string dirOf(const Ctx& c, const Case& k);
// the scene name of every figure run (result.csv's scene column, summary.json, scene.toml's header:
// figure runs were runs of an empty base.toml, and their outputs keep the name)
inline constexpr const char* kFigureSceneName = "base";
// the model a case runs with: the default model (docs/model.md, Experiment and parameters) with the case's
// parameters, the context's element length and growth step, growth steps to reach the case's length
Model modelOf(const Ctx& c, const Case& k);
// what a case's run writes: no VTK, a snapshot every half hour
OutputParams outputOf(const Ctx& c);
// what a picture of the case shows beside the root: its model's (sceneInfoOf, snapshot.hpp)
SceneInfo infoOf(const Ctx& c, const Case& k);

}  // namespace rootsim::fig
