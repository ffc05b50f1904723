// The write rule (write_rule.hpp) through every command that writes, as a careless or hostile user
// would meet it: the run's own data, a user's file, a device, a FIFO, a symbolic link, a user's folder,
// the working folder, rootsim's own earlier output with and without --force, a second process, a killed
// one. Each case runs the rootsim binary; the cases that draw pictures are in render/test_write_render.cpp.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <thread>

#include "rootsim/errors.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/write_rule.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("write", name); }

using rootsim::test::kScene;
// a run of a few seconds' hundredths: 10 growth steps, coarse elements
const std::string kShort = " --set growth.steps=10 --set root.element_length_mm=0.1 --quiet";

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// a small finished run directory
fs::path makeRun(const fs::path& d, const std::string& name = "r") {
  const fs::path r = d / name;
  const Result res = run("run " + kScene + kShort + " --out " + q(r));
  REQUIRE(res.code == 0);
  return r;
}

// every file below dir with its bytes
std::map<std::string, std::string> snapshot(const fs::path& dir) { return rootsim::test::fileTree(dir); }

// this process holds the lock of an output path, as a second rootsim process would
struct HeldLock {
  int fd = -1;
  explicit HeldLock(const fs::path& out) {
    const fs::path a = fs::absolute(out).lexically_normal();
    const fs::path file = a.parent_path() / ("." + a.filename().string() + ".rootsim-lock");
    fs::create_directories(file.parent_path());
    fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(fd >= 0);
    REQUIRE(::flock(fd, LOCK_EX | LOCK_NB) == 0);
    const std::string text = "rootsim lock " + std::to_string(::getpid()) + "\n";
    REQUIRE(::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()));
  }
  ~HeldLock() { ::close(fd); }
};

void checkRefused(const Result& r, const std::string& what) {
  INFO(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find(what) != std::string::npos);
}

const std::string kSweep = R"([sweep]
scene = "base.toml"
[grid]
"plane.alpha_deg" = [35.7, 40.0]
[set]
"growth.steps" = 10
"root.element_length_mm" = 0.1
)";

// a sweep file beside a copy of the base scene
fs::path makeSweep(const fs::path& d) {
  fs::copy_file(kScene, d / "base.toml", fs::copy_options::overwrite_existing);
  std::ofstream(d / "sweep.toml") << kSweep;
  return d / "sweep.toml";
}

// shell text that writes the exit code of the command before it into rc whole: beside it, then renamed, so a
// test polling for rc never reads it half-written
std::string exitCodeTo(const fs::path& rc) {
  fs::path tmp = rc;
  tmp += ".tmp";
  return "echo $? > " + q(tmp) + " && mv " + q(tmp) + " " + q(rc);
}
}  // namespace

TEST_CASE("render and montage never write over a run's own data, nor into or onto a run directory they read") {
  const fs::path d = scratch("own_data");
  const fs::path r = makeRun(d), r2 = makeRun(d, "r2");
  const auto before = snapshot(r);
  for (const char* f : {"trajectory.bin", "scene.toml", "summary.json", ".rootsim-run", "vtk/step_000000.vtp"}) {
    INFO(f);
    checkRefused(run("render " + q(r) + " --quiet --mp4 " + q(r / f)), "which this command reads");
    checkRefused(run("render " + q(r) + " --quiet --final-png " + q(r / f)), "which this command reads");
    checkRefused(run("montage " + q(r) + " " + q(r2) + " --quiet --mp4 " + q(r / f)), "which this command reads");
  }
  // the run directory itself, and a frame folder inside it
  checkRefused(run("render " + q(r) + " --quiet --mp4 " + q(r)), "is " + r.string());
  checkRefused(run("render " + q(r) + " --quiet --png-dir " + q(r / "frames")), "which this command reads");
  CHECK(snapshot(r) == before);
  CHECK(!fs::exists(fs::path(r.string() + ".partial")));
  CHECK(!fs::exists(r / "frames"));
  fs::remove_all(d);
}

