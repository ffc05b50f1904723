// stills and time windows (src/app/render_run.cpp, src/render/movie.cpp): `rootsim render --png --at-h`
// is the movie's frame with the same flags, pixel for pixel; --final-png is the movie's last frame;
// --from-h / --to-h / --hours-per-second pick the frames (movieFrames) and set the MP4's duration
#include <doctest/doctest.h>

#include "../test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "render_test_util.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/png.hpp"

namespace fs = std::filesystem;
using namespace rootsim;
using rootsim::test::Result;
using rootsim::test::run;

namespace {

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string frameName(int k) {
  char b[32];
  std::snprintf(b, sizeof b, "frame_%05d.png", k);
  return b;
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// a small run: 11 snapshots, steps 0, 4, ..., 40 (0, 0.2, ..., 2 h)
struct TinyRun {
  fs::path dir;
  std::vector<double> timesH;
};
TinyRun tinyRun(const fs::path& d) {
  TinyRun t{d / "run", {}};
  const Result ran = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                         "/scenes/fig2b_waving.toml --set growth.steps=40 --set output.every_steps=4 --quiet --out " +
                         t.dir.string());
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  // snapshot k at step 4k of 0.05 h (the flags below keep a margin of a tenth of the spacing, so
  // rounding in the run's own clock does not matter)
  for (int k = 0; k <= 10; ++k) t.timesH.push_back(0.05 * 4 * k);
  return t;
}

}  // namespace

