// PNG and MP4 files (src/render/png.cpp, video_writer.cpp, movie.cpp) and `rootsim render`
// (src/app/render_run.cpp): read back independently, frame counts, sizes, durations, errors
#include <doctest/doctest.h>

#include "../test_support.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "render_test_util.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/png.hpp"
#include "rootsim/video_writer.hpp"

namespace fs = std::filesystem;
using namespace rootsim;

namespace {

// left half red, right half blue, a white square in the middle; alpha 255
Image testCard(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      const bool centre = std::abs(x - w / 2) < w / 8 && std::abs(y - h / 2) < h / 8;
      p[0] = centre || x < w / 2 ? 255 : 0;
      p[1] = centre ? 255 : 0;
      p[2] = centre || x >= w / 2 ? 255 : 0;
      p[3] = 255;
    }
  return img;
}

// growing, twisting rods: one snapshot per frame
std::vector<Snapshot> growingRod(int frames) {
  std::vector<Snapshot> v;
  for (int k = 0; k < frames; ++k) {
    Snapshot s = rtest::straightRod(40, 20, 1.0 + 0.1 * k, 0.1, [k](double sMm) { return 0.3 * k * sMm; });
    s.step = 10 * k;
    s.timeH = 0.5 * k;
    v.push_back(std::move(s));
  }
  return v;
}

using rootsim::test::Result;
using rootsim::test::run;

}  // namespace

TEST_CASE("PNG round trip is lossless, the write atomic, errors name the path") {
  const fs::path d = rtest::scratch("png");
  Image img = testCard(97, 41);  // odd sizes are fine for PNG
  img.at(3, 3)[3] = 17;          // and alpha survives
  const std::string path = (d / "card.png").string();
  writePng(path, img);
  const Image back = readPng(path);
  CHECK(back.width == 97);
  CHECK(back.height == 41);
  CHECK(back.rgba == img.rgba);
  // nothing else left beside it
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++files;
  CHECK(files == 1);
  CHECK_THROWS_WITH_AS(writePng((d / "no" / "such" / "dir.png").string(), img), doctest::Contains("no/such/dir.png"),
                       RenderError);
  CHECK_THROWS_WITH_AS(readPng((d / "missing.png").string()), doctest::Contains("missing.png"), RenderError);
  CHECK_THROWS_AS(writePng(path, Image()), RenderError);
}

TEST_CASE("MP4: frame count, size, duration, yuv420p BT.709, colours survive") {
  const fs::path d = rtest::scratch("mp4");
  const std::string path = (d / "card.mp4").string();
  VideoOptions o;
  o.fps = 24;
  o.crf = 18;
  {
    VideoWriter w(path, 320, 240, o);
    const Image card = testCard(320, 240);
    for (int i = 0; i < 36; ++i) w.add(card);
    CHECK(w.frames() == 36);
    CHECK(fs::exists(path + ".partial"));
    CHECK_FALSE(fs::exists(path));
    w.finish();
    w.finish();  // idempotent
  }
  CHECK(fs::exists(path));
  CHECK_FALSE(fs::exists(path + ".partial"));
  const rtest::Decoded m = rtest::decodeMp4(path);
  CHECK(m.codec == "h264");
  CHECK(m.pixFmt == "yuv420p");
  CHECK(m.width == 320);
  CHECK(m.height == 240);
  CHECK(m.frames == 36);
  CHECK(m.durationS == doctest::Approx(1.5).epsilon(0.001));  // 36 frames / 24 fps, not one frame short
  CHECK(m.colorspace == 1);                                    // AVCOL_SPC_BT709
  // decoded with the tagged matrix, the colours come back
  auto near = [](const std::uint8_t* p, int r, int g, int b) {
    return std::abs(p[0] - r) <= 12 && std::abs(p[1] - g) <= 12 && std::abs(p[2] - b) <= 12;
  };
  CHECK(near(m.first.at(40, 40), 255, 0, 0));
  CHECK(near(m.first.at(280, 200), 0, 0, 255));
  CHECK(near(m.first.at(160, 120), 255, 255, 255));
}