TEST_CASE("a user's file, a device, a FIFO or a symbolic link as an output: refused, untouched") {
  const fs::path d = scratch("foreign_file");
  const fs::path r = makeRun(d);
  std::ofstream(d / "notes.txt") << "my notes\n";
  REQUIRE(::mkfifo((d / "fifo").c_str(), 0644) == 0);
  fs::create_symlink(d / "notes.txt", d / "link.mp4");
  for (const std::string flag : {"--mp4", "--final-png"}) {
    INFO(flag);
    checkRefused(run("render " + q(r) + " --quiet " + flag + " " + q(d / "notes.txt")), "was not written by rootsim");
    checkRefused(run("render " + q(r) + " --quiet " + flag + " " + q(d / "fifo")), "is a FIFO");
    checkRefused(run("render " + q(r) + " --quiet " + flag + " " + q(d / "link.mp4")), "is a symbolic link");
    checkRefused(run("render " + q(r) + " --quiet " + flag + " /dev/null --force"), "is a device");
  }
  checkRefused(run("montage " + q(r) + " --quiet --force --mp4 " + q(d / "notes.txt")), "was not written by rootsim");
  checkRefused(run("montage " + q(r) + " --quiet --mp4 " + q(d / "fifo")), "is a FIFO");
  // --force never makes a user's file rootsim's
  checkRefused(run("render " + q(r) + " --quiet --force --mp4 " + q(d / "notes.txt")), "was not written by rootsim");
  CHECK(slurp(d / "notes.txt") == "my notes\n");
  CHECK(fs::is_fifo(d / "fifo"));
  CHECK(fs::is_symlink(d / "link.mp4"));
  struct stat st {};
  REQUIRE(::stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
  fs::remove_all(d);
}

TEST_CASE("--png-dir: a user's folder, the root folder, a folder holding a user's frame are refused") {
  const fs::path d = scratch("foreign_frames");
  const fs::path r = makeRun(d);
  fs::create_directories(d / "mine");
  std::ofstream(d / "mine" / "frame_00003.png") << "my picture";
  for (const char* cmd : {"render", "montage"}) {
    INFO(cmd);
    checkRefused(run(std::string(cmd) + " " + q(r) + " --quiet --force --png-dir " + q(d / "mine")), "not a rootsim frame folder");
    checkRefused(run(std::string(cmd) + " " + q(r) + " --quiet --force --png-dir /"), "not a name of its own");
  }
  CHECK(slurp(d / "mine" / "frame_00003.png") == "my picture");
  CHECK(!fs::exists("/frame_00000.png"));
  // a folder of rootsim's frames with a user's file added is no longer rootsim's alone
  fs::create_directories(d / "frames");
  std::ofstream(d / "frames" / ".rootsim-frames") << "rootsim rootsim frame folder\n";
  std::ofstream(d / "frames" / "notes.txt") << "mine";
  checkRefused(run("render " + q(r) + " --quiet --force --png-dir " + q(d / "frames")), "holds notes.txt");
  CHECK(slurp(d / "frames" / "notes.txt") == "mine");
  fs::remove_all(d);
}

TEST_CASE("run: rootsim's working names, empty and too long --out names are refused with their reason") {
  const fs::path d = scratch("names");
  for (const char* suffix : {".partial", ".incomplete", ".replaced", ".tmp"})
    checkRefused(run("run " + kScene + kShort + " --out " + q(d / (std::string("X") + suffix))), "rootsim's working names");
  checkRefused(run("run " + kScene + kShort + " --out ''"), "--out: empty value");
  checkRefused(run("sweep " + q(makeSweep(d)) + " --quiet --out ''"), "--out: empty value");
  checkRefused(run("figure fig2b --quick --quiet --out ''"), "--out: empty value");
  // 256 bytes: the message says so (it once said "contains ../base.toml")
  checkRefused(run("run " + kScene + kShort + " --out " + q(d / std::string(256, 'a'))), "its last part is 256 bytes");
  // 246 bytes: no room for DIR.incomplete; a failing run once stayed DIR.partial without a word
  const Result r = run("run " + kScene + kShort + " --set solver.max_substeps=1 --set solver.kind=dynamic --out " +
                       q(d / std::string(246, 'b')));
  checkRefused(r, "at most 241");
  for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().filename().string().rfind("bbb", 0) != 0);
  fs::remove_all(d);
}

TEST_CASE("run --resume never deletes a finished run left at DIR.partial, nor a failed DIR.incomplete without --force") {
  const fs::path d = scratch("keep");
  // a finished run moved to X.partial by hand (a kill between its last write and the rename looks the same)
  const fs::path x = makeRun(d, "X");
  fs::rename(x, d / "X.partial");
  const auto before = snapshot(d / "X.partial");
  checkRefused(run("run " + kScene + kShort + " --resume --out " + q(d / "X")), "holds a finished run without a checkpoint");
  CHECK(snapshot(d / "X.partial") == before);
  CHECK(!fs::exists(d / "X"));
  // a failed run: Z.incomplete with its ERROR.txt
  const Result fail = run("run " + kScene + kShort + " --set solver.kind=dynamic --set solver.max_substeps=1 --out " + q(d / "Z"));
  REQUIRE(fail.code == 1);
  REQUIRE(fs::exists(d / "Z.incomplete" / "ERROR.txt"));
  const std::string error = slurp(d / "Z.incomplete" / "ERROR.txt");
  checkRefused(run("run " + kScene + kShort + " --out " + q(d / "Z")), "holds a failed run");
  CHECK(slurp(d / "Z.incomplete" / "ERROR.txt") == error);
  // with --force the new run replaces it
  CHECK(run("run " + kScene + kShort + " --force --out " + q(d / "Z")).code == 0);
  CHECK(fs::exists(d / "Z" / "summary.json"));
  CHECK(!fs::exists(d / "Z.incomplete"));
  fs::remove_all(d);
}

TEST_CASE("a second process on a run, sweep or figure folder being written is refused naming the holder's PID") {
  const fs::path d = scratch("locked");
  const std::string pid = "PID " + std::to_string(::getpid());
  {
    const HeldLock lock(d / "C");
    checkRefused(run("run " + kScene + kShort + " --out " + q(d / "C")), pid);
    checkRefused(run("run " + kScene + kShort + " --resume --out " + q(d / "C")), pid);
    checkRefused(run("run " + kScene + kShort + " --force --out " + q(d / "C")), pid);
    CHECK(!fs::exists(d / "C"));
    CHECK(!fs::exists(d / "C.partial"));
  }
  const fs::path r = makeRun(d);
  {
    const HeldLock lock(d / "m.mp4");
    checkRefused(run("render " + q(r) + " --quiet --mp4 " + q(d / "m.mp4")), pid);
  }
  {
    const HeldLock lock(r);
    checkRefused(run("modes " + q(r) + " --quiet"), pid);
  }
  {
    const HeldLock lock(d / "figs");
    checkRefused(run("figure fig2b --quick --quiet --out " + q(d / "figs")), pid);
  }
  const fs::path sw = makeSweep(d);
  REQUIRE(run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + " --shard 1/2").code == 0);
  {
    // one shard is locked: the same shard again is refused, another shard runs
    const HeldLock lock(d / "S" / "shard-2-of-2");
    checkRefused(run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + " --shard 2/2"), pid);
  }
  fs::remove_all(d);
}

