// Checkpoints and `rootsim run --resume` (issue 15 item 3), compact outputs (item 8): a run killed after
// a checkpoint and resumed writes the same bytes as one never interrupted (summary.json's wall time
// aside); refusals; sweeps resume; the zlib ParaView files and trajectory.bin decode to the snapshots.
//
// A kill is emulated by the test binary rootsim_killable (tests/seams/kill_at_step.cpp) with
// ROOTSIM_TEST_KILL="C:K": a checkpoint after growth step C, then _Exit(137) after step K, leaving
// DIR.partial as SIGKILL would (the files written after the checkpoint included, so resuming has to cut
// them back).
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/units.hpp"
#include "run_rootsim.hpp"
#include "test_files.hpp"

namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::runBinary;

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("resume", name); }

using rootsim::test::slurp;

// summary.json without its wall time (the one field that may differ)
std::string stripWall(std::string s) {
  const auto p = s.find("\"wall_time_s\"");
  if (p != std::string::npos) s.erase(p, s.find('\n', p) - p);
  return s;
}

// the run marker without its line for summary.json (whose size follows the wall time)
std::string stripSummarySize(std::string s) {
  const auto p = s.find("file summary.json ");
  if (p != std::string::npos) s.erase(p, s.find('\n', p) + 1 - p);
  return s;
}

// every file below dir (relative path -> bytes)
std::map<std::string, std::string> files(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      const std::string rel = fs::relative(e.path(), dir).string();
      out[rel] = rel == "summary.json"   ? stripWall(slurp(e.path()))
                 : rel == ".rootsim-run" ? stripSummarySize(slurp(e.path()))
                                         : slurp(e.path());
    }
  return out;
}

// the two run directories hold the same files with the same bytes
void checkSameRun(const fs::path& a, const fs::path& b) {
  const auto fa = files(a), fb = files(b);
  std::string namesA, namesB;
  for (const auto& [k, v] : fa) namesA += k + " ";
  for (const auto& [k, v] : fb) namesB += k + " ";
  CHECK(namesA == namesB);
  for (const auto& kv : fa) {
    const std::string& k = kv.first;
    const std::string& v = kv.second;
    INFO(k);
    const auto it = fb.find(k);
    REQUIRE(it != fb.end());
    CHECK(!v.empty());
    CHECK(v.size() == it->second.size());
    CHECK((v == it->second));
  }
}

// runs rootsim_killable with its kill seam set
Result runKilled(const std::string& args, const std::string& hook) {
  ::setenv("ROOTSIM_TEST_KILL", hook.c_str(), 1);
  Result r = runBinary(ROOTSIM_KILLABLE_BINARY, args);
  ::unsetenv("ROOTSIM_TEST_KILL");
  return r;
}

const std::string kScene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
// every output on: both trajectory formats, ParaView; checkpoints only where the hook asks
const std::string kSets = " --set growth.steps=120 --set output.every_steps=10 --set output.trajectory_format=both "
                          "--set output.checkpoint_every_s=1e6 --quiet";
}  // namespace