TEST_CASE("stills: movieFrames and nearestSnapshot pick the window and the speed and break ties to the earlier snapshot") {
  const std::vector<double> t = {0.0, 0.5, 1.0, 1.5, 2.0};
  CHECK(nearestSnapshot(t, -3.0) == 0);
  CHECK(nearestSnapshot(t, 0.24) == 0);
  CHECK(nearestSnapshot(t, 0.25) == 0);  // a tie: the earlier
  CHECK(nearestSnapshot(t, 0.26) == 1);
  CHECK(nearestSnapshot(t, 1.0) == 2);
  CHECK(nearestSnapshot(t, 9.0) == 4);
  // the window alone: the snapshots in [from, to], one frame each
  CHECK(movieFrames(t, -1e300, 1e300, 0.0, 30) == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(movieFrames(t, 0.5, 1.5, 0.0, 30) == std::vector<int>{1, 2, 3});
  CHECK(movieFrames(t, 0.4, 1.6, 0.0, 30) == std::vector<int>{1, 2, 3});
  CHECK(movieFrames(t, 0.6, 0.9, 0.0, 30).empty());
  // fast: 1 h/s at 1 fps over [0, 2] h -> floor(2 / 1) + 1 = 3 frames at 0, 1, 2 h (snapshots skipped)
  CHECK(movieFrames(t, 0.0, 2.0, 1.0, 1) == std::vector<int>{0, 2, 4});
  // slow: 0.25 h/s at 2 fps -> frames every 0.125 h over [0.5, 1.5]: 9 frames; 0.75 h and 1.25 h are
  // ties -> the earlier snapshot (0.5 h, 1 h)
  CHECK(movieFrames(t, 0.5, 1.5, 0.25, 2) == std::vector<int>{1, 1, 1, 2, 2, 2, 2, 3, 3});
  // a speed that is not a divisor: 0.4 h/s at 1 fps over [0, 2] -> floor(5) + 1 = 6 frames at 0, 0.4, ... 2.0 h
  CHECK(movieFrames(t, 0.0, 2.0, 0.4, 1) == std::vector<int>{0, 1, 2, 2, 3, 4});
  // the window's own first and last snapshots are the span, not the flags
  CHECK(movieFrames(t, 0.3, 1.7, 0.5, 1) == std::vector<int>{1, 2, 3});
}

TEST_CASE("stills: a still is the movie's frame with the same flags pixel for pixel and --final-png is its last frame") {
  const fs::path d = rtest::scratch("stills");
  const TinyRun r = tinyRun(d);
  const std::string rd = r.dir.string();
  // every look flag, in four groups
  const std::vector<std::string> looks = {
      " --size 320x180",
      " --size 320x240 --camera follow --field-mm 1.5 --color-by twist --whiskers",
      " --size 480x270 --view 3d --inset --plot theta_tip,Tw --shadows",
      " --size 256x256 --camera follow --transparent --no-overlays",
  };
  for (std::size_t li = 0; li < looks.size(); ++li) {
    const std::string& look = looks[li];
    CAPTURE(look);
    const fs::path frames = d / ("frames" + std::to_string(li));
    const Result movie = run("render " + rd + look + " --quiet --png-dir " + frames.string());
    REQUIRE_MESSAGE(movie.code == 0, movie.out);
    for (int k : {0, 3, 7, 10}) {
      CAPTURE(k);
      const fs::path atH = d / ("at_" + std::to_string(li) + "_" + std::to_string(k) + ".png");
      const fs::path byFrame = d / ("frame_" + std::to_string(li) + "_" + std::to_string(k) + ".png");
      // a time a little after the snapshot: still the nearest
      const double h = r.timesH[static_cast<std::size_t>(k)] + (k < 10 ? 0.2 : 0.0) * (r.timesH[1] - r.timesH[0]);
      const Result s1 = run("render " + rd + look + " --quiet --at-h " + num(h) + " --png " + atH.string());
      REQUIRE_MESSAGE(s1.code == 0, s1.out);
      const Result s2 = run("render " + rd + look + " --quiet --frame " + std::to_string(k) + " --png " + byFrame.string());
      REQUIRE_MESSAGE(s2.code == 0, s2.out);
      const Image want = readPng((frames / frameName(k)).string());
      const Image got = readPng(atH.string());
      REQUIRE(got.width == want.width);
      REQUIRE(got.height == want.height);
      CHECK_MESSAGE(got.rgba == want.rgba, "still " << rtest::hash(got) << " movie frame " << rtest::hash(want));
      CHECK(bytes(atH) == bytes(frames / frameName(k)));
      CHECK(bytes(byFrame) == bytes(frames / frameName(k)));
    }
    // the final picture: the movie's last frame, with the same look (alone, and beside a movie)
    const fs::path fin = d / ("final" + std::to_string(li) + ".png");
    const Result f = run("render " + rd + look + " --quiet --final-png " + fin.string());
    REQUIRE_MESSAGE(f.code == 0, f.out);
    CHECK(readPng(fin.string()).rgba == readPng((frames / frameName(10)).string()).rgba);
  }
  // the stills do show different times
  CHECK(readPng((d / "frames1" / frameName(3)).string()).rgba != readPng((d / "frames1" / frameName(7)).string()).rgba);
  // a 3-D follow final picture is not the plain top view any more
  const fs::path plain = d / "plain.png", f3d = d / "f3d.png";
  REQUIRE(run("render " + rd + " --size 320x180 --quiet --final-png " + plain.string()).code == 0);
  REQUIRE(run("render " + rd + " --size 320x180 --view 3d --camera follow --quiet --final-png " + f3d.string()).code == 0);
  CHECK(readPng(plain.string()).rgba != readPng(f3d.string()).rgba);
  // with a window, the still is framed like the windowed movie
  const fs::path wframes = d / "wframes", wstill = d / "wstill.png";
  const double dt = r.timesH[1] - r.timesH[0];
  const std::string win = " --size 320x240 --camera follow --from-h " + num(r.timesH[2] - 0.1 * dt) + " --to-h " +
                          num(r.timesH[8] + 0.1 * dt);
  REQUIRE(run("render " + rd + win + " --quiet --png-dir " + wframes.string()).code == 0);
  const Result ws = run("render " + rd + win + " --quiet --at-h " + num(r.timesH[5]) + " --png " + wstill.string());
  REQUIRE_MESSAGE(ws.code == 0, ws.out);
  CHECK(readPng(wstill.string()).rgba == readPng((wframes / frameName(3)).string()).rgba);
  // a still writes that one file and nothing else (no movie in the run directory)
  CHECK_FALSE(fs::exists(r.dir / "movie.mp4"));
  CHECK_FALSE(fs::exists(r.dir / "final_top.png"));
}

TEST_CASE("stills: --from-h --to-h and --hours-per-second set the frames and the MP4 duration and bad values exit 2") {
  const fs::path d = rtest::scratch("windows");
  const TinyRun r = tinyRun(d);
  const std::string rd = r.dir.string();
  const double dt = r.timesH[1] - r.timesH[0];  // between snapshots [h]
  // the window [t2, t8]: 7 snapshots, one frame each at 10 fps -> 0.7 s
  const std::string win = " --from-h " + num(r.timesH[2] - 0.1 * dt) + " --to-h " + num(r.timesH[8] + 0.1 * dt);
  const Result w = run("render " + rd + " --size 320x180 --fps 10 --quiet" + win + " --mp4 " + (d / "w.mp4").string());
  REQUIRE_MESSAGE(w.code == 0, w.out);
  const rtest::Decoded mw = rtest::decodeMp4((d / "w.mp4").string());
  CHECK(mw.frames == 7);
  CHECK(mw.durationS == doctest::Approx(0.7).epsilon(0.001));
  // fast: 2 snapshot spacings per frame -> the snapshots t2, t4, t6, t8: 4 frames, 0.4 s
  const Result fast = run("render " + rd + " --size 320x180 --fps 10 --quiet" + win + " --hours-per-second " +
                          num(20 * dt) + " --mp4 " + (d / "fast.mp4").string() + " --png-dir " + (d / "fast").string());
  REQUIRE_MESSAGE(fast.code == 0, fast.out);
  const rtest::Decoded mf = rtest::decodeMp4((d / "fast.mp4").string());
  CHECK(mf.frames == 4);
  CHECK(mf.durationS == doctest::Approx(0.4).epsilon(0.001));
  // slow: a quarter of a snapshot spacing per frame: floor(6 * 4) + 1 = 25 frames, 2.5 s; snapshots repeat
  const Result slow = run("render " + rd + " --size 320x180 --fps 10 --quiet" + win + " --hours-per-second " +
                          num(2.5 * dt) + " --mp4 " + (d / "slow.mp4").string() + " --png-dir " + (d / "slow").string());
  REQUIRE_MESSAGE(slow.code == 0, slow.out);
  const rtest::Decoded ms = rtest::decodeMp4((d / "slow.mp4").string());
  CHECK(ms.frames == 25);
  CHECK(ms.durationS == doctest::Approx(2.5).epsilon(0.001));
  // frames 0 and 1 show t2 (t2 and t2 + dt/4), frames 3 and 4 t3 (t2 + 3dt/4, t2 + dt)
  const auto px = [&](const char* dir, int k) { return readPng((d / dir / frameName(k)).string()).rgba; };
  CHECK(px("slow", 0) == px("slow", 1));
  CHECK(px("slow", 1) != px("slow", 3));
  CHECK(px("slow", 3) == px("slow", 4));
  CHECK(px("slow", 21) != px("slow", 24));  // t2 + 5.25 dt is t7
  CHECK(px("slow", 23) == px("slow", 24));  // t2 + 5.75 dt is t8
  CHECK(px("fast", 0) != px("fast", 1));
  // bad values: exit 2, the flag named, nothing written
  struct Bad {
    std::string args, says;
  };
  const std::string mp4 = " --mp4 " + (d / "bad.mp4").string();
  const std::vector<Bad> bad = {
      {" --from-h 1.5 --to-h 0.5" + mp4, "--from-h 1.5: after --to-h 0.5"},
      {" --from-h -1" + mp4, "--from-h -1: expected a finite number in [0, 1e+06] h"},
      {" --to-h -2" + mp4, "--to-h -2: expected a finite number in [0, 1e+06] h"},
      {" --from-h " + num(r.timesH[3] + 0.2 * dt) + " --to-h " + num(r.timesH[3] + 0.6 * dt) + mp4, "no snapshot in"},
      {" --from-h 50" + mp4, "--from-h 50: no snapshot in [50, "},
      {" --hours-per-second 0" + mp4, "--hours-per-second 0: expected a finite number in (0, 1e+06] h/s"},
      {" --hours-per-second -3" + mp4, "--hours-per-second -3: expected a finite number in (0, 1e+06] h/s"},
      {" --hours-per-second nan" + mp4, "--hours-per-second nan: expected a finite number"},
      // the frames a speed makes are counted before they are made (each holds a copy of its snapshot)
      {" --hours-per-second 1e-7" + mp4, "would make "},
      {" --hours-per-second 1e-7" + mp4, "frames, more than the cap of 20000 (caps::kMovieFrames"},
      {" --at-h nan --png " + (d / "bad.png").string(), "--at-h nan: expected a finite number in [0, 1e+06] h"},
      {" --at-h 0 --trace " + std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/rsml/smartroot_pixels.rsml --trace-px-per-mm 1e-300 --png " +
           (d / "bad.png").string(),
       "--trace-px-per-mm 1e-300: expected a finite number in [0.01, 1e+05] px/mm"},
      {" --at-h 50 --png " + (d / "bad.png").string(), "--at-h 50: outside the run's snapshots, 0 .. "},
      {" --at-h 0.1", "--at-h 0.1: writes a still; add --png FILE"},
      {" --png " + (d / "bad.png").string(), "add --at-h H or --frame N"},
      {" --frame 11 --png " + (d / "bad.png").string(), "--frame 11: the movie has frames 0 .. 10"},
      {" --frame 1 --at-h 0.1 --png " + (d / "bad.png").string(), "give --at-h or --frame, not both"},
      {" --at-h 0.1 --png " + (d / "bad.png").string() + mp4, "a still is one picture"},
      {" --at-h 0.1 --hours-per-second 1 --png " + (d / "bad.png").string(), "--hours-per-second 1: paces a movie"},
      {" --from-h " + num(r.timesH[5] - 0.1 * dt) + " --at-h " + num(r.timesH[1]) + " --png " + (d / "bad.png").string(),
       "outside the window's snapshots"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.args);
    const Result res = run("render " + rd + " --size 320x180 --quiet" + b.args);
    CHECK(res.code == 2);
    CHECK_MESSAGE(res.out.find(b.says) != std::string::npos, res.out);
  }
  CHECK_FALSE(fs::exists(d / "bad.mp4"));
  CHECK_FALSE(fs::exists(d / "bad.png"));
  // the write rule: a still never replaces a user's file, and its own only with --force
  const fs::path mine = d / "mine.png";
  { std::ofstream(mine) << "my picture"; }
  const Result refused = run("render " + rd + " --size 320x180 --quiet --frame 2 --png " + mine.string() + " --force");
  CHECK(refused.code == 2);
  CHECK(refused.out.find("--png") != std::string::npos);
  CHECK(bytes(mine) == "my picture");
  const fs::path ours = d / "ours.png";
  REQUIRE(run("render " + rd + " --size 320x180 --quiet --frame 2 --png " + ours.string()).code == 0);
  const Result again = run("render " + rd + " --size 320x180 --quiet --frame 3 --png " + ours.string());
  CHECK(again.code == 2);
  CHECK(again.out.find("--force") != std::string::npos);
  REQUIRE(run("render " + rd + " --size 320x180 --quiet --frame 3 --png " + ours.string() + " --force").code == 0);
}

TEST_CASE("stills: run --movie defaults to the inset look and its final_top.png is the movie's last frame") {
  const fs::path d = rtest::scratch("first_picture");
  const std::string scene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
  // about 9 mm of root: its tube under 24 px wide in the fit view, so the inset magnifies it
  const std::string base = " --set growth.steps=800 --set output.every_steps=200 --quiet --movie --out ";
  const fs::path r1 = d / "default", r2 = d / "fit";
  const Result a = run("run " + scene + base + r1.string());
  REQUIRE_MESSAGE(a.code == 0, a.out);
  const Result b = run("run " + scene + base + r2.string() + " --camera fit");
  REQUIRE_MESSAGE(b.code == 0, b.out);
  CHECK(rtest::decodeMp4((r1 / "movie.mp4").string()).frames == 5);
  // the default is render --inset, the explicit fit is render's own default
  const fs::path inset = d / "inset.png", plain = d / "plain.png", frames = d / "frames";
  REQUIRE(run("render " + r1.string() + " --inset --quiet --final-png " + inset.string() + " --png-dir " +
              frames.string()).code == 0);
  REQUIRE(run("render " + r1.string() + " --quiet --final-png " + plain.string()).code == 0);
  const Image def = readPng((r1 / "final_top.png").string());
  CHECK(def.rgba == readPng(inset.string()).rgba);
  CHECK(def.rgba == readPng((frames / frameName(4)).string()).rgba);
  CHECK(def.rgba != readPng(plain.string()).rgba);
  CHECK(readPng((r2 / "final_top.png").string()).rgba == readPng(plain.string()).rgba);
  // the inset's frame (the look's blue, 0 110 230) is there in the default picture, not in the plain one
  auto blue = [](const Image& img) {
    long n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = img.at(x, y);
        n += p[0] < 20 && p[1] > 90 && p[1] < 130 && p[2] > 210;
      }
    return n;
  };
  CHECK(blue(def) > 1000);
  CHECK(blue(readPng(plain.string())) == 0);
}