TEST_CASE("MP4: odd or zero sizes, wrong frame sizes and unwritable paths are clear errors") {
  const fs::path d = rtest::scratch("mp4err");
  const std::string path = (d / "x.mp4").string();
  CHECK_THROWS_WITH_AS(VideoWriter(path, 321, 240), doctest::Contains("must be positive and even"), RenderError);
  CHECK_THROWS_WITH_AS(VideoWriter(path, 320, 241), doctest::Contains("320x241"), RenderError);
  CHECK_THROWS_WITH_AS(VideoWriter(path, 0, 0), doctest::Contains("even"), RenderError);
  CHECK_FALSE(fs::exists(path + ".partial"));
  CHECK_THROWS_WITH_AS(VideoWriter((d / "no" / "x.mp4").string(), 320, 240), doctest::Contains("no/x.mp4"), RenderError);
  VideoWriter w(path, 320, 240);
  CHECK_THROWS_WITH_AS(w.add(testCard(160, 120)), doctest::Contains("160x120"), RenderError);
}

TEST_CASE("a writer dropped without finish() leaves a playable .partial") {
  const fs::path d = rtest::scratch("partial");
  const std::string path = (d / "cut.mp4").string();
  {
    VideoWriter w(path, 160, 120);
    for (int i = 0; i < 5; ++i) w.add(testCard(160, 120));
  }
  CHECK_FALSE(fs::exists(path));
  REQUIRE(fs::exists(path + ".partial"));
  CHECK(rtest::decodeMp4(path + ".partial").frames == 5);
}

TEST_CASE("movie: every snapshot one frame, PNG frames, final picture, one framing") {
  const fs::path d = rtest::scratch("movie");
  const std::vector<Snapshot> snaps = growingRod(12);
  MovieJob job;
  job.mp4 = (d / "m.mp4").string();
  job.pngDir = (d / "frames").string();
  job.finalPng = (d / "final.png").string();
  job.view.width = 320;
  job.view.height = 180;
  job.video.fps = 12;
  int calls = 0, lastDone = 0;
  renderMovie(snaps, rtest::info(40), job, [&](int done, int total) {
    ++calls;
    lastDone = done;
    CHECK(total == 12);
  });
  CHECK(calls == 12);
  CHECK(lastDone == 12);
  const rtest::Decoded m = rtest::decodeMp4(job.mp4);
  CHECK(m.frames == 12);
  CHECK(m.width == 320);
  CHECK(m.height == 180);
  CHECK(m.durationS == doctest::Approx(1.0).epsilon(0.001));
  for (int k = 0; k < 12; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", k);
    CHECK(fs::exists(d / "frames" / name));
  }
  // the final picture is the last frame
  CHECK(readPng(job.finalPng).rgba == readPng((d / "frames" / "frame_00011.png").string()).rgba);
  // one framing for the whole movie: the base of the root stays on the same pixel row
  auto topRow = [](const Image& img) {
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = img.at(x, y);
        if (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 60) return y;  // a stripe
      }
    return -1;
  };
  const int first = topRow(readPng((d / "frames" / "frame_00000.png").string()));
  CHECK(first > 0);
  CHECK(first == topRow(readPng(job.finalPng)));
}

TEST_CASE("movie errors: transparent MP4, PNG folder that is a file, encoder errors surface") {
  const fs::path d = rtest::scratch("movieerr");
  const std::vector<Snapshot> snaps = growingRod(2);
  MovieJob job;
  job.view.width = 160;
  job.view.height = 90;
  job.mp4 = (d / "t.mp4").string();
  job.view.transparent = true;
  CHECK_THROWS_WITH_AS(renderMovie(snaps, rtest::info(40), job), doctest::Contains("PNG only"), RenderError);
  job.view.transparent = false;
  job.mp4.clear();
  std::ofstream((d / "file").string()) << "x";
  job.pngDir = (d / "file").string();
  CHECK_THROWS_WITH_AS(renderMovie(snaps, rtest::info(40), job), doctest::Contains("PNG folder"), RenderError);
  job.pngDir.clear();
  job.view.width = 161;  // odd: refused by the video writer before any drawing
  job.mp4 = (d / "odd.mp4").string();
  CHECK_THROWS_WITH_AS(renderMovie(snaps, rtest::info(40), job), doctest::Contains("even"), RenderError);
}

