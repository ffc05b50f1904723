// How a movie looks (src/app/movie_look.cpp): the look flags checked into a MovieLook, each refusal naming
// the flag; --field-mm sizes a follow window (the follow camera, an inset, or run --movie's default inset
// look) and never exceeds the plate the fit view shows.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "rootsim/colour_map.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/movie_look.hpp"

using namespace rootsim;
using namespace rootsim::app;

TEST_CASE("movie look: the defaults are the fit camera, no inset, no colours, no plots, no shadows") {
  const MovieLook l = parseLook(LookOptions{});
  CHECK(l.camera == CameraMode::Fit);
  CHECK(l.fieldMm == 2.0);
  CHECK_FALSE(l.inset);
  CHECK(l.colourBy == ColourField::None);
  CHECK(l.plots.empty());
  CHECK_FALSE(l.shadows);
  CHECK(l.defaultCamera);
}

TEST_CASE("movie look: the camera, colours, plots in the order given and shadows") {
  LookOptions o;
  o.camera = "follow";
  o.cameraGiven = true;
  o.fieldMm = 1.5;
  o.fieldGiven = true;
  o.colorBy = "curvature";
  o.plot = "Wr,theta_tip";
  o.shadows = true;
  const MovieLook l = parseLook(o);
  CHECK(l.camera == CameraMode::Follow);
  CHECK(l.fieldMm == 1.5);
  CHECK(l.colourBy == ColourField::Curvature);
  CHECK(l.plots == std::vector<std::string>{"Wr", "theta_tip"});
  CHECK(l.shadows);
  CHECK_FALSE(l.defaultCamera);
}

TEST_CASE("movie look: --field-mm sizes a follow window: with --camera follow, --inset, or run --movie's default inset") {
  LookOptions o;
  o.fieldMm = 3.0;
  o.fieldGiven = true;
  CHECK_THROWS_WITH_AS(parseLook(o), "--field-mm 3: sizes the follow window; add --camera follow or --inset", SceneError);
  o.inset = true;
  const MovieLook withInset = parseLook(o);
  CHECK(withInset.inset);
  CHECK_FALSE(withInset.defaultCamera);
  o.inset = false;
  o.insetByDefault = true;  // run --movie without --camera
  const MovieLook implied = parseLook(o);
  CHECK(implied.inset);
  CHECK(implied.camera == CameraMode::Fit);
  o.cameraGiven = true;  // run --movie --camera fit --field-mm: no inset to size
  CHECK_THROWS_AS(parseLook(o), SceneError);
}

TEST_CASE("movie look: each bad flag is refused naming it") {
  LookOptions o;
  o.camera = "orbit";
  CHECK_THROWS_WITH_AS(parseLook(o), "--camera orbit: expected fit or follow", SceneError);
  o = LookOptions{};
  o.camera = "follow";
  o.inset = true;
  CHECK_THROWS_WITH_AS(parseLook(o), "--inset: puts a follow window into the fit view; use it with --camera fit", SceneError);
  o = LookOptions{};
  o.camera = "follow";
  o.fieldMm = 0.0;
  CHECK_THROWS_WITH_AS(parseLook(o), doctest::Contains("--field-mm"), SceneError);
  o = LookOptions{};
  o.plot = "theta_tip,speed";
  CHECK_THROWS_WITH_AS(parseLook(o), "--plot theta_tip,speed: unknown key 'speed' (expected any of theta_tip,Eb,Et,Wr,Tw)",
                       SceneError);
  o.plot = "Eb,Eb";
  CHECK_THROWS_WITH_AS(parseLook(o), "--plot Eb,Eb: 'Eb' given twice", SceneError);
  o = LookOptions{};
  o.colorBy = "rainbow";
  CHECK_THROWS_WITH_AS(parseLook(o), doctest::Contains("--color-by rainbow: expected one of"), SceneError);
}

TEST_CASE("movie look: a follow window wider than the plate the fit view shows is refused, the fit view alone is not") {
  LookOptions o;
  o.camera = "follow";
  o.fieldMm = 12.0;
  o.fieldGiven = true;
  const MovieLook follow = parseLook(o);
  CHECK_NOTHROW(checkFieldAgainstPlate(follow, 12.0));
  CHECK_THROWS_WITH_AS(checkFieldAgainstPlate(follow, 10.0),
                       "--field-mm 12: larger than the plate (10 mm wide in the fit view)", SceneError);
  const MovieLook fit = parseLook(LookOptions{});
  CHECK_NOTHROW(checkFieldAgainstPlate(fit, 0.5));
}