TEST_CASE("a killed holder never blocks: its lock file left behind is taken over and removed") {
  const fs::path d = scratch("stale_lock");
  // what a SIGKILLed rootsim leaves: the lock file with its (now dead) PID, no lock held
  std::ofstream(d / ".C.rootsim-lock") << "rootsim lock 999999\n";
  const Result r = run("run " + kScene + kShort + " --out " + q(d / "C"));
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(fs::exists(d / "C" / "summary.json"));
  CHECK(!fs::exists(d / ".C.rootsim-lock"));
  fs::remove_all(d);
}

TEST_CASE("two real processes on one run directory: the second is refused, the first completes whole") {
  const fs::path d = scratch("two_runs");
  // a run of a few seconds (the explicit solver), in the background
  const std::string slow = " --set growth.steps=300 --set solver.kind=dynamic --quiet --out " + q(d / "C");
  const std::string cmd = std::string(ROOTSIM_BINARY) + " run " + kScene + slow + " > " + q(d / "first.log") +
                          " 2>&1; " + exitCodeTo(d / "first.rc");
  REQUIRE(std::system(("(" + cmd + ") &").c_str()) == 0);
  for (int i = 0; i < 500 && !fs::exists(d / "C.partial" / "scene.toml"); ++i) ::usleep(10000);
  REQUIRE(fs::exists(d / "C.partial"));
  for (const char* extra : {" --resume", " --force"}) {
    const Result second = run("run " + kScene + slow + extra);
    // the first must still be running for the check to mean anything
    REQUIRE_MESSAGE(!fs::exists(d / "first.rc"), "the first run ended before the second looked: make it longer");
    checkRefused(second, "being written by another rootsim process");
  }
  for (int i = 0; i < 6000 && !fs::exists(d / "first.rc"); ++i) ::usleep(10000);
  CHECK(slurp(d / "first.rc") == "0\n");
  CHECK(fs::exists(d / "C" / "summary.json"));
  CHECK(!fs::exists(d / "C.partial"));
  fs::remove_all(d);
}

TEST_CASE("sweep: a user's folder, the working folder and its parent are refused - rootsim's own folder resumes") {
  const fs::path d = scratch("sweep_out");
  const fs::path sw = makeSweep(d);
  fs::create_directories(d / "myproj");
  std::ofstream(d / "myproj" / "table.csv") << "my,table\n";
  checkRefused(run("sweep " + q(sw) + " --quiet --out " + q(d / "myproj")), "not a rootsim sweep folder");
  CHECK(slurp(d / "myproj" / "table.csv") == "my,table\n");
  checkRefused(run("--version >/dev/null; cd " + q(d) + " && " + ROOTSIM_BINARY + " sweep sweep.toml --quiet --out ."), "not a name of its own");
  checkRefused(run("--version >/dev/null; cd " + q(d / "myproj") + " && " + ROOTSIM_BINARY + " sweep ../sweep.toml --quiet --out .."), "not a name of its own");
  // the folder holding the sweep file itself, by its name
  checkRefused(run("sweep " + q(sw) + " --quiet --out " + q(d)), "contains");
  for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().filename().string().rfind("run_", 0) != 0);
  CHECK(!fs::exists(d / "table.csv"));
  // its own folder: the second sweep finds both points complete
  REQUIRE(run("sweep " + q(sw) + " --quiet --out " + q(d / "S")).code == 0);
  const Result again = run("sweep " + q(sw) + " --out " + q(d / "S"));
  CHECK(again.code == 0);
  CHECK(again.out.find("0 ran, 2 already complete") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("sweep: a changed base scene or a damaged point is not taken as complete - --force reruns them") {
  const fs::path d = scratch("sweep_stale");
  const fs::path sw = makeSweep(d);
  REQUIRE(run("sweep " + q(sw) + " --quiet --out " + q(d / "S")).code == 0);
  const std::string table = slurp(d / "S" / "table.csv");
  // the base scene changes (beta 0.2 -> 0.3): both points are stale
  std::string base = slurp(d / "base.toml");
  const auto at = base.find("\nbeta = 0.2");
  REQUIRE(at != std::string::npos);
  base.replace(at, 11, "\nbeta = 0.3");
  std::ofstream(d / "base.toml") << base;
  checkRefused(run("sweep " + q(sw) + " --quiet --out " + q(d / "S")), "2 point(s) hold runs that cannot be kept");
  CHECK(slurp(d / "S" / "table.csv") == table);
  const Result forced = run("sweep " + q(sw) + " --out " + q(d / "S") + " --force");
  CHECK(forced.code == 0);
  CHECK(forced.out.find("2 point(s) rerun") != std::string::npos);
  CHECK(forced.out.find("2 ran, 0 already complete") != std::string::npos);
  CHECK(slurp(d / "S" / "table.csv") != table);
  // a point whose time series was cut short (a second process, a full disk) is not complete
  fs::path point;
  for (const auto& e : fs::directory_iterator(d / "S"))
    if (e.path().filename().string().rfind("run_0000", 0) == 0) point = e.path();
  REQUIRE(!point.empty());
  // is not rootsim's any more: refused with --force too, naming the file, until it is moved away
  fs::resize_file(point / "timeseries.csv", 100);
  for (const char* force : {"", " --force"}) {
    const Result r = run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + force);
    checkRefused(r, "timeseries.csv, changed since rootsim wrote it");
    CHECK(r.out.find("move it away or delete it") != std::string::npos);
    CHECK(fs::file_size(point / "timeseries.csv") == 100);
  }
  fs::remove_all(point);
  CHECK(run("sweep " + q(sw) + " --quiet --out " + q(d / "S")).code == 0);
  CHECK(fs::file_size(point / "timeseries.csv") > 100);
  fs::remove_all(d);
}

