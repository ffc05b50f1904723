// The flags `render` and `montage` share (src/app/flags.cpp): the view, the picture size (even, 64 px to
// 4K either way round), the video's frame rate and quality and the colour field, each refused naming the
// flag, the value and what was expected.
#include <doctest/doctest.h>

#include <string>
#include <utility>

#include "flags.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/errors.hpp"

using namespace rootsim;
using namespace rootsim::app;

TEST_CASE("flags: --view is top or 3d") {
  CHECK(parseViewKind("top") == View::Kind::Top);
  CHECK(parseViewKind("3d") == View::Kind::Perspective);
  CHECK_THROWS_WITH_AS(parseViewKind("side"), "--view side: expected top or 3d", SceneError);
}

TEST_CASE("flags: --size is WIDTHxHEIGHT, both even, at least 64 px, at most 3840x2160 either way round") {
  CHECK(parseSize("1280x720") == std::pair<int, int>{1280, 720});
  CHECK(parseSize("64x64") == std::pair<int, int>{64, 64});
  CHECK(parseSize("3840x2160") == std::pair<int, int>{3840, 2160});
  CHECK(parseSize("2160x3840") == std::pair<int, int>{2160, 3840});
  CHECK_THROWS_WITH_AS(parseSize("1280"), doctest::Contains("--size 1280: expected WIDTHxHEIGHT in pixels"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("12a0x720"), doctest::Contains("--size 12a0x720: expected WIDTHxHEIGHT"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("x720"), doctest::Contains("expected WIDTHxHEIGHT"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("-640x480"), doctest::Contains("expected WIDTHxHEIGHT"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("123456x480"), doctest::Contains("expected WIDTHxHEIGHT"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("62x480"), doctest::Contains("--size 62x480: width and height must be at least 64 px"),
                       SceneError);
  CHECK_THROWS_WITH_AS(parseSize("3842x2160"), doctest::Contains("at most 3840x2160 (or 2160x3840)"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("2162x2162"), doctest::Contains("at most 3840x2160"), SceneError);
  CHECK_THROWS_WITH_AS(parseSize("641x481"), doctest::Contains("must be even (H.264 yuv420p), e.g. 642x482"), SceneError);
}

TEST_CASE("flags: --fps 1..240 and --crf 0..51") {
  const VideoOptions v = parseVideo(24, 0);
  CHECK(v.fps == 24);
  CHECK(v.crf == 0);
  CHECK(parseVideo(1, 51).crf == 51);
  CHECK(parseVideo(240, 18).fps == 240);
  CHECK_THROWS_WITH_AS(parseVideo(0, 18), "--fps 0: expected 1..240", SceneError);
  CHECK_THROWS_WITH_AS(parseVideo(241, 18), "--fps 241: expected 1..240", SceneError);
  CHECK_THROWS_WITH_AS(parseVideo(30, -1), "--crf -1: expected 0..51", SceneError);
  CHECK_THROWS_WITH_AS(parseVideo(30, 52), "--crf 52: expected 0..51", SceneError);
}

TEST_CASE("flags: --color-by is one of the colour fields, an unknown one refused listing them") {
  CHECK(parseColourBy("none") == ColourField::None);
  CHECK(parseColourBy("twist") == ColourField::Twist);
  CHECK(parseColourBy("kappa0") == ColourField::Kappa0);
  const std::string want = "--color-by hue: expected one of " + colourFieldNames();
  CHECK_THROWS_WITH_AS(parseColourBy("hue"), want.c_str(), SceneError);
}
