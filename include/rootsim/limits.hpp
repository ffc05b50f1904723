#pragma once
// Work that input sizes, bounded before it is done, and numbers given to flags and keywords checked like
// scene keys. The caps live here, each with its reason; docs/outputs.md, "Caps", lists them.
#include <exception>
#include <new>
#include <string>
#include <vector>

namespace rootsim {

namespace caps {
// resampled points of one traced root (analyze, compare, fit, render --trace): the shape analysis holds
// about 100 bytes a point (positions, tangents, angles, curvature, arc length and their copies), so a
// million points is about 100 MB, and 50 m of
// root at the default step of 0.05 mm
inline constexpr double kTracePoints = 1e6;
// frames of one movie (render, run --movie): a frame holds a copy of its snapshot, about 120 bytes a node
// (15 doubles), so 20 000 frames of a 600-node root (a shipped 3000-step run) are 1.4 GB; 20 000 frames
// are 11 minutes at 30 fps
inline constexpr double kMovieFrames = 2e4;
// roots of one plate, seedlings and the laterals they can grow together: every root is relaxed at every
// growth step and checked against the roots within reach, so the time grows with the roots (the shipped
// plate_wildtype, 42 roots, takes minutes; 2000 roots, hours); memory is not the bound (tens of KB a root)
inline constexpr double kPlateRoots = 2000;
// runs of one montage: every run's snapshots are held at once, about 22 MB for a shipped 3000-step run
// (300 snapshots of 600 nodes at ~120 bytes a node), so 64 runs are about 1.4 GB
inline constexpr double kMontageRuns = 64;
// pixels on the width of one figure panel's PNG (figure --width-mm and --dpi): cairo draws it whole in
// memory at 4 bytes a pixel, so a square panel of 20 000 px is 1.6 GB (cairo refuses beyond 32 767 px);
// a 180 mm journal column at 2400 dpi is 17 008 px
inline constexpr double kFigurePixels = 20000;
// files of an --every-h series (export): one RSML file each (a few KB to MB), written all or none
inline constexpr double kSeriesFiles = 1e5;
}  // namespace caps

// a number flag not given: the value the options structs (AnalyzeOptions, RenderOptions, ExportOptions)
// hold until the command line sets it
inline constexpr double kUnsetFlag = -1e300;
constexpr bool flagGiven(double v) { return v != kUnsetFlag; }

// the range a number flag accepts, in its unit; open ends exclude the bound
struct NumberRange {
  double lo = 0, hi = 0;
  bool loOpen = false, hiOpen = false;
  const char* unit = "";  // "mm", "h", "px/mm"; "" for a pure number
};

// a growth time given to a flag (--at-h, --from-h, --to-h): 0 to a million hours (a century)
inline constexpr NumberRange kGrowthHours{0, 1e6, false, false, "h"};

// the range as text, with its unit: "in (0, 10] mm"
std::string rangeText(const NumberRange& r);
// v when it is finite and in r; else SceneError "FLAG V: expected a finite number in RANGE" (exit 2).
// The one check every number flag of the CLI and every number keyword of the Python package goes through.
double checkedNumber(const std::string& flag, double v, const NumberRange& r);
// a count the input decides, checked against its cap before the work is done: SceneError
// "WHAT: would make COUNT ITEMS, more than the cap of CAP (REASON)" when count > cap (or is not finite)
void checkCount(const std::string& what, double count, double cap, const std::string& items, const std::string& reason);

// a number read from outside a scene for a scene key (an RSML file's properties, read as hints): checked
// like the key in a scene file (scene.cpp); "" when the key accepts it, else why not ("must be > 0 (got
// -1)"), and "is not a number key of a scene" for a name the schema does not have
std::string sceneNumberProblem(const std::string& key, double value);
// the name of `names` nearest `word` (edit distance) when it is a near miss, as scene keys are suggested
// (scene.cpp); "" when none is near: "did you mean ...?" for flags and commands
std::string closestName(const std::string& word, const std::vector<std::string>& names);

// what a failure says (ERROR.txt, the CLI's "run failed:"): an exception's text, except that memory running
// out is named as such with where it ran out ("out of memory during WHERE"), never only "std::bad_alloc"
inline std::string failureText(const std::exception& e, const std::string& where) {
  if (dynamic_cast<const std::bad_alloc*>(&e))
    return "out of memory during " + where + " (std::bad_alloc): the work exceeds this machine's memory; "
           "docs/outputs.md, Caps, lists the bounds rootsim checks before it starts";
  return e.what();
}

}  // namespace rootsim