TEST_CASE("a killed run resumed from its checkpoint writes the same bytes as an uninterrupted run") {
  struct Variant {
    const char* name;
    std::string scene;
  };
  const std::string src = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/";
  for (const Variant& v : {Variant{"newton", kScene}, Variant{"dynamic", kScene + " --set solver.kind=dynamic"},
                           Variant{"friction", src + "friction_waving.toml"},
                           Variant{"obstacle", src + "obstacle_peg.toml"},
                           Variant{"window", kScene + " --set solver.window_mm=1"},
                           // a long frozen part at the checkpoint (4 mm, ~80 elements): the frozen
                           // twists' kept stiffness carried over it
                           Variant{"frozen", kScene + " --set solver.window_mm=1 --set growth.step_h=0.5"},
                           // a coil in self-contact from step 30 on: the sparse Jacobian's pattern,
                           // pivots and last factors (the next step's chord step) carried over the
                           // checkpoint
                           Variant{"coil", src + "fig2a_alpha90.toml --set tropism.beta=1 --set growth.step_h=0.2"}}) {
    const std::string variant = v.name;
    CAPTURE(variant);
    const fs::path d = scratch(std::string("same_") + v.name);
    const std::string args = "run " + v.scene + kSets + " --out ";
    REQUIRE(run(args + (d / "a").string()).code == 0);
    // killed at step 63, 16 steps after the checkpoint of step 47: the frames of steps 50 and 60 are on
    // disk and must be cut back and written again
    const Result k = runKilled(args + (d / "b").string(), "47:63");
    CHECK(k.code == 137);
    CHECK(!fs::exists(d / "b"));
    REQUIRE(fs::exists(d / "b.partial" / "checkpoint.bin"));
    CHECK(fs::exists(d / "b.partial" / "vtk" / "step_000060.vtp"));
    const Result r = run(args + (d / "b").string() + " --resume");
    REQUIRE_MESSAGE(r.code == 0, r.out);
    CHECK(r.out.find("resuming " + (d / "b").string() + " from the checkpoint of growth step 47 of 120") != std::string::npos);
    CHECK(!fs::exists(d / "b.partial"));
    CHECK(!fs::exists(d / "b" / "checkpoint.bin"));
    checkSameRun(d / "a", d / "b");
    fs::remove_all(d);
  }
}