TEST_CASE("stills: run --movie --field-mm alone sizes the default inset - and without --movie or with --camera fit it is refused") {
  const fs::path d = rtest::scratch("field_inset");
  const std::string scene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
  // about 9 mm of root, as above: the 2 mm window is narrowed to magnify twice, 1.2 mm is kept
  const std::string base = " --set growth.steps=800 --set output.every_steps=200 --quiet";
  const fs::path r1 = d / "field";
  const Result a = run("run " + scene + base + " --movie --field-mm 1.2 --out " + r1.string());
  REQUIRE_MESSAGE(a.code == 0, a.out);
  // the picture is render --inset --field-mm 1.2's, not the 2 mm inset's
  const fs::path small = d / "small.png", wide = d / "wide.png";
  REQUIRE(run("render " + r1.string() + " --inset --field-mm 1.2 --quiet --final-png " + small.string()).code == 0);
  REQUIRE(run("render " + r1.string() + " --inset --quiet --final-png " + wide.string()).code == 0);
  const Image def = readPng((r1 / "final_top.png").string());
  CHECK(def.rgba == readPng(small.string()).rgba);
  CHECK(def.rgba != readPng(wide.string()).rgba);
  // refused before the run: nothing written, the flag named, one line
  const fs::path r2 = d / "refused";
  for (const std::string& args : {base + " --field-mm 1.2", base + " --movie --camera fit --field-mm 1.2",
                                  base + " --movie --field-mm 500"}) {
    const Result r = run("run " + scene + args + " --out " + r2.string());
    INFO(args << " -> " << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find("--field-mm") != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(r2));
  }
}

