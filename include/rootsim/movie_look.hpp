#pragma once
// How a movie looks (`rootsim render`, `run --movie`; docs/cli.md): camera, colours, plots, shadows. The
// flags as given, checked into a MovieLook (SceneError naming the flag: exit 2), applied to a job.
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/camera.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {
struct MovieJob;
}

namespace rootsim::app {

// the look flags, as given
struct LookOptions {
  std::string camera = "fit";  // fit | follow
  double fieldMm = 2.0;        // follow window width [mm]
  bool fieldGiven = false;     // --field-mm was on the command line
  bool inset = false;          // fit view with a follow window in its corner
  std::string colorBy = "none";  // none | curvature | twist | kappa0 | stretch | contact
  std::string plot;            // comma-separated subset of theta_tip,Eb,Et,Wr,Tw
  bool shadows = false;        // the root's shadow on the plate
  bool cameraGiven = false;    // --camera was on the command line (run --movie: else the inset look)
  bool insetByDefault = false; // run --movie: without --camera the look is the fit view with a follow
                               // inset, so --field-mm alone sizes that inset (render: --field-mm needs
                               // --camera follow or --inset)
};

// the look, checked
struct MovieLook {
  CameraMode camera = CameraMode::Fit;
  double fieldMm = 2.0;
  bool inset = false;
  ColourField colourBy = ColourField::None;
  std::vector<std::string> plots;  // keys in the order given
  bool shadows = false;
  bool defaultCamera = false;  // neither --camera nor --inset given (run --movie picks the inset look)
};
MovieLook parseLook(const LookOptions& o);
// --field-mm larger than the plate a fit view shows (plateMm wide) is refused (SceneError)
void checkFieldAgainstPlate(const MovieLook& look, double plateMm);

// the look applied to a job of the run in runDir (its snapshots): camera, colours (the trajectory must
// hold the field), plots (from runDir/timeseries.csv), shadows
void applyLook(const MovieLook& look, const std::filesystem::path& runDir, const std::vector<Snapshot>& snaps,
               MovieJob& job);

}  // namespace rootsim::app