TEST_CASE("a run killed with SIGKILL once a checkpoint exists resumes to the same bytes") {
  // the real thing, at whatever point of the step the signal lands (inside a checkpoint write included)
  const fs::path d = scratch("sigkill");
  const std::string sets = " --set growth.steps=1000 --set output.checkpoint_every_s=0.05 --quiet --out ";
  REQUIRE(run("run " + kScene + sets + (d / "a").string()).code == 0);
  const std::string out = (d / "b").string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::execl(ROOTSIM_BINARY, ROOTSIM_BINARY, "run", kScene.c_str(), "--set", "growth.steps=1000", "--set",
            "output.checkpoint_every_s=0.05", "--quiet", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // wait for the first checkpoint, let the run go on a little, kill it
  int status = 0;
  bool ended = false;
  while (!fs::exists(d / "b.partial" / "checkpoint.bin") && !ended) {
    ::usleep(2000);
    ended = ::waitpid(pid, &status, WNOHANG) == pid;
  }
  ::usleep(30000);
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  REQUIRE_MESSAGE(WIFSIGNALED(status), "the run ended before it could be killed");
  CHECK(!fs::exists(d / "b"));
  const Result r = run("run " + kScene + sets + out + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("a run killed twice (the second time while resuming) still ends with the same bytes") {
  const fs::path d = scratch("twice");
  const std::string args = "run " + kScene + kSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  CHECK(runKilled(args + (d / "b").string(), "20:29").code == 137);
  CHECK(runKilled(args + (d / "b").string() + " --resume", "75:99").code == 137);
  // a checkpoint writer killed mid-write leaves checkpoint.bin.tmp: ignored and removed
  { std::ofstream(d / "b.partial" / "checkpoint.bin.tmp") << "torn"; }
  { std::ofstream(d / "b.partial" / "vtk" / "step_000080.vtp.tmp") << "torn"; }
  const Result r = run(args + (d / "b").string() + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("resume on a complete run says so and exits 0 and on another scene's complete run exits 2") {
  const fs::path d = scratch("complete");
  const std::string out = (d / "a").string();
  REQUIRE(run("run " + kScene + kSets + " --out " + out).code == 0);
  const std::string before = slurp(d / "a" / "summary.json");
  const Result again = run("run " + kScene + kSets + " --out " + out + " --resume");
  CHECK(again.code == 0);
  CHECK(again.out.find("is complete: nothing to resume") != std::string::npos);
  CHECK(slurp(d / "a" / "summary.json") == before);
  const Result other = run("run " + kScene + kSets + " --set tropism.beta=0.3 --out " + out + " --resume");
  CHECK(other.code == 2);
  CHECK(other.out.find("complete run of another scene") != std::string::npos);
  CHECK(slurp(d / "a" / "summary.json") == before);
  fs::remove_all(d);
}

TEST_CASE("resume refuses an interrupted run of another scene with exit 2 and with --force starts again") {
  const fs::path d = scratch("otherscene");
  const std::string out = (d / "b").string();
  CHECK(runKilled("run " + kScene + kSets + " --out " + out, "30:35").code == 137);
  const Result r = run("run " + kScene + kSets + " --set plane.alpha_deg=50 --out " + out + " --resume");
  CHECK(r.code == 2);
  CHECK(r.out.find("written by another scene") != std::string::npos);
  CHECK(fs::exists(d / "b.partial" / "checkpoint.bin"));
  // without --resume the interrupted run is not discarded either; the message says how to continue
  const Result plain = run("run " + kScene + kSets + " --out " + out);
  CHECK(plain.code == 2);
  CHECK(plain.out.find("--resume") != std::string::npos);
  const Result forced = run("run " + kScene + kSets + " --set plane.alpha_deg=50 --out " + out + " --resume --force");
  CHECK(forced.code == 0);
  CHECK(slurp(d / "b" / "scene.toml").find("alpha_deg = 50") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("a corrupt or truncated checkpoint exits 2 naming it and --force discards it and starts again") {
  const fs::path d = scratch("corrupt");
  const std::string args = "run " + kScene + kSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  const fs::path ck = d / "b.partial" / "checkpoint.bin";
  CHECK(runKilled(args + (d / "b").string(), "40:45").code == 137);
  const std::string good = slurp(ck);
  REQUIRE(good.size() > 100);
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x10);
  for (const std::string& bad : {good.substr(0, good.size() / 2), flipped, std::string("RSCHKPT"), std::string()}) {
    CAPTURE(bad.size());
    { std::ofstream(ck, std::ios::binary) << bad; }
    const Result r = run(args + (d / "b").string() + " --resume");
    CHECK(r.code == 2);
    CHECK(r.out.find(ck.string() + ": corrupt checkpoint") != std::string::npos);
    CHECK(r.out.find("--force") != std::string::npos);
    CHECK(fs::exists(ck));  // nothing discarded without --force
    CHECK(!fs::exists(d / "b"));
  }
  // a valid checkpoint, but a stream shorter than it says (the file was damaged): refused before
  // anything is touched
  { std::ofstream(ck, std::ios::binary) << good; }
  fs::resize_file(d / "b.partial" / "timeseries.csv.tmp", 100);
  const Result shortened = run(args + (d / "b").string() + " --resume");
  CHECK(shortened.code == 2);
  CHECK(shortened.out.find("timeseries.csv.tmp: missing or shorter") != std::string::npos);
  CHECK(fs::exists(ck));
  CHECK(!fs::exists(d / "b.incomplete"));
  const Result forced = run(args + (d / "b").string() + " --resume --force");
  REQUIRE_MESSAGE(forced.code == 0, forced.out);
  CHECK(forced.out.find("no usable checkpoint") != std::string::npos);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("a killed sweep resumes its unfinished point from the checkpoint and matches an uninterrupted sweep") {
  const fs::path d = scratch("sweep");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene << "\"\n[grid]\n\"tropism.beta\" = [0.1, 0.2]\n"
                                << "[set]\n\"growth.steps\" = 90\n\"output.checkpoint_every_s\" = 1e6\n";
  }
  const std::string cmd = "sweep " + (d / "s.toml").string() + " -j 1 --quiet --out ";
  REQUIRE(run(cmd + (d / "a").string()).code == 0);
  // the first point is killed at step 66 after a checkpoint at 52
  CHECK(runKilled(cmd + (d / "b").string(), "52:66").code == 137);
  std::vector<std::string> points, partials;
  for (const auto& e : fs::directory_iterator(d / "a"))
    if (e.is_directory()) points.push_back(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(d / "b"))
    if (e.path().extension() == ".partial") partials.push_back(e.path().filename().string());
  REQUIRE(points.size() == 2);
  REQUIRE(partials.size() == 1);
  CHECK(fs::exists(d / "b" / partials[0] / "checkpoint.bin"));
  const Result r = run("sweep " + (d / "s.toml").string() + " -j 1 --out " + (d / "b").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  CHECK(r.out.find("2 ran") != std::string::npos);
  for (const std::string& p : points) {
    CAPTURE(p);
    checkSameRun(d / "a" / p, d / "b" / p);
  }
  // table.csv holds the wall time of each run: compare the rest
  auto table = [](const fs::path& f) {
    std::istringstream in(slurp(f));
    std::string line, out;
    std::getline(in, line);
    const auto col = [&] {
      int c = 0;
      std::istringstream h(line);
      std::string name;
      while (std::getline(h, name, ',')) {
        if (name == "wall_time_s") return c;
        ++c;
      }
      return -1;
    }();
    out += line + "\n";
    while (std::getline(in, line)) {
      std::istringstream row(line);
      std::string cell;
      for (int c = 0; std::getline(row, cell, ','); ++c) out += (c == col ? std::string("*") : cell) + ",";
      out += "\n";
    }
    return out;
  };
  CHECK(table(d / "a" / "table.csv") == table(d / "b" / "table.csv"));
  fs::remove_all(d);
}

namespace {
// the appended data of a VTK XML file written with vtkZLibDataCompressor and header_type UInt64: the
// array at `offset`, decompressed
std::string vtkArray(const std::string& file, std::size_t offset) {
  const std::size_t start = file.find("<AppendedData encoding=\"raw\">\n_");
  REQUIRE(start != std::string::npos);
  const char* p = file.data() + start + std::strlen("<AppendedData encoding=\"raw\">\n_") + offset;
  std::uint64_t head[3];
  std::memcpy(head, p, sizeof head);
  const std::uint64_t blocks = head[0], blockSize = head[1], last = head[2];
  std::vector<std::uint64_t> sizes(blocks);
  std::memcpy(sizes.data(), p + sizeof head, blocks * 8);
  const char* data = p + sizeof head + blocks * 8;
  std::string out;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    uLongf n = (k + 1 == blocks && last != 0) ? last : blockSize;
    std::string block(n, '\0');
    REQUIRE(uncompress(reinterpret_cast<Bytef*>(block.data()), &n, reinterpret_cast<const Bytef*>(data), sizes[k]) == Z_OK);
    block.resize(n);
    out += block;
    data += sizes[k];
  }
  return out;
}

// the offset= of the DataArray named `name` (Points: the first, unnamed)
std::size_t vtkOffset(const std::string& file, const std::string& name) {
  const std::size_t at = name.empty() ? file.find("<Points>") : file.find("Name=\"" + name + "\"");
  REQUIRE(at != std::string::npos);
  const std::size_t o = file.find("offset=\"", at) + 8;
  return std::stoul(file.substr(o, file.find('"', o) - o));
}

template <class T>
std::vector<T> as(const std::string& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}
}  // namespace

TEST_CASE("ParaView files are zlib-compressed binary that decodes to the snapshot and trajectory.bin reads as the CSV") {
  const fs::path d = scratch("formats");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + kSets + " --out " + out.string()).code == 0);
  const std::vector<rootsim::Snapshot> csv = rootsim::readTrajectory(out / "trajectory.csv");
  const std::vector<rootsim::Snapshot> bin = rootsim::readTrajectory(out / "trajectory.bin");
  REQUIRE(csv.size() == 13);
  REQUIRE(bin.size() == csv.size());
  CHECK(rootsim::trajectoryPath(out) == out / "trajectory.bin");
  // bit for bit: the renderer sees the same snapshots from either file
  for (std::size_t f = 0; f < csv.size(); ++f) {
    CAPTURE(f);
    const rootsim::Snapshot &a = csv[f], &b = bin[f];
    CHECK(a.step == b.step);
    CHECK(a.timeH == b.timeH);
    CHECK(a.x == b.x);
    CHECK(a.d1 == b.d1);
    CHECK(a.d3 == b.d3);
    CHECK(a.radius == b.radius);
    CHECK(a.kappa0 == b.kappa0);
    CHECK(a.plateForce == b.plateForce);
    CHECK(a.contactForce == b.contactForce);
  }
  CHECK(fs::file_size(out / "trajectory.bin") * 2 < fs::file_size(out / "trajectory.csv"));

  // the last ParaView file against the last snapshot
  const rootsim::Snapshot& s = bin.back();
  const std::string vtp = slurp(out / "vtk" / "step_000120.vtp");
  CHECK(vtp.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
  CHECK(vtp.find("header_type=\"UInt64\"") != std::string::npos);
  CHECK(vtp.find("format=\"ascii\"") == std::string::npos);
  const int n = s.elements();
  CHECK(vtp.find("NumberOfPoints=\"" + std::to_string(n + 1) + "\"") != std::string::npos);
  const auto pts = as<double>(vtkArray(vtp, vtkOffset(vtp, "")));
  REQUIRE(pts.size() == static_cast<std::size_t>(3 * (n + 1)));
  for (int i = 0; i <= n; ++i)
    for (int c = 0; c < 3; ++c) CHECK(pts[static_cast<std::size_t>(3 * i + c)] * rootsim::units::mm == s.x(c, i));
  const auto conn = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "connectivity")));
  const auto offs = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "offsets")));
  REQUIRE(conn.size() == static_cast<std::size_t>(2 * n));
  REQUIRE(offs.size() == static_cast<std::size_t>(n));
  CHECK(conn[0] == 0);
  CHECK(conn.back() == n);
  CHECK(offs.back() == 2 * n);
  const auto rad = as<double>(vtkArray(vtp, vtkOffset(vtp, "radius_mm")));
  const auto d1 = as<double>(vtkArray(vtp, vtkOffset(vtp, "d1")));
  const auto d3 = as<double>(vtkArray(vtp, vtkOffset(vtp, "d3")));
  REQUIRE(rad.size() == static_cast<std::size_t>(n));
  REQUIRE(d1.size() == static_cast<std::size_t>(3 * n));
  REQUIRE(d3.size() == static_cast<std::size_t>(3 * n));
  for (int i = 0; i < n; ++i) {
    CHECK(rad[static_cast<std::size_t>(i)] * rootsim::units::mm == s.radius[i]);
    for (int c = 0; c < 3; ++c) {
      CHECK(d1[static_cast<std::size_t>(3 * i + c)] == s.d1(c, i));
      CHECK(d3[static_cast<std::size_t>(3 * i + c)] == s.d3(c, i));
    }
  }
  fs::remove_all(d);
}