TEST_CASE("stills: --trace draws the traced root over the picture / its own export lies on the root, a turned one beside it") {
  const fs::path d = rtest::scratch("trace");
  const TinyRun t = tinyRun(d);
  const fs::path own = d / "own.rsml";
  REQUIRE(run("export " + t.dir.string() + " --rsml " + own.string() + " --quiet").code == 0);
  // the trace's ink (render_scene.cpp kTraceInk)
  auto ink = [](const Image& img, int& minX, int& maxX) {
    int n = 0;
    minX = img.width;
    maxX = -1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = &img.rgba[4 * (static_cast<std::size_t>(y) * img.width + x)];
        if (std::abs(p[0] - 13) < 12 && std::abs(p[1] - 51) < 12 && std::abs(p[2] - 140) < 12) {
          ++n;
          minX = std::min(minX, x);
          maxX = std::max(maxX, x);
        }
      }
    return n;
  };
  const fs::path plain = d / "plain.png", traced = d / "traced.png", turned = d / "turned.png";
  const std::string still = " --size 640x360 --at-h 2 --quiet --png ";
  REQUIRE(run("render " + t.dir.string() + still + plain.string()).code == 0);
  const Result r = run("render " + t.dir.string() + " --trace " + own.string() + still + traced.string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  int x0 = 0, x1 = 0;
  CHECK(ink(readPng(plain.string()), x0, x1) == 0);
  const Image a = readPng(traced.string());
  const int onRoot = ink(a, x0, x1);
  CHECK(onRoot > 100);  // the line, and the legend's swatch
  // the same trace turned by 90 degrees (--trace-downhill 90: its +x is downhill) lies across the plate
  const Result r2 = run("render " + t.dir.string() + " --trace " + own.string() + " --trace-downhill 90" + still + turned.string());
  REQUIRE_MESSAGE(r2.code == 0, r2.out);
  int y0 = 0, y1 = 0;
  CHECK(ink(readPng(turned.string()), y0, y1) > 100);
  CHECK(readPng(turned.string()).rgba != a.rgba);
  // its flags without --trace, and a bad one, exit 2 naming them
  const Result bad = run("render " + t.dir.string() + " --trace-root 1" + still + (d / "x.png").string());
  CHECK(bad.code == 2);
  CHECK(bad.out.find("give --trace") != std::string::npos);
  const Result badRoot = run("render " + t.dir.string() + " --trace " + own.string() + " --trace-root 7" + still + (d / "x.png").string());
  CHECK(badRoot.code == 2);
  CHECK(badRoot.out.find("--trace-root 7: no such root") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "x.png"));
}