TEST_CASE("rootsim render on a tiny run: movie.mp4 with one frame per snapshot, final_top.png") {
  const fs::path d = rtest::scratch("cli");
  const std::string runDir = (d / "run").string();
  const Result ran = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                         "/scenes/fig2b_waving.toml --set growth.steps=40 --set output.every_steps=4 "
                         "--set output.trajectory_format=csv --quiet --out " + runDir);
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  // asked for explicitly: the run directory's own files, plus frames elsewhere
  const Result rendered = run("render " + runDir + " --size 320x180 --fps 10 --mp4 " + runDir + "/movie.mp4 --final-png " +
                              runDir + "/final_top.png --png-dir " + (d / "frames").string());
  REQUIRE_MESSAGE(rendered.code == 0, rendered.out);
  CHECK(rendered.out.find("(100 %)") != std::string::npos);  // progress lines
  const rtest::Decoded m = rtest::decodeMp4(runDir + "/movie.mp4");
  CHECK(m.frames == 11);  // steps 0, 4, ..., 40
  CHECK(m.width == 320);
  CHECK(m.height == 180);
  CHECK(m.durationS == doctest::Approx(1.1).epsilon(0.001));
  const Image top = readPng(runDir + "/final_top.png");
  CHECK(top.width == 320);
  CHECK(top.height == 180);
  CHECK(fs::exists(d / "frames" / "frame_00010.png"));

  SUBCASE("--view 3d renders the movie; --quiet prints nothing") {
    const Result r3 = run("render " + runDir + " --view 3d --size 320x180 --quiet --mp4 " + (d / "3d.mp4").string());
    REQUIRE_MESSAGE(r3.code == 0, r3.out);
    CHECK(r3.out.empty());
    CHECK(rtest::decodeMp4((d / "3d.mp4").string()).frames == 11);
  }
  SUBCASE("rootsim run --movie renders after the run") {
    const std::string dir2 = (d / "run2").string();
    const Result rm = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                          "/scenes/fig2b_waving.toml --set growth.steps=20 --set output.every_steps=4 --quiet --movie --out " +
                          dir2);
    REQUIRE_MESSAGE(rm.code == 0, rm.out);
    const rtest::Decoded mm = rtest::decodeMp4(dir2 + "/movie.mp4");
    CHECK(mm.frames == 6);
    // size auto: a root that grows straight downhill gets a portrait frame
    CHECK(mm.width == 720);
    CHECK(mm.height == 1280);
    CHECK(readPng(dir2 + "/final_top.png").width == 720);
  }
  SUBCASE("--transparent writes PNG frames with alpha and no movie; --whiskers and --no-overlays render") {
    const Result rt = run("render " + runDir + " --transparent --size 320x180 --quiet --png-dir " + (d / "tframes").string());
    REQUIRE_MESSAGE(rt.code == 0, rt.out);
    const Image t = readPng((d / "tframes" / "frame_00010.png").string());
    CHECK(t.at(2, 2)[3] == 0);  // a corner: no plate, transparent
    const Result bad = run("render " + runDir + " --transparent --quiet");
    CHECK(bad.code == 2);
    CHECK(bad.out.find("--transparent") != std::string::npos);
    const Result rw = run("render " + runDir + " --whiskers --no-overlays --size 320x180 --quiet --mp4 " +
                          (d / "w.mp4").string());
    REQUIRE_MESSAGE(rw.code == 0, rw.out);
    CHECK(rtest::decodeMp4((d / "w.mp4").string()).frames == 11);
    const Result rs = run("render " + runDir + " --size 320x180 --quiet --shader-dir " + std::string(ROOTSIM_SOURCE_DIR) +
                          "/shaders --mp4 " + (d / "s.mp4").string());
    REQUIRE_MESSAGE(rs.code == 0, rs.out);
    const Result rbad = run("render " + runDir + " --quiet --shader-dir " + (d / "nowhere").string());
    CHECK(rbad.code == 2);
    CHECK(rbad.out.find("--shader-dir") != std::string::npos);
  }
  SUBCASE("render to another path leaves every byte of the run directory as it was") {
    // every file of the run directory, path -> contents
    auto contents = [](const fs::path& dir) {
      std::map<std::string, std::string> files;
      for (const auto& e : fs::recursive_directory_iterator(dir)) {
        std::ifstream in(e.path(), std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        files[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? ss.str() : std::string("<dir>");
      }
      return files;
    };
    const auto before = contents(runDir);
    const Result r1 = run("render " + runDir + " --size 320x180 --quiet --mp4 " + (d / "elsewhere.mp4").string());
    REQUIRE_MESSAGE(r1.code == 0, r1.out);
    const Result r2 = run("render " + runDir + " --view 3d --size 320x180 --quiet --png-dir " + (d / "pngs").string() +
                          " --final-png " + (d / "last.png").string());
    REQUIRE_MESSAGE(r2.code == 0, r2.out);
    CHECK(contents(runDir) == before);
    CHECK(rtest::decodeMp4((d / "elsewhere.mp4").string()).frames == 11);
    CHECK(fs::exists(d / "pngs" / "frame_00010.png"));
    // the final picture is the movie's last frame, in the movie's look (here the 3-D view)
    CHECK(readPng((d / "last.png").string()).rgba == readPng((d / "pngs" / "frame_00010.png").string()).rgba);
    // no output flag at all: the run directory's movie.mp4 and final_top.png, nothing else
    fs::remove(runDir + "/movie.mp4");
    fs::remove(runDir + "/final_top.png");
    const Result r3 = run("render " + runDir + " --size 320x180 --quiet");
    REQUIRE_MESSAGE(r3.code == 0, r3.out);
    const auto after = contents(runDir);
    CHECK(after.size() == before.size());
    CHECK(after.at("final_top.png") == before.at("final_top.png"));
  }
  SUBCASE("bad input exits 2 naming the flag or the file") {
    const Result odd = run("render " + runDir + " --size 321x180");
    CHECK(odd.code == 2);
    CHECK(odd.out.find("--size 321x180") != std::string::npos);
    CHECK(odd.out.find("even") != std::string::npos);
    const Result junk = run("render " + runDir + " --size big");
    CHECK(junk.code == 2);
    CHECK(junk.out.find("--size big") != std::string::npos);
    const Result tiny = run("render " + runDir + " --size 16x16");
    CHECK(tiny.code == 2);
    const Result missing = run("render " + (d / "nothing").string());
    CHECK(missing.code == 2);
    CHECK(missing.out.find("run directory not found") != std::string::npos);
    // a malformed trajectory: the error names the file and the line
    fs::copy(runDir, d / "broken", fs::copy_options::recursive);
    {
      std::ifstream in(d / "broken" / "trajectory.csv");
      std::stringstream ss;
      ss << in.rdbuf();
      std::string text = ss.str();
      const std::size_t line3 = text.find('\n', text.find('\n') + 1);
      text.insert(line3 + 1, "1,2,oops\n");
      std::ofstream(d / "broken" / "trajectory.csv") << text;
    }
    const Result broken = run("render " + (d / "broken").string() + " --quiet");
    CHECK(broken.code == 2);
    CHECK(broken.out.find("trajectory.csv:") != std::string::npos);
  }
}

TEST_CASE("movie looks on the command line (follow, colour, plots, inset, shadows, montage) and bad options that exit 2 and write nothing") {
  const fs::path d = rtest::scratch("looks");
  const std::string scene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
  const std::string runDir = (d / "run").string();
  const Result ran = run("run " + scene + " --set growth.steps=40 --set output.every_steps=8 --quiet --out " + runDir);
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  // every look at once, 720p: one frame per snapshot
  const Result all = run("render " + runDir + " --camera follow --field-mm 2 --color-by twist --plot theta_tip,Eb,Et,Wr,Tw "
                         "--shadows --size 1280x720 --quiet --mp4 " + (d / "all.mp4").string());
  REQUIRE_MESSAGE(all.code == 0, all.out);
  CHECK(rtest::decodeMp4((d / "all.mp4").string()).frames == 6);
  const Result inset = run("render " + runDir + " --inset --color-by contact --size 640x360 --quiet --png-dir " +
                           (d / "inset").string());
  REQUIRE_MESSAGE(inset.code == 0, inset.out);
  CHECK(readPng((d / "inset" / "frame_00005.png").string()).width == 640);
  // run --movie with the follow camera: one flag away
  const std::string run2 = (d / "run2").string();
  const Result rm = run("run " + scene + " --set growth.steps=16 --set output.every_steps=8 --quiet --movie --camera follow --out " + run2);
  REQUIRE_MESSAGE(rm.code == 0, rm.out);
  const rtest::Decoded fm = rtest::decodeMp4(run2 + "/movie.mp4");
  CHECK(fm.frames == 3);
  CHECK(fm.width == 1280);
  CHECK(fs::exists(run2 + "/final_top.png"));
  // a montage of the two runs, frames matched by time: the union of their snapshot times (0, 0.4, 0.8 h,
  // then the longer run's 1.2 ... 2.0 h)
  const Result mo = run("montage " + runDir + " " + run2 + " --size 640x360 --quiet --png-dir " + (d / "mont").string() +
                        " --mp4 " + (d / "mont.mp4").string());
  REQUIRE_MESSAGE(mo.code == 0, mo.out);
  CHECK(rtest::decodeMp4((d / "mont.mp4").string()).frames == 6);
  CHECK(fs::exists(d / "mont" / "frame_00005.png"));

  // bad options: exit 2, the option named, nothing written
  const std::string out = (d / "bad.mp4").string(), pngs = (d / "badpng").string();
  const std::string outputs = " --mp4 " + out + " --png-dir " + pngs;
  // the run directory n times, as montage's arguments
  const auto repeated = [&](int n) {
    std::string a;
    for (int i = 0; i < n; ++i) a += " " + runDir;
    return a;
  };
  const struct {
    std::string args, names;
  } bad[] = {
      {"render " + runDir + " --camera follow --field-mm 0" + outputs, "--field-mm"},
      {"render " + runDir + " --camera follow --field-mm -2" + outputs, "--field-mm"},
      {"render " + runDir + " --camera follow --field-mm 500" + outputs, "larger than the plate"},
      {"render " + runDir + " --inset --field-mm 500" + outputs, "--field-mm"},
      {"render " + runDir + " --camera orbit" + outputs, "--camera orbit"},
      {"render " + runDir + " --color-by colour" + outputs, "--color-by colour"},
      {"render " + runDir + " --plot theta_tip,Ek" + outputs, "--plot"},
      {"render " + runDir + " --plot Eb,Eb" + outputs, "--plot"},
      {"render " + runDir + " --size 3842x2160" + outputs, "--size 3842x2160"},
      {"render " + runDir + " --size 3840x2162" + outputs, "--size"},
      {"render " + runDir + " --camera follow --inset" + outputs, "--inset"},
      {"render " + runDir + " --field-mm 3" + outputs, "--field-mm 3"},
      {"render " + runDir + " --transparent --shadows --png-dir " + pngs, "--transparent"},
      {"render " + runDir + " --transparent --plot Tw --png-dir " + pngs, "--transparent"},
      {"run " + std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2c_free_organ.toml --set growth.steps=4 --movie --shadows --out " +
           (d / "run3").string(), "--shadows"},
      {"montage --size 640x360" + outputs, "no run directories"},
      {"montage " + runDir + " " + (d / "nothing").string() + outputs, "nothing not found"},
      {"montage " + runDir + " --labels a,b" + outputs, "--labels"},
      {"montage " + runDir + " --size 4096x2160" + outputs, "--size"},
      {"montage " + runDir + " --color-by heat" + outputs, "--color-by"},
      {"montage " + runDir, "nothing to write"},
      // more runs than the cap, counted before their snapshots are read; runs whose tiles do not fit the frame
      {"montage" + repeated(65) + outputs, "montage of 65 run directories: would make 65 tiles, more than the cap of 64"},
      {"montage" + repeated(64) + " --size 64x64" + outputs, "--size 64x64: montage: 64 tiles do not fit 64x64"},
      {"montage " + runDir + " --fps 0" + outputs, "rootsim: error: montage: --fps: Value 0 not in range 1 to 240"},
      {"run " + scene + " --set growth.steps=4 --movie --camera follow --field-mm 0 --out " + (d / "run3").string(), "--field-mm"},
      {"run " + scene + " --set growth.steps=4 --movie --color-by nope --out " + (d / "run3").string(), "--color-by"},
      {"run " + scene + " --set growth.steps=4 --camera follow --out " + (d / "run3").string(), "--movie"},
      {"run " + scene + " --set growth.steps=30000 --set output.every_steps=1 --movie --out " + (d / "run3").string(),
       "would make 30001 frames, more than the cap of 20000"},
  };
  for (const auto& b : bad) {
    const Result r = run(b.args);
    INFO(b.args.substr(0, 300) << "\n-> " << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find(b.names) != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);  // one line
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(out + ".partial"));
    CHECK_FALSE(fs::exists(pngs));
    CHECK_FALSE(fs::exists(d / "run3"));
  }
  // 4K works
  const Result k4 = run("render " + runDir + " --size 3840x2160 --color-by curvature --shadows --quiet --final-png " +
                        (d / "k4.png").string());
  REQUIRE_MESSAGE(k4.code == 0, k4.out);
  CHECK(readPng((d / "k4.png").string()).width == 3840);
}