TEST_CASE("a truncated or corrupt trajectory.bin is refused naming the file and the byte") {
  const fs::path d = scratch("badbin");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + " --set growth.steps=20 --set output.vtk=false --quiet --out " + out.string()).code == 0);
  REQUIRE(fs::exists(out / "trajectory.bin"));
  CHECK(!fs::exists(out / "trajectory.csv"));
  // readTrajectory(run/trajectory.csv) reads the binary sibling (what callers written for the CSV do)
  CHECK(rootsim::readTrajectory(out / "trajectory.csv").size() == 3);
  const std::string good = slurp(out / "trajectory.bin");
  auto refused = [&](const std::string& bytes, const std::string& why) {
    CAPTURE(why);
    { std::ofstream(out / "trajectory.bin", std::ios::binary) << bytes; }
    std::string e;
    try {
      rootsim::readTrajectory(out / "trajectory.bin");
    } catch (const rootsim::SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((out / "trajectory.bin").string() + ": byte ") == 0);
    CHECK(e.find(why) != std::string::npos);
  };
  refused(good.substr(0, good.size() - 5), "truncated");
  std::string nan = good;
  const double q = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + 16 + 24, &q, 8);  // the first x of the first frame
  refused(nan, "x_mm: not a finite number");
  refused(std::string("RSTRAJ01\x02\0\0\0\0\0\0\0", 16), "version");
  fs::remove_all(d);
}