TEST_CASE("the same sweep started twice into one folder: the second is refused, the first ends whole") {
  const fs::path d = scratch("sweep_twice");
  fs::copy_file(kScene, d / "base.toml");
  // four points of a few seconds each (the explicit solver)
  std::ofstream(d / "sweep.toml") << "[sweep]\nscene = \"base.toml\"\n[grid]\n\"plane.alpha_deg\" = [30.0, 35.0, 40.0, 45.0]\n"
                                     "[set]\n\"growth.steps\" = 150\n\"solver.kind\" = \"dynamic\"\n";
  const std::string args = " sweep " + q(d / "sweep.toml") + " --quiet --out " + q(d / "S");
  REQUIRE(std::system(("(" + std::string(ROOTSIM_BINARY) + args + " > " + q(d / "first.log") + " 2>&1; " +
                       exitCodeTo(d / "first.rc") + ") &").c_str()) == 0);
  // until the first sweep's first point is being written
  auto started = [&] {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(d / "S", ec))
      if (e.path().extension() == ".partial") return true;
    return false;
  };
  for (int i = 0; i < 1000 && !started(); ++i) ::usleep(10000);
  const Result second = run(args);
  REQUIRE_MESSAGE(!fs::exists(d / "first.rc"), "the first sweep ended before the second looked: make it longer");
  checkRefused(second, "being written by another rootsim process");
  for (int i = 0; i < 12000 && !fs::exists(d / "first.rc"); ++i) ::usleep(10000);
  CHECK(slurp(d / "first.rc") == "0\n");
  const Result rerun = run(" sweep " + q(d / "sweep.toml") + " --out " + q(d / "S"));
  CHECK(rerun.code == 0);
  CHECK(rerun.out.find("0 ran, 4 already complete") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("figure: a user's folder or a user's panel file is refused - rootsim's panels are replaced only with --force") {
  const fs::path d = scratch("figure_out");
  fs::create_directories(d / "figs");
  std::ofstream(d / "figs" / "fig2b.png") << "my figure";
  checkRefused(run("figure fig2b --quick --quiet --out " + q(d / "figs")), "not a rootsim figure folder");
  fs::create_directories(d / "figs2");
  std::ofstream(d / "figs2" / "report.md") << "my report";
  checkRefused(run("figure all --quick --quiet --force --out " + q(d / "figs2")), "not a rootsim figure folder");
  CHECK(slurp(d / "figs" / "fig2b.png") == "my figure");
  CHECK(slurp(d / "figs2" / "report.md") == "my report");
  checkRefused(run("--version >/dev/null; cd " + q(d) + " && " + ROOTSIM_BINARY + " figure fig2b --quick --quiet --out ."), "not a name of its own");
  fs::remove_all(d);
}

TEST_CASE("modes replaces its own modes.csv only with --force") {
  const fs::path d = scratch("modes_again");
  const fs::path r = makeRun(d);
  REQUIRE(run("modes " + q(r) + " --quiet").code == 0);
  const std::string csv = slurp(r / "modes.csv");
  checkRefused(run("modes " + q(r) + " --quiet"), "pass --force to replace it");
  CHECK(run("modes " + q(r) + " --quiet --force").code == 0);
  CHECK(slurp(r / "modes.csv") == csv);
  fs::remove_all(d);
}

TEST_CASE("a read-only earlier run is replaced whole with --force (no run.replaced left behind)") {
  const fs::path d = scratch("readonly");
  // as an ordinary user: root may remove read-only files anyway, which would hide the defect
  fs::permissions(d, fs::perms::all);
  const std::string asUser = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  if (::geteuid() == 0 && std::system("command -v setpriv >/dev/null") != 0) {
    rootsim::test::skipCase("setpriv (util-linux) is needed to run as an ordinary user");
    return;
  }
  const std::string prefix = ::geteuid() == 0 ? asUser : "";
  // the ordinary user must reach the binary (a build inside a private folder, e.g. mktemp -d, hides it)
  if (!prefix.empty() && run("--version >/dev/null; " + prefix + std::string(ROOTSIM_BINARY) + " --version").code != 0) {
    rootsim::test::skipCase("an ordinary user cannot run " + std::string(ROOTSIM_BINARY) + " (a private build folder)");
    fs::remove_all(d);
    return;
  }
  const std::string rs = std::string(ROOTSIM_BINARY) + " run " + kScene + kShort + " --out " + q(d / "run");
  const Result first = run("--version >/dev/null; " + prefix + rs);
  if (!prefix.empty() && first.code != 0) {
    // e.g. the scene or the build lies in a folder only root may read
    rootsim::test::skipCase("an ordinary user cannot run the scene here: " + first.out.substr(0, first.out.find('\n')));
    fs::remove_all(d);
    return;
  }
  REQUIRE(first.code == 0);
  REQUIRE(run("--version >/dev/null; " + prefix + "chmod -R a-w " + q(d / "run")).code == 0);
  const Result r = run("--version >/dev/null; " + prefix + rs + " --force");
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(fs::exists(d / "run" / "summary.json"));
  CHECK(!fs::exists(d / "run.replaced"));
  std::system(("chmod -R u+w " + q(d)).c_str());
  fs::remove_all(d);
}

TEST_CASE("a full disk before the run starts is a failed run (exit 1), not bad input") {
  const fs::path d = scratch("full_before");
  const fs::path mnt = d / "mnt";
  fs::create_directories(mnt);
  if (::geteuid() != 0 || ::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0) {
    rootsim::test::skipCase("mounting a 64 KiB tmpfs needs root (CI runs as root)");
    fs::remove_all(d);
    return;
  }
  // fill it
  {
    std::ofstream f(mnt / "fill", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && f; ++i) f << block;
  }
  const Result r = run("run " + kScene + kShort + " --out " + q(mnt / "out"));
  INFO(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("No space left on device") != std::string::npos);
  CHECK(!fs::exists(mnt / "out"));
  ::umount(mnt.c_str());
  fs::remove_all(d);
}

// ---- ownership by record: a single file by its format's signature, a folder's files by its marker ----

namespace {
std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void writeBytes(const fs::path& p, const std::string& b) { std::ofstream(p, std::ios::binary) << b; }

// the refusal of a user's file: exit 2, the file named, how to go on, its bytes unchanged
void checkUsersFile(const Result& r, const fs::path& file, const std::string& before) {
  INFO(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find(file.filename().string()) != std::string::npos);
  CHECK(r.out.find("move it away or delete it") != std::string::npos);
  CHECK(bytesOf(file) == before);
}
}  // namespace

TEST_CASE("a file holding rootsim's signature as bytes anywhere is not rootsim's: RSML, GLB, MP4 and PNG refused with --force") {
  const fs::path d = scratch("substring");
  const fs::path r = makeRun(d);
  const std::string script = "assert b'rootsim-output' in data\n";
  writeBytes(d / "check.py", script);
  checkUsersFile(run("export " + q(r) + " --quiet --force --rsml " + q(d / "check.py")), d / "check.py", script);
  const std::string notes = "notes: rootsim-output rootsim 1.0 was here\n";
  writeBytes(d / "notes.glb", notes);
  checkUsersFile(run("export " + q(r) + " --quiet --force --gltf " + q(d / "notes.glb")), d / "notes.glb", notes);
  // a movie-sized file of someone else's with the bytes at offset 70 000
  std::string movie(100000, '\x42');
  movie.replace(70000, 14, "rootsim-output");
  writeBytes(d / "holiday.mp4", movie);
  checkUsersFile(run("render " + q(r) + " --quiet --force --mp4 " + q(d / "holiday.mp4")), d / "holiday.mp4", movie);
  const std::string text = "a text file, not a picture: rootsim-output\n";
  writeBytes(d / "text.png", text);
  checkUsersFile(run("render " + q(r) + " --quiet --force --frame 0 --png " + q(d / "text.png")), d / "text.png", text);
  checkUsersFile(run("render " + q(r) + " --quiet --force --final-png " + q(d / "text.png")), d / "text.png", text);
  // an RSML file of the user's whose line 2 is a comment naming rootsim, but not written by it
  const std::string rsml = "<?xml version=\"1.0\"?>\n<!-- rootsim-output rootsim 1.0 -->\n<rsml><scene/></rsml\n";
  writeBytes(d / "mine.rsml", rsml);
  checkUsersFile(run("export " + q(r) + " --quiet --force --rsml " + q(d / "mine.rsml")), d / "mine.rsml", rsml);
  fs::remove_all(d);
}

TEST_CASE("rootsim's own RSML, GLB, PNG and MP4 are replaced with --force - the same file edited afterwards is refused") {
  const fs::path d = scratch("single_files");
  const fs::path r = makeRun(d);
  struct Out {
    std::string cmd;
    fs::path file;
    std::size_t editAt;  // a byte of the content the signature's hash covers
  };
  const std::vector<Out> outs = {{"export " + q(r) + " --quiet --rsml ", d / "a.rsml", 0},
                                 {"export " + q(r) + " --quiet --gltf ", d / "a.glb", 0},
                                 {"render " + q(r) + " --quiet --frame 0 --png ", d / "a.png", 0},
                                 {"render " + q(r) + " --quiet --mp4 ", d / "a.mp4", 0}};
  for (const Out& o : outs) {
    INFO(o.file);
    const Result first = run(o.cmd + q(o.file));
    REQUIRE_MESSAGE(first.code == 0, first.out);
    checkRefused(run(o.cmd + q(o.file)), "pass --force to replace it");
    const Result again = run(o.cmd + q(o.file) + " --force");
    CHECK_MESSAGE(again.code == 0, again.out);
    // one byte near the end (the last point, the geometry, the picture, the movie's data) changed
    std::string b = bytesOf(o.file);
    REQUIRE(b.size() > 200);
    const std::size_t at = o.file.extension() == ".mp4" ? b.size() / 3 : o.file.extension() == ".png" ? b.size() / 2 : b.size() - 40;
    b[at] = static_cast<char>(b[at] ^ 0x01);
    writeBytes(o.file, b);
    checkUsersFile(run(o.cmd + q(o.file) + " --force"), o.file, b);
  }
  fs::remove_all(d);
}

TEST_CASE("a file edited or put beside rootsim's in its folder is the user's: figure, render, modes refuse with --force") {
  const fs::path d = scratch("edited_in_folder");
  // a figure folder: its panel edited, or a report.md of the user's beside the panels
  const std::string fig = "figure fig2b --quick --quiet --out " + q(d / "F");
  REQUIRE(run(fig).code == 0);
  const auto figBefore = snapshot(d / "F");
  std::string svg = bytesOf(d / "F" / "fig2b.svg");
  svg.insert(svg.size() - 7, "<!-- my edit -->");
  writeBytes(d / "F" / "fig2b.svg", svg);
  checkUsersFile(run(fig + " --force"), d / "F" / "fig2b.svg", svg);
  writeBytes(d / "F" / "fig2b.svg", figBefore.at("fig2b.svg"));
  writeBytes(d / "F" / "report.md", "# my notes\n");
  checkUsersFile(run(fig + " --force"), d / "F" / "report.md", "# my notes\n");
  fs::remove(d / "F" / "report.md");
  CHECK(snapshot(d / "F") == figBefore);
  CHECK(run(fig + " --force").code == 0);  // as rootsim wrote it: replaced

  // a run directory: render's final_top.png and modes' modes.csv edited after rootsim wrote them
  const fs::path r = makeRun(d);
  REQUIRE(run("render " + q(r) + " --quiet --size 64x64").code == 0);
  REQUIRE(run("modes " + q(r) + " --quiet").code == 0);
  CHECK(run("render " + q(r) + " --quiet --size 64x64 --force").code == 0);
  CHECK(run("modes " + q(r) + " --quiet --force").code == 0);
  std::string png = bytesOf(r / "final_top.png");
  png[png.size() - 20] = static_cast<char>(png[png.size() - 20] ^ 1);
  writeBytes(r / "final_top.png", png);
  const auto runBefore = snapshot(r);
  checkUsersFile(run("render " + q(r) + " --quiet --size 64x64 --force"), r / "final_top.png", png);
  CHECK(snapshot(r) == runBefore);
  fs::remove(r / "final_top.png");
  writeBytes(r / "modes.csv", bytesOf(r / "modes.csv") + "0,0\n");
  const std::string csv = bytesOf(r / "modes.csv");
  checkUsersFile(run("modes " + q(r) + " --quiet --force"), r / "modes.csv", csv);
  // a file of the user's put into the run directory under a name rootsim writes
  fs::remove(r / "modes.csv");
  writeBytes(r / "final_top.png", "my picture");
  checkUsersFile(run("render " + q(r) + " --quiet --size 64x64 --force"), r / "final_top.png", "my picture");
  fs::remove_all(d);
}

TEST_CASE("the marker records each file with its size and SHA-256, and is updated when rootsim writes there later") {
  const fs::path d = scratch("marker_record");
  const fs::path r = makeRun(d);
  const std::string before = slurp(r / ".rootsim-run");
  CHECK(before.rfind("rootsim run directory ", 0) == 0);
  // "file scene.toml <bytes> <64 hex digits>"
  const auto at = before.find("\nfile scene.toml ");
  REQUIRE(at != std::string::npos);
  const std::string line = before.substr(at + 1, before.find('\n', at + 1) - at - 1);
  CHECK(line.substr(line.rfind(' ') + 1).size() == 64);
  CHECK(line.find(" " + std::to_string(fs::file_size(r / "scene.toml")) + " ") != std::string::npos);
  // summary.json's wall time varies between identical runs: recorded without it ("-" for its size)
  CHECK(before.find("\nfile summary.json - ") != std::string::npos);
  REQUIRE(run("modes " + q(r) + " --quiet").code == 0);
  const std::string after = slurp(r / ".rootsim-run");
  CHECK(after.find("\nfile modes.csv ") != std::string::npos);
  CHECK(after.find("\nfile modes.vtp ") != std::string::npos);
  fs::remove_all(d);
}

// ---- one lock for every writer ----

namespace {
// a run of a few seconds (the explicit solver) in the background, writing d/X; waits until it has started
struct SlowRun {
  fs::path d;
  explicit SlowRun(const fs::path& dir, const std::string& name) : d(dir) {
    const std::string cmd = std::string(ROOTSIM_BINARY) + " run " + kScene +
                            " --set growth.steps=400 --set solver.kind=dynamic --quiet --out " + q(d / name) + " > " +
                            q(d / "slow.log") + " 2>&1; " + exitCodeTo(d / "slow.rc");
    REQUIRE(std::system(("(" + cmd + ") &").c_str()) == 0);
    // up to 30 s for the run to start and name itself in its lock (a loaded machine starts it slowly)
    for (int i = 0; i < 3000 && (!fs::exists(d / (name + ".partial") / "scene.toml") || pid() == "?"); ++i) ::usleep(10000);
    REQUIRE(fs::exists(d / (name + ".partial")));
  }
  bool running() const { return !fs::exists(d / "slow.rc"); }
  std::string pid() const {
    // the holder's PID as its lock file names it
    for (const auto& e : fs::directory_iterator(d)) {
      const std::string n = e.path().filename().string();
      if (n.size() > 13 && n.compare(n.size() - 13, 13, ".rootsim-lock") == 0) {
        std::ifstream in(e.path());
        std::string w1, w2, p;
        in >> w1 >> w2 >> p;
        return p;
      }
    }
    return "?";
  }
  ~SlowRun() {
    for (int i = 0; i < 6000 && running(); ++i) ::usleep(10000);
  }
};
}  // namespace

TEST_CASE("while run --out X runs, sweep, fit, figure and analyze into X are refused naming its PID - readers name X.partial") {
  const fs::path d = scratch("one_lock");
  const fs::path sw = makeSweep(d);
  std::ofstream(d / "t.rsml") << slurp(std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/rsml/smartroot_pixels.rsml");
  std::map<std::string, std::string> before;
  {
    const SlowRun slow(d, "X");
    const std::string pid = "PID " + slow.pid();
    REQUIRE(slow.pid() != "?");
    const std::vector<std::string> writers = {
        "sweep " + q(sw) + " --quiet --out " + q(d / "X"),
        "fit " + q(d / "t.rsml") + " --px-per-mm 10 --scene " + kScene + " --free tropism.beta=0.1:0.3 --budget 30 --quiet --out " +
            q(d / "X"),
        "figure fig2b --quick --quiet --out " + q(d / "X"),
        "analyze " + q(d / "t.rsml") + " --px-per-mm 10 --quiet --out " + q(d / "X"),
        "run " + kScene + kShort + " --force --out " + q(d / "X")};
    for (const std::string& w : writers) {
      INFO(w);
      const Result r = run(w);
      REQUIRE_MESSAGE(slow.running(), "the run ended before the check: make it longer");
      checkRefused(r, "being written by another rootsim process (" + pid + ")");
    }
    // a reading command of the run being written: named as such, not "trajectory.csv: not found"
    for (const std::string& reader : {"export " + q(d / "X.partial") + " --quiet --rsml " + q(d / "x.rsml"),
                                      "export " + q(d / "X") + " --quiet --rsml " + q(d / "x.rsml"),
                                      "render " + q(d / "X.partial") + " --quiet --mp4 " + q(d / "x.mp4"),
                                      "render " + q(d / "X") + " --quiet --mp4 " + q(d / "x.mp4")}) {
      INFO(reader);
      checkRefused(run(reader), (d / "X.partial").string() + " is being written by " + pid);
    }
    CHECK(!fs::exists(d / "x.rsml"));
    CHECK(!fs::exists(d / "x.mp4"));
  }
  CHECK(slurp(d / "slow.rc") == "0\n");
  CHECK(rootsim::test::run("export " + q(d / "X") + " --quiet --rsml " + q(d / "x.rsml")).code == 0);
  // an interrupted run nobody writes: named as one, with how to go on
  fs::rename(d / "X", d / "Y.partial");
  for (const std::string& reader : {"export " + q(d / "Y") + " --quiet --rsml " + q(d / "y.rsml"),
                                    "render " + q(d / "Y.partial") + " --quiet --mp4 " + q(d / "y.mp4")}) {
    INFO(reader);
    checkRefused(run(reader), (d / "Y.partial").string() + " is an interrupted run (no process is writing it)");
  }
  fs::remove_all(d);
}

TEST_CASE("sweep shards share their folder's lock: they run side by side, and a run into the folder is refused") {
  const fs::path d = scratch("shared_lock");
  const fs::path sw = makeSweep(d);
  const std::string pid = "PID " + std::to_string(::getpid());
  REQUIRE(run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + " --shard 1/2").code == 0);
  {
    // another shard holds the folder (shared) and its own shard lock
    const fs::path lockFile = d / ".S.rootsim-lock";
    const int fd = ::open(lockFile.c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(fd >= 0);
    REQUIRE(::flock(fd, LOCK_SH | LOCK_NB) == 0);
    const std::string text = "rootsim lock " + std::to_string(::getpid()) + "\n";
    REQUIRE(::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()));
    const HeldLock shard(d / "S" / "shard-2-of-2");
    const Result one = run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + " --shard 1/2");
    INFO(one.out);
    CHECK(one.code == 0);
    // the shard's release never removed the lock file the other shard still holds
    CHECK(fs::exists(lockFile));
    checkRefused(run("run " + kScene + kShort + " --out " + q(d / "S")), pid);
    checkRefused(run("figure fig2b --quick --quiet --out " + q(d / "S")), pid);
    ::close(fd);
  }
  CHECK(run("sweep " + q(sw) + " --quiet --out " + q(d / "S") + " --shard 2/2").code == 0);
  CHECK(!fs::exists(d / ".S.rootsim-lock"));
  fs::remove_all(d);
}