TEST_CASE("render reads trajectory.bin and draws the same frames as from trajectory.csv") {
  const fs::path d = rtest::scratch("binframes");
  const std::string both = (d / "both").string();
  const Result ran = run("run " + std::string(ROOTSIM_SOURCE_DIR) +
                         "/scenes/fig2b_waving.toml --set growth.steps=40 --set output.every_steps=8 "
                         "--set output.trajectory_format=both --set output.vtk=false --quiet --out " + both);
  REQUIRE_MESSAGE(ran.code == 0, ran.out);
  // one copy with only the CSV, one with only the binary file
  fs::copy(both, d / "csv", fs::copy_options::recursive);
  fs::copy(both, d / "bin", fs::copy_options::recursive);
  fs::remove(d / "csv" / "trajectory.bin");
  fs::remove(d / "bin" / "trajectory.csv");
  for (const char* which : {"csv", "bin"}) {
    const Result r = run("render " + (d / which).string() + " --size 320x180 --color-by kappa0 --quiet --png-dir " +
                         (d / (std::string("frames_") + which)).string());
    REQUIRE_MESSAGE(r.code == 0, r.out);
  }
  int frames = 0;
  for (const auto& e : fs::directory_iterator(d / "frames_csv")) {
    if (e.path().extension() != ".png") continue;  // the folder's marker, .rootsim-frames
    CAPTURE(e.path().filename().string());
    auto slurp = [](const fs::path& p) {
      std::ifstream in(p, std::ios::binary);
      std::stringstream s;
      s << in.rdbuf();
      return s.str();
    };
    const std::string a = slurp(e.path()), b = slurp(d / "frames_bin" / e.path().filename());
    CHECK(!a.empty());
    CHECK((a == b));
    ++frames;
  }
  CHECK(frames == 6);
  fs::remove_all(d);
}