namespace {
// FNV-1a 64, the checkpoint's checksum (include/rootsim/checkpoint.hpp)
std::uint64_t fnv1a(const std::string& s, std::size_t from, std::size_t to) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = from; i < to; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
  return h;
}
}  // namespace

TEST_CASE("a forged checkpoint with a recomputed checksum and an impossible frame count is refused naming the field") {
  const fs::path d = scratch("forged");
  // no ParaView entries: the payload ends with the trajectory frame count (i32) and the entry count (u64)
  const std::string args = "run " + kScene + kSets + " --set output.vtk=false --out ";
  CHECK(runKilled(args + (d / "b").string(), "40:45").code == 137);
  const fs::path ck = d / "b.partial" / "checkpoint.bin";
  const std::string good = slurp(ck);
  REQUIRE(good.size() > 100);
  const std::size_t framesAt = good.size() - 8 - 8 - 4;
  std::int32_t frames = 0;
  std::memcpy(&frames, good.data() + framesAt, 4);
  REQUIRE(frames == 5);  // steps 0, 10, 20, 30, 40
  auto forged = [&](std::int32_t f) {
    std::string b = good;
    std::memcpy(b.data() + framesAt, &f, 4);
    const std::uint64_t sum = fnv1a(b, 40, b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
    return b;
  };
  const std::pair<std::int32_t, std::string> cases[] = {
      {-5, "trajectory frame count -5 out of range (0 .. 41: at most one per growth step up to 40, and the initial one)"},
      {2000000000, "trajectory frame count 2000000000 out of range (0 .. 41"},
      {4, "trajectory frame count 4 disagrees with"},
  };
  for (const auto& c : cases) {
    // (not a structured binding: clang before 16 cannot capture one in CAPTURE's lambda)
    const std::int32_t f = c.first;
    const std::string& why = c.second;
    CAPTURE(f);
    { std::ofstream(ck, std::ios::binary) << forged(f); }
    const Result r = run(args + (d / "b").string() + " --resume");
    INFO(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find(ck.string() + ": corrupt checkpoint (" + why) != std::string::npos);
    CHECK(r.out.find("--force") != std::string::npos);
    CHECK(fs::exists(ck));
    CHECK(!fs::exists(d / "b"));
  }
  // the genuine one still resumes
  { std::ofstream(ck, std::ios::binary) << good; }
  const Result ok = run(args + (d / "b").string() + " --resume");
  CHECK_MESSAGE(ok.code == 0, ok.out);
  fs::remove_all(d);
}

TEST_CASE("a trajectory.bin with one huge finite coordinate is refused by render quickly (it grew past 4 GB)") {
  const fs::path d = scratch("hugebin");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + " --set growth.steps=20 --set output.vtk=false --quiet --out " + out.string()).code == 0);
  std::string b = slurp(out / "trajectory.bin");
  const double huge = 1e7;  // mm
  std::memcpy(b.data() + 16 + 24 + 8, &huge, 8);  // y of node 0 of the first frame
  { std::ofstream(out / "trajectory.bin", std::ios::binary) << b; }
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = run("render " + out.string() + " --final-png " + (d / "x.png").string() + " --quiet");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.code == 2);
  CHECK(r.out.find((out / "trajectory.bin").string() + ": byte 48: frame 0, node 0: y_mm = 1e+07 is outside -10000 .. "
                                                      "10000 mm (positions are bounded to |x|, |y|, |z| <= 10 m)") !=
        std::string::npos);
  CHECK(s < 20);
  CHECK(!fs::exists(d / "x.png"));
  fs::remove_all(d);
}

TEST_CASE("the production binary has no kill seam: ROOTSIM_TEST_KILL changes nothing") {
  const fs::path d = scratch("no_seam");
  ::setenv("ROOTSIM_TEST_KILL", "2:3", 1);
  const Result r = run("run " + kScene + " --set growth.steps=6 --quiet --out " + (d / "a").string());
  ::unsetenv("ROOTSIM_TEST_KILL");
  CHECK(r.code == 0);
  CHECK(fs::exists(d / "a" / "summary.json"));
  CHECK(!fs::exists(d / "a.partial"));
}