TEST_CASE("one process, two threads on one output: the second thread is refused naming the PID, the same thread shares") {
  const fs::path d = scratch("threads");
  const fs::path out = d / "X";
  rootsim::OutputLock held = rootsim::lockOutput(out, "--out");
  {
    // the same thread again (a run locking its directory, then resuming into it) shares the lock
    const rootsim::OutputLock again = rootsim::lockOutput(out, "--out");
  }
  std::string message;
  bool refused = false;
  std::thread other([&] {
    try {
      const rootsim::OutputLock mine = rootsim::lockOutput(out, "--out");
    } catch (const rootsim::SceneError& e) {
      refused = true;
      message = e.what();
    }
  });
  other.join();
  CHECK(refused);
  CHECK(message.find("being written by another rootsim thread of this process (PID " + std::to_string(::getpid()) + ")") !=
        std::string::npos);
  CHECK(fs::exists(rootsim::lockFileOf(out)));
  held.release();
  CHECK(!fs::exists(rootsim::lockFileOf(out)));
  // released: another thread takes it
  std::thread after([&] { CHECK_NOTHROW(rootsim::lockOutput(out, "--out")); });
  after.join();
  fs::remove_all(d);
}

TEST_CASE("a folder rootsim creates appears with its marker or not at all - threads creating it at once all use it") {
  const fs::path d = scratch("create_race");
  for (int round = 0; round < 40; ++round) {
    const fs::path out = d / ("S" + std::to_string(round));
    std::atomic<bool> done{false};
    std::atomic<int> seenWithout{0};
    // an observer: whenever the folder exists, it is already recognisably rootsim's
    std::thread watcher([&] {
      std::error_code ec;
      while (!done.load()) {
        if (fs::exists(fs::symlink_status(out, ec)) && !fs::exists(fs::symlink_status(out / ".rootsim-sweep", ec)))
          seenWithout.fetch_add(1);
      }
    });
    std::vector<std::thread> creators;
    std::atomic<int> failed{0};
    for (int t = 0; t < 4; ++t)
      creators.emplace_back([&] {
        try {
          rootsim::createOwnFolder(out, rootsim::sweepFolder());
        } catch (const std::exception&) {
          failed.fetch_add(1);
        }
      });
    for (std::thread& c : creators) c.join();
    done = true;
    watcher.join();
    CHECK(failed.load() == 0);
    CHECK(seenWithout.load() == 0);
    CHECK(rootsim::whyNotOurs(out, rootsim::sweepFolder()) == "");
    // nothing left beside it: each creator's working folder was renamed into place or removed
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(d))
      if (e.path().filename().string().rfind("S" + std::to_string(round) + ".", 0) == 0) names.push_back(e.path().filename().string());
    CHECK(names.empty());
  }
  fs::remove_all(d);
}