TEST_CASE("stills: a 2D+t trace drawn with --trace grows with the frames / the root as it was at the frame's time") {
  const fs::path d = rtest::scratch("trace_lapse");
  const TinyRun t = tinyRun(d);
  // RootSystemTracker's 2D+t: a straight root reaching 0.5 mm at 1 h and 1 mm at 2 h (50 um pixels)
  const fs::path lapse = d / "lapse.rsml";
  {
    std::ofstream f(lapse);
    f << "<rsml><metadata><unit>pixel(um)</unit><size>50</size><observation-hours>1,2</observation-hours></metadata>"
         "<scene><plant ID=\"1\"><root ID=\"1.1\"><geometry><polyline>"
         "<point coord_x=\"0\" coord_y=\"0\" coord_t=\"0\" coord_th=\"0\"/>"
         "<point coord_x=\"0\" coord_y=\"10\" coord_t=\"1\" coord_th=\"1\"/>"
         "<point coord_x=\"0\" coord_y=\"20\" coord_t=\"2\" coord_th=\"2\"/>"
         "</polyline></geometry></root></plant></scene></rsml>\n";
  }
  // the rows of the trace's ink below the legend (the frame's top 85 %)
  auto inkRows = [](const Image& img) {
    int rows = 0;
    for (int y = 0; y < img.height * 85 / 100; ++y) {
      bool any = false;
      for (int x = 0; x < img.width && !any; ++x) {
        const std::uint8_t* p = &img.rgba[4 * (static_cast<std::size_t>(y) * img.width + x)];
        any = std::abs(p[0] - 13) < 12 && std::abs(p[1] - 51) < 12 && std::abs(p[2] - 140) < 12;
      }
      rows += any;
    }
    return rows;
  };
  std::vector<int> rows;
  for (const char* h : {"0.6", "1.2", "2"}) {
    const fs::path png = d / (std::string("at_") + h + ".png");
    const Result r = run("render " + t.dir.string() + " --trace " + lapse.string() + " --size 360x640 --quiet --at-h " + h + " --png " + png.string());
    REQUIRE_MESSAGE(r.code == 0, r.out);
    rows.push_back(inkRows(readPng(png.string())));
  }
  // 0.3, 0.6 and 1 mm of trace: the line grows, in proportion
  CHECK(rows[0] > 0);
  CHECK(rows[0] < rows[1]);
  CHECK(rows[1] < rows[2]);
  CHECK(static_cast<double>(rows[1]) / rows[2] == doctest::Approx(0.6).epsilon(0.15));
}

