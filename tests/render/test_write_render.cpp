// The write rule (write_rule.hpp) where pictures are drawn: a movie, a picture or a frame folder that
// rootsim wrote is replaced only with --force, a frame folder is replaced whole (old frames never mix
// with new ones), and every PNG and MP4 rootsim writes carries its signature. The refusals that need no
// drawing are in tests/test_write_rule.cpp.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.hpp"

namespace fs = std::filesystem;

namespace {

using rootsim::test::Result;
using rootsim::test::slurp;

using rootsim::test::run;

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("write_render", name); }

const std::string kScene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";

// a run of `steps` growth steps with a snapshot every 10: steps / 10 + 1 frames
fs::path makeRun(const fs::path& d, const std::string& name, int steps) {
  const fs::path r = d / name;
  const Result res = run("run " + kScene + " --set growth.steps=" + std::to_string(steps) +
                             " --set root.element_length_mm=0.1 --set output.every_steps=10 --quiet --out " + r.string());
  REQUIRE(res.code == 0);
  return r;
}

int frames(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".png";
  return n;
}

}  // namespace

TEST_CASE("every PNG and MP4 rootsim writes carries its signature (what lets --force replace it later)") {
  const fs::path d = scratch("signature");
  const fs::path r = makeRun(d, "r", 20);
  REQUIRE(run("render " + r.string() + " --quiet --size 128x128 --mp4 " + (d / "m.mp4").string() + " --final-png " +
                  (d / "p.png").string()).code == 0);
  CHECK(slurp(d / "m.mp4").find("rootsim-output rootsim ") != std::string::npos);
  // PNG: the tEXt chunk "Software" after the image data (png_encode.hpp), then IEND (its 12 bytes)
  const std::string png = slurp(d / "p.png");
  const auto sig = png.find(std::string("tEXtSoftware") + '\0' + "rootsim-output rootsim ");
  REQUIRE(sig != std::string::npos);
  CHECK(sig > png.rfind("IDAT"));
  CHECK(png.compare(png.size() - 8, 4, "IEND") == 0);
  fs::remove_all(d);
}

TEST_CASE("render and montage: a movie or picture rootsim wrote is replaced only with --force") {
  const fs::path d = scratch("again");
  const fs::path r = makeRun(d, "r", 20);
  const std::string out = " --quiet --size 128x128 --mp4 " + (d / "m.mp4").string() + " --final-png " + (d / "p.png").string();
  REQUIRE(run("render " + r.string() + out).code == 0);
  const std::string mp4 = slurp(d / "m.mp4");
  Result again = run("render " + r.string() + out);
  CHECK(again.code == 2);
  CHECK(again.out.find("written by rootsim earlier); pass --force") != std::string::npos);
  again = run("render " + r.string() + out + " --force");
  CHECK(again.code == 0);
  CHECK(slurp(d / "m.mp4") == mp4);  // same run, same bytes
  // montage over the same movie
  CHECK(run("montage " + r.string() + " --quiet --size 128x128 --mp4 " + (d / "m.mp4").string()).code == 2);
  CHECK(run("montage " + r.string() + " --quiet --size 128x128 --force --mp4 " + (d / "m.mp4").string()).code == 0);
  // the run directory's own movie and picture (render RUN with no output flag): the same rule
  REQUIRE(run("render " + r.string() + " --quiet --size 128x128").code == 0);
  CHECK(fs::exists(r / "movie.mp4"));
  CHECK(run("render " + r.string() + " --quiet --size 128x128").code == 2);
  CHECK(run("render " + r.string() + " --quiet --size 128x128 --force").code == 0);
  fs::remove_all(d);
}

TEST_CASE("--png-dir: rootsim's earlier frames are replaced whole (21 old frames never mix with 6 new ones)") {
  const fs::path d = scratch("frames");
  const fs::path longRun = makeRun(d, "long", 200), shortRun = makeRun(d, "short", 50);
  const fs::path f = d / "frames";
  REQUIRE(run("render " + longRun.string() + " --quiet --size 128x128 --png-dir " + f.string()).code == 0);
  CHECK(frames(f) == 21);
  CHECK(fs::exists(f / ".rootsim-frames"));
  const Result refused = run("render " + shortRun.string() + " --quiet --size 128x128 --png-dir " + f.string());
  CHECK(refused.code == 2);
  CHECK(frames(f) == 21);
  REQUIRE(run("render " + shortRun.string() + " --quiet --size 128x128 --force --png-dir " + f.string()).code == 0);
  CHECK(frames(f) == 6);
  CHECK(!fs::exists(f / "frame_00006.png"));
  CHECK(!fs::exists(fs::path(f.string() + ".partial")));
  CHECK(!fs::exists(fs::path(f.string() + ".replaced")));
  // montage writes frame folders the same way
  REQUIRE(run("montage " + longRun.string() + " " + shortRun.string() + " --quiet --size 128x128 --force --png-dir " +
                  f.string()).code == 0);
  CHECK(frames(f) == 21);
  fs::remove_all(d);
}

TEST_CASE("figure: its own panels are replaced only with --force") {
  const fs::path d = scratch("figure");
  const std::string args = "figure fig2b --quick --quiet --out " + (d / "figs").string();
  REQUIRE(run(args).code == 0);
  CHECK(fs::exists(d / "figs" / "fig2b.png"));
  CHECK(fs::exists(d / "figs" / ".rootsim-figures"));
  const Result again = run(args);
  CHECK(again.code == 2);
  CHECK(again.out.find("holds fig2b.png from an earlier `rootsim figure`; pass --force") != std::string::npos);
  CHECK(run(args + " --force").code == 0);
  // a user's file dropped into it makes it no longer rootsim's alone
  std::ofstream(d / "figs" / "notes.txt") << "mine";
  CHECK(run(args + " --force").code == 2);
  CHECK(slurp(d / "figs" / "notes.txt") == "mine");
  fs::remove_all(d);
}