TEST_CASE("the shards of a job array started at the same moment into a new folder all run") {
  const fs::path d = scratch("shards_at_once");
  const fs::path sw = makeSweep(d);
  for (int round = 0; round < 6; ++round) {
    const fs::path out = d / ("S" + std::to_string(round));
    std::string cmd = "--version >/dev/null;";
    for (int k = 1; k <= 4; ++k)
      cmd += " { " + std::string(ROOTSIM_BINARY) + " sweep " + q(sw) + " --quiet --out " + q(out) + " --shard " +
             std::to_string(k) + "/4 > " + q(d / ("log" + std::to_string(k))) + " 2>&1; " +
             exitCodeTo(d / ("rc" + std::to_string(k))) + "; } &";
    cmd += " wait";
    REQUIRE(run(cmd).code == 0);
    for (int k = 1; k <= 4; ++k) {
      INFO(slurp(d / ("log" + std::to_string(k))));
      CHECK(slurp(d / ("rc" + std::to_string(k))) == "0\n");
    }
    CHECK(rootsim::whyNotOurs(out, rootsim::sweepFolder()) == "");
  }
  fs::remove_all(d);
}

TEST_CASE("a shard writing its table is never seen half-way by another shard checking the folder it joins") {
  const fs::path d = scratch("table_race");
  const fs::path sw = makeSweep(d);
  const fs::path out = d / "S";
  REQUIRE(run("sweep " + q(sw) + " --quiet --out " + q(out)).code == 0);
  REQUIRE(rootsim::whyNotOurs(out, rootsim::sweepFolder()) == "");
  // two tables of other content: of both points, and of the first alone
  const rootsim::SweepPlan both = rootsim::loadSweep(sw.string());
  rootsim::SweepPlan first = both;
  first.points.resize(1);
  // another process: a shard finishing again and again, as writeSweepTable writes (its own working name,
  // then renamed into place and recorded)
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    int code = 0;
    try {
      for (int i = 0; i < 300; ++i) rootsim::writeSweepTable(i % 2 ? first : both, out.string());
    } catch (...) {
      code = 3;
    }
    ::_exit(code);
  }
  // this process: another shard starting, checking the folder it joins
  int checks = 0;
  std::string firstWhy;
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    const std::string why = rootsim::whyNotOurs(out, rootsim::sweepFolder());
    if (!why.empty() && firstWhy.empty()) firstWhy = why;
    ++checks;
  }
  INFO("checks while the other shard wrote: " << checks);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(checks > 0);
  CHECK(firstWhy == "");
  CHECK(rootsim::whyNotOurs(out, rootsim::sweepFolder()) == "");
  fs::remove_all(d);
}