TEST_CASE("stills: a plate's run draws every root, and --scan is the plate at PX px/mm with the roots where they are sown") {
  const fs::path d = rootsim::test::scratchDir("stills", "plate");
  // the collision scene, coarsened: two seedlings on a 40 x 40 mm plate at [20, 5] and [23, 7] mm
  const Result ran = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                         "/scenes/plate_collision.toml --set growth.steps=60 --quiet --out " + (d / "plate").string());
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  const Result scan = run("render " + (d / "plate").string() + " --scan 10 --png " + (d / "scan.png").string() + " --quiet");
  REQUIRE_MESSAGE(scan.code == 0, scan.out);
  const Image img = readPng((d / "scan.png").string());
  CHECK(img.width == 400);   // 40 mm at 10 px/mm
  CHECK(img.height == 400);
  auto lum = [&](double lateralMm, double downhillMm) {
    const int x = static_cast<int>(lateralMm * 10), y = static_cast<int>(downhillMm * 10);
    const std::uint8_t* p = &img.rgba[4 * (static_cast<size_t>(y) * img.width + static_cast<size_t>(x))];
    return (p[0] + p[1] + p[2]) / 3;
  };
  // light roots: "down" from [20, 5] straight downhill, "across" from [23, 7] towards -lateral; dark plate
  CHECK(lum(20.0, 5.6) > 150);
  CHECK(lum(22.4, 7.0) > 150);
  CHECK(lum(10.0, 30.0) < 30);
  CHECK(lum(30.0, 20.0) < 30);
  // the plate view and --root; errors name the flag
  CHECK(run("render " + (d / "plate").string() + " --plate-view --png " + (d / "view.png").string() + " --at-h 3 --quiet").code == 0);
  CHECK(readPng((d / "view.png").string()).width == 1080);
  // the plate view frames the sown area: its roots span more of the picture than on the whole plate; its
  // still without --at-h is the last snapshot, as --scan's is
  CHECK(run("render " + (d / "plate").string() + " --plate-view --png " + (d / "sown.png").string() + " --quiet").code == 0);
  CHECK(run("render " + (d / "plate").string() + " --plate-view --whole-plate --png " + (d / "whole.png").string() + " --quiet").code == 0);
  // 60 steps of 0.05 h: the last snapshot is the one at 3 h
  const Image sown = readPng((d / "sown.png").string()), last = readPng((d / "view.png").string()),
              whole = readPng((d / "whole.png").string());
  CHECK(sown.rgba == last.rgba);
  // root pixels (the stripes: warm and saturated), above the legend (its swatches have the stripes'
  // colours; on the whole plate it lies inside the outline, at about 0.87 of the height) and below the
  // time; the roots are sown near the plate's top
  auto rootSpan = [](const Image& im) {
    int x0 = im.width, x1 = -1;
    for (int y = im.height * 12 / 100; y < im.height * 82 / 100; ++y)
      for (int x = 0; x < im.width; ++x) {
        const std::uint8_t* q = im.at(x, y);
        if (q[0] > 200 && q[0] > q[2] + 40) x0 = std::min(x0, x), x1 = std::max(x1, x);
      }
    return x1 >= x0 ? static_cast<double>(x1 - x0 + 1) / im.width : 0.0;
  };
  INFO("root span: sown area " << rootSpan(sown) << ", whole plate " << rootSpan(whole));
  CHECK(rootSpan(sown) > 2.0 * rootSpan(whole));
  CHECK(rootSpan(sown) > 0.25);
  const Result noView = run("render " + (d / "plate").string() + " --whole-plate --png " + (d / "z.png").string() + " --at-h 3");
  CHECK(noView.code == 2);
  CHECK(noView.out.find("--whole-plate: ") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "z.png"));
  CHECK(run("render " + (d / "plate").string() + " --root down --camera follow --png " + (d / "follow.png").string() +
            " --at-h 3 --quiet").code == 0);
  const Result noRoot = run("render " + (d / "plate").string() + " --root sideways --png " + (d / "x.png").string() + " --at-h 3");
  CHECK(noRoot.code == 2);
  CHECK(noRoot.out.find("--root sideways: ") != std::string::npos);
  CHECK(noRoot.out.find("(its roots: down, across)") != std::string::npos);
  const Result noPng = run("render " + (d / "plate").string() + " --scan 10");
  CHECK(noPng.code == 2);
  CHECK(noPng.out.find("add --png FILE") != std::string::npos);
  // a run of one root has no plate to scan, and each root's folder is a run of one root
  const Result one = run("render " + (d / "plate" / "roots" / "down").string() + " --scan 10 --png " + (d / "y.png").string());
  CHECK(one.code == 2);
  CHECK(one.out.find("a run of one root") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "x.png"));
  CHECK_FALSE(fs::exists(d / "y.png"));
}
