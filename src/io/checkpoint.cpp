// Checkpoint files (include/rootsim/checkpoint.hpp): raw little-endian bytes, written and read in one
// fixed order by the Out / In helpers below.
#include "rootsim/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"

namespace fs = std::filesystem;

namespace rootsim {

static_assert(std::endian::native == std::endian::little, "checkpoints are written as little-endian raw bytes");

namespace {

constexpr char kMagic[8] = {'R', 'S', 'C', 'H', 'K', 'P', 'T', '\0'};
constexpr std::size_t kHeaderBytes = 40;
// no array in a checkpoint is longer than this (elements are capped far below by the scene limits)
constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 28;

std::uint64_t fnv1a(const char* p, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(p[i])) * 1099511628211ull;
  return h;
}

// appends raw values
struct Out {
  std::string b;
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    b.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void count(std::size_t n) { pod(static_cast<std::uint64_t>(n)); }
  void raw(const void* p, std::size_t bytes) {
    if (bytes > 0) b.append(static_cast<const char*>(p), bytes);  // an empty vector's data() may be null
  }
  void mat(const Eigen::Matrix3Xd& m) {
    count(static_cast<std::size_t>(m.cols()));
    raw(m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
  }
  void vec(const Eigen::VectorXd& v) {
    count(static_cast<std::size_t>(v.size()));
    raw(v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
  }
  template <class T>
  void list(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    count(v.size());
    raw(v.data(), sizeof(T) * v.size());
  }
  // Eigen's fixed-size matrices are plain column-major doubles (not trivially copyable for the compiler)
  void mats(const std::vector<Mat3>& v) {
    count(v.size());
    for (const Mat3& q : v) raw(q.data(), 9 * sizeof(double));
  }
  void str(const std::string& s) {
    count(s.size());
    raw(s.data(), s.size());
  }
};

// reads raw values, every length checked against what is left
struct In {
  const std::string& b;
  std::size_t pos;
  std::size_t end;
  std::string file;
  [[noreturn]] void bad(const std::string& why) const {
    throw SceneError(file + ": corrupt checkpoint (" + why + " at byte " + std::to_string(pos) +
                     "); rerun with --force to discard it and start again");
  }
  void take(void* p, std::size_t bytes) {
    if (bytes > end - pos) bad("truncated");
    if (bytes > 0) std::memcpy(p, b.data() + pos, bytes);  // an empty vector's data() may be null
    pos += bytes;
  }
  template <class T>
  T pod() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::size_t count(std::size_t elemBytes) {
    const auto n = pod<std::uint64_t>();
    if (n > kMaxCount || n * elemBytes > end - pos) bad("array length " + std::to_string(n) + " out of range");
    return static_cast<std::size_t>(n);
  }
  void mat(Eigen::Matrix3Xd& m) {
    const std::size_t n = count(3 * sizeof(double));
    m.resize(3, static_cast<Eigen::Index>(n));
    take(m.data(), 3 * sizeof(double) * n);
  }
  void vec(Eigen::VectorXd& v) {
    const std::size_t n = count(sizeof(double));
    v.resize(static_cast<Eigen::Index>(n));
    take(v.data(), sizeof(double) * n);
  }
  template <class T>
  void list(std::vector<T>& v) {
    const std::size_t n = count(sizeof(T));
    v.resize(n);
    take(v.data(), sizeof(T) * n);
  }
  void mats(std::vector<Mat3>& v) {
    const std::size_t n = count(9 * sizeof(double));
    v.resize(n);
    for (Mat3& q : v) take(q.data(), 9 * sizeof(double));
  }
  void str(std::string& s) {
    const std::size_t n = count(1);
    s.assign(b.data() + pos, n);
    pos += n;
  }
};

// StepRecord field by field (no padding bytes in the file)
void putRecord(Out& o, const StepRecord& r) {
  o.pod(r.step);
  o.pod(r.timeH);
  o.pod(r.length);
  o.pod(r.elements);
  o.pod(r.thetaTip);
  o.pod(r.zone);
  o.pod(r.substeps);
  o.pod(r.iterations);
  o.pod(r.lowestEigenvalue);
  o.pod(r.residualForce);
  o.pod(r.splits);
  o.pod(r.unstable);
  o.raw(r.tip.data(), 3 * sizeof(double));
  o.pod(r.selfContacts);
  o.pod(r.minSelfDistance);
  o.pod(r.obstacleContacts);
  o.pod(r.slipEvents);
  o.pod(r.frictionWork);
}
void getRecord(In& in, StepRecord& r) {
  r.step = in.pod<int>();
  r.timeH = in.pod<double>();
  r.length = in.pod<double>();
  r.elements = in.pod<int>();
  r.thetaTip = in.pod<double>();
  r.zone = in.pod<ZoneObservables>();
  r.substeps = in.pod<long>();
  r.iterations = in.pod<long>();
  r.lowestEigenvalue = in.pod<double>();
  r.residualForce = in.pod<double>();
  r.splits = in.pod<int>();
  r.unstable = in.pod<int>();
  in.take(r.tip.data(), 3 * sizeof(double));
  r.selfContacts = in.pod<int>();
  r.minSelfDistance = in.pod<double>();
  r.obstacleContacts = in.pod<int>();
  r.slipEvents = in.pod<long>();
  r.frictionWork = in.pod<double>();
}

// A checkpoint whose checksum matches may still be forged or written by a bug: every count and
// position is checked against its range and against the run's own files it describes (a negative
// frame count resumed to other output). Files shorter than the checkpoint says are left to the caller
// (resuming refuses them naming the file).
[[noreturn]] void refuse(const fs::path& path, const std::string& field, const std::string& why) {
  throw SceneError(path.string() + ": corrupt checkpoint (" + field + " " + why +
                   "); rerun with --force to discard it and start again");
}

// the first `bytes` bytes of the run's stream `name` (name.tmp while the run is going, else name);
// false when the file holds fewer
bool streamPrefix(const fs::path& dir, const std::string& name, std::uint64_t bytes, std::string& out) {
  std::error_code ec;
  fs::path f = dir / (name + ".tmp");
  if (!fs::is_regular_file(f, ec)) f = dir / name;
  if (!fs::is_regular_file(f, ec) || fs::file_size(f, ec) < bytes || ec) return false;
  std::ifstream in(f, std::ios::binary);
  out.assign(static_cast<std::size_t>(bytes), '\0');
  return static_cast<bool>(in.read(out.data(), static_cast<std::streamsize>(bytes)));
}

// the number of whole snapshots in the first bytes of a trajectory.bin (layout in outputs.hpp), or -1
// when they do not end at a snapshot's end
long binaryFrames(const std::string& b) {
  if (b.size() < 16) return -1;
  std::size_t pos = 16;
  long frames = 0;
  while (pos < b.size()) {
    if (b.size() - pos < 24) return -1;
    std::int32_t nodes = 0;
    std::uint32_t fields = 0;
    std::memcpy(&nodes, b.data() + pos + 8, 4);
    std::memcpy(&fields, b.data() + pos + 12, 4);
    if (nodes < 2 || (fields & ~7u) != 0) return -1;
    const std::uint64_t perNode = 10 + (fields & 1u ? 1 : 0) + (fields & 2u ? 1 : 0) + (fields & 4u ? 3 : 0);
    const std::uint64_t size = 24 + (perNode * static_cast<std::uint64_t>(nodes) - 7) * sizeof(double);
    if (size > b.size() - pos) return -1;
    pos += static_cast<std::size_t>(size);
    ++frames;
  }
  return frames;
}

// the first field of the last line of a text that ends with a newline ("" when it does not)
std::string lastRowFirstField(const std::string& t) {
  if (t.empty() || t.back() != '\n') return "";
  const std::size_t start = t.rfind('\n', t.size() - 2);
  const std::size_t from = start == std::string::npos ? 0 : start + 1;
  return t.substr(from, t.find(',', from) == std::string::npos ? std::string::npos : t.find(',', from) - from);
}

void checkRanges(const RunCheckpoint& c, long elements, const fs::path& path) {
  auto num = [](auto v) { return std::to_string(v); };
  const SimulationCarry& k = c.carry;
  const RunAccumulators& a = c.acc;
  const WriterPositions& w = c.writers;
  // a checkpoint is written after a growth step (1, 2, ...): every output step so far left at most one
  // snapshot (and time-series row), the initial state's included
  if (c.step < 1) refuse(path, "growth step", num(c.step) + " out of range (>= 1)");
  const long maxFrames = static_cast<long>(c.step) + 1;
  if (!(std::isfinite(c.state.time) && c.state.time >= 0))
    refuse(path, "rod time", "out of range (finite, >= 0)");
  for (const auto& [name, v] : {std::pair<const char*, long>{"total substeps", k.totalSubsteps},
                                {"total iterations", k.totalIterations},
                                {"slip events", k.slipEvents},
                                {"contact list builds", k.pairsBuilds},
                                {"max substeps", a.maxSubsteps},
                                {"max self-contacts", a.maxSelfContacts},
                                {"Newton negative eigenvalues", k.newtonNegative},
                                {"Newton factors dofs", k.newtonFactorsDofs},
                                {"Newton factors first block", k.newtonFactorsFirstBlock},
                                {"Newton first free node", k.newtonFirstFreeNode},
                                {"Newton mature age", k.newtonMatureAge},
                                {"sparse lower bandwidth", k.newtonSparse.kl},
                                {"sparse upper bandwidth", k.newtonSparse.ku}})
    if (v < 0) refuse(path, name, num(v) + " out of range (>= 0)");
  if (k.newtonFirstFreeNode > elements + 1)
    refuse(path, "Newton first free node", num(k.newtonFirstFreeNode) + " out of range (0 .. " + num(elements + 1) + ")");
  if (k.newtonSparse.n < -1)  // -1: no sparse pattern
    refuse(path, "sparse pattern size", num(k.newtonSparse.n) + " out of range (>= -1)");
  if (k.pairsBuiltElements < -1)  // -1: no contact list built
    refuse(path, "contact list elements", num(k.pairsBuiltElements) + " out of range (>= -1)");
  if (!(std::isfinite(a.wallBefore) && a.wallBefore >= 0))
    refuse(path, "earlier wall time", "out of range (finite, >= 0 s)");
  if (w.trajectoryFrames < 0 || w.trajectoryFrames > maxFrames)
    refuse(path, "trajectory frame count", num(w.trajectoryFrames) + " out of range (0 .. " + num(maxFrames) +
                                               ": at most one per growth step up to " + num(c.step) + ", and the initial one)");
  if (static_cast<long>(w.vtkEntries.size()) > maxFrames)
    refuse(path, "ParaView entry count", num(w.vtkEntries.size()) + " out of range (0 .. " + num(maxFrames) + ")");
  for (const auto& [t, name] : w.vtkEntries)
    if (!(std::isfinite(t) && t >= 0)) refuse(path, "ParaView entry time", "out of range (finite, >= 0 h)");
  // the run's own files agree (where they hold what the checkpoint says: shorter ones are refused by
  // the caller, naming the file)
  const fs::path dir = path.parent_path();
  const bool trajectory = w.trajectoryBytes > 0 || w.trajectoryBinaryBytes > 0;
  if (!trajectory && w.trajectoryFrames != 0)
    refuse(path, "trajectory frame count", num(w.trajectoryFrames) + " with no trajectory written (must be 0)");
  std::string t;
  if (w.trajectoryBinaryBytes > 0 && streamPrefix(dir, "trajectory.bin", w.trajectoryBinaryBytes, t))
    if (binaryFrames(t) != w.trajectoryFrames)
      refuse(path, "trajectory frame count", num(w.trajectoryFrames) + " disagrees with trajectory.bin (" +
                                                 num(binaryFrames(t)) + " whole frames in its first " +
                                                 num(w.trajectoryBinaryBytes) + " bytes)");
  if (w.trajectoryBytes > 0 && streamPrefix(dir, "trajectory.csv", w.trajectoryBytes, t))
    if (lastRowFirstField(t) != (w.trajectoryFrames > 0 ? num(w.trajectoryFrames - 1) : std::string("frame")))
      refuse(path, "trajectory frame count", num(w.trajectoryFrames) + " disagrees with trajectory.csv (its first " +
                                                 num(w.trajectoryBytes) + " bytes end in frame " +
                                                 printable(lastRowFirstField(t)) + ")");
  if (w.timeseriesBytes > 0 && streamPrefix(dir, "timeseries.csv", w.timeseriesBytes, t)) {
    const long rows = static_cast<long>(std::count(t.begin(), t.end(), '\n')) - 1;
    const std::string last = lastRowFirstField(t);
    if (last.empty() || rows < 1 || rows > maxFrames || (trajectory && rows != w.trajectoryFrames))
      refuse(path, "time-series position",
             num(w.timeseriesBytes) + (trajectory ? " does not end after row " + num(w.trajectoryFrames) +
                                                        " of timeseries.csv (one row per trajectory frame)"
                                                  : " does not end after one of the first " + num(maxFrames) +
                                                        " rows of timeseries.csv"));
  }
}

}  // namespace

std::uint64_t sceneHash(const std::string& resolvedToml) { return fnv1a(resolvedToml.data(), resolvedToml.size()); }

void writeCheckpoint(const fs::path& path, const RunCheckpoint& c) {
  static_assert(std::is_trivially_copyable_v<ZoneObservables>);
  Out o;
  // the rod state
  const RodState& s = c.state;
  o.mat(s.x);
  o.mat(s.v);
  o.mats(s.Q);
  o.mat(s.w);
  o.vec(s.l0);
  o.vec(s.S);
  o.mat(s.kappa0);
  o.mat(s.anchor);
  o.list(s.anchored);
  o.mat(s.plateStick);
  o.list(s.hasPlateStick);
  o.mat(s.obstacleStick);
  o.list(s.hasObstacleStick);
  o.raw(s.clampFrame.data(), 9 * sizeof(double));
  o.pod(s.time);
  // the simulation's carry
  const SimulationCarry& k = c.carry;
  o.pod(k.step);
  o.pod(k.totalSubsteps);
  o.pod(k.totalIterations);
  o.pod(k.thetaUnwrapped);
  o.pod(k.slipEvents);
  o.pod(k.frictionWork);
  putRecord(o, k.last);
  o.list(k.newtonMode);
  o.pod(k.newtonModeSize);
  o.pod(k.newtonFirstFreeNode);
  o.pod(k.newtonNegative);
  o.pod(k.newtonLowestEigenvalue);
  o.pod(static_cast<std::uint8_t>(k.newtonFactorsValid));
  o.pod(static_cast<std::uint8_t>(k.newtonSparseActive));
  o.pod(k.newtonFactorsDofs);
  o.pod(k.newtonFactorsFirstBlock);
  o.pod(k.newtonBandN);
  o.pod(k.newtonBandKl);
  o.pod(k.newtonBandKu);
  o.list(k.newtonBand);
  o.list(k.newtonPivots);
  o.pod(k.newtonSparse.n);
  o.pod(k.newtonSparse.kl);
  o.pod(k.newtonSparse.ku);
  o.list(k.newtonSparse.places);
  o.list(k.newtonSparse.pivotValues);
  o.list(k.newtonSparse.lastValues);
  o.list(k.newtonMatureK);
  o.pod(k.newtonMatureValid);
  o.pod(k.newtonMatureAge);
  o.list(k.pairs);
  o.mat(k.pairsBuiltX);
  o.pod(k.pairsBuiltElements);
  o.pod(k.pairsBuiltRestLength);
  o.pod(k.pairsBuilds);
  // the run's accumulators
  const RunAccumulators& a = c.acc;
  for (double v : {a.snapFirst, a.snapVertical, a.snapPrevTheta, a.snapPrevTime}) o.pod(v);
  o.pod(a.maxSubsteps);
  o.pod(a.maxSelfContacts);
  o.pod(a.minSelfDistance);
  o.pod(a.wallBefore);
  // the writers
  o.pod(c.writers.timeseriesBytes);
  o.pod(c.writers.trajectoryBytes);
  o.pod(c.writers.trajectoryBinaryBytes);
  o.pod(c.writers.trajectoryFrames);
  o.count(c.writers.vtkEntries.size());
  for (const auto& [t, f] : c.writers.vtkEntries) {
    o.pod(t);
    o.str(f);
  }

  Out h;
  h.raw(kMagic, sizeof kMagic);
  h.pod(kCheckpointVersion);
  h.pod(std::uint32_t{0});
  h.pod(c.sceneHash);
  h.pod(static_cast<std::int32_t>(c.step));
  h.pod(std::uint32_t{0});
  h.pod(static_cast<std::uint64_t>(o.b.size()));
  h.b += o.b;
  h.pod(fnv1a(o.b.data(), o.b.size()));
  writeFileAtomic(path, h.b);
}

RunCheckpoint readCheckpoint(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path.string() + ": cannot open the checkpoint");
  const std::string b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  In in{b, 0, b.size(), path.string()};
  if (b.size() < kHeaderBytes + 8 || std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
    in.bad("not a rootsim checkpoint, or truncated");
  in.pos = sizeof kMagic;
  const auto version = in.pod<std::uint32_t>();
  if (version != kCheckpointVersion)
    in.bad("version " + std::to_string(version) + ", this rootsim reads version " + std::to_string(kCheckpointVersion));
  in.pod<std::uint32_t>();
  RunCheckpoint c;
  c.sceneHash = in.pod<std::uint64_t>();
  c.step = in.pod<std::int32_t>();
  in.pod<std::uint32_t>();
  const auto payload = in.pod<std::uint64_t>();
  if (payload != b.size() - kHeaderBytes - 8) in.bad("length " + std::to_string(b.size()) + " does not match its header");
  std::uint64_t sum = 0;
  std::memcpy(&sum, b.data() + b.size() - 8, 8);
  if (sum != fnv1a(b.data() + kHeaderBytes, payload)) in.bad("checksum mismatch");
  in.end = b.size() - 8;

  RodState& s = c.state;
  in.mat(s.x);
  in.mat(s.v);
  in.mats(s.Q);
  in.mat(s.w);
  in.vec(s.l0);
  in.vec(s.S);
  in.mat(s.kappa0);
  in.mat(s.anchor);
  in.list(s.anchored);
  in.mat(s.plateStick);
  in.list(s.hasPlateStick);
  in.mat(s.obstacleStick);
  in.list(s.hasObstacleStick);
  in.take(s.clampFrame.data(), 9 * sizeof(double));
  s.time = in.pod<double>();
  // the fields must agree on the element count (a checksum collision aside, a writer bug)
  const long n = s.l0.size();
  if (n < 1 || s.x.cols() != n + 1 || s.v.cols() != n + 1 || static_cast<long>(s.Q.size()) != n || s.w.cols() != n ||
      s.S.size() != n + 1 || s.kappa0.cols() != std::max(n - 1, 0L) || s.anchor.cols() != n + 1 ||
      static_cast<long>(s.anchored.size()) != n + 1 || s.plateStick.cols() != n + 1 ||
      static_cast<long>(s.hasPlateStick.size()) != n + 1 || s.obstacleStick.cols() != n + 1 ||
      static_cast<long>(s.hasObstacleStick.size()) != n + 1)
    in.bad("rod state fields disagree on the element count");
  SimulationCarry& k = c.carry;
  k.step = in.pod<int>();
  k.totalSubsteps = in.pod<long>();
  k.totalIterations = in.pod<long>();
  k.thetaUnwrapped = in.pod<double>();
  k.slipEvents = in.pod<long>();
  k.frictionWork = in.pod<double>();
  getRecord(in, k.last);
  in.list(k.newtonMode);
  k.newtonModeSize = in.pod<int>();
  k.newtonFirstFreeNode = in.pod<int>();
  k.newtonNegative = in.pod<int>();
  k.newtonLowestEigenvalue = in.pod<double>();
  k.newtonFactorsValid = in.pod<std::uint8_t>() != 0;
  k.newtonSparseActive = in.pod<std::uint8_t>() != 0;
  k.newtonFactorsDofs = in.pod<int>();
  k.newtonFactorsFirstBlock = in.pod<int>();
  k.newtonBandN = in.pod<int>();
  k.newtonBandKl = in.pod<int>();
  k.newtonBandKu = in.pod<int>();
  in.list(k.newtonBand);
  in.list(k.newtonPivots);
  k.newtonSparse.n = in.pod<int>();
  k.newtonSparse.kl = in.pod<int>();
  k.newtonSparse.ku = in.pod<int>();
  in.list(k.newtonSparse.places);
  in.list(k.newtonSparse.pivotValues);
  in.list(k.newtonSparse.lastValues);
  in.list(k.newtonMatureK);
  k.newtonMatureValid = in.pod<int>();
  k.newtonMatureAge = in.pod<int>();
  in.list(k.pairs);
  in.mat(k.pairsBuiltX);
  k.pairsBuiltElements = in.pod<int>();
  k.pairsBuiltRestLength = in.pod<double>();
  k.pairsBuilds = in.pod<long>();
  if (k.step != c.step || k.newtonModeSize < 0 || static_cast<std::size_t>(k.newtonModeSize) > k.newtonMode.size() ||
      k.newtonMatureValid < 0 || 3 * static_cast<std::size_t>(k.newtonMatureValid) > k.newtonMatureK.size())
    in.bad("inconsistent solver state");
  for (const auto& [i, j] : k.pairs)
    if (i < 0 || j < 0 || i >= n || j >= n) in.bad("contact pair out of range");
  if (k.newtonFactorsValid && !k.newtonSparseActive &&
      (k.newtonBandN < 1 || k.newtonBandKl < 0 || k.newtonBandKu < 0 ||
       k.newtonBand.size() != static_cast<std::size_t>(2 * k.newtonBandKl + k.newtonBandKu + 1) *
                                  static_cast<std::size_t>(k.newtonBandN) ||
       k.newtonPivots.size() != static_cast<std::size_t>(k.newtonBandN)))
    in.bad("inconsistent Newton factors");
  RunAccumulators& a = c.acc;
  for (double* v : {&a.snapFirst, &a.snapVertical, &a.snapPrevTheta, &a.snapPrevTime}) *v = in.pod<double>();
  a.maxSubsteps = in.pod<long>();
  a.maxSelfContacts = in.pod<int>();
  a.minSelfDistance = in.pod<double>();
  a.wallBefore = in.pod<double>();
  c.writers.timeseriesBytes = in.pod<std::uint64_t>();
  c.writers.trajectoryBytes = in.pod<std::uint64_t>();
  c.writers.trajectoryBinaryBytes = in.pod<std::uint64_t>();
  c.writers.trajectoryFrames = in.pod<int>();
  const std::size_t entries = in.count(sizeof(double) + 8);
  for (std::size_t i = 0; i < entries; ++i) {
    const auto t = in.pod<double>();
    std::string name;
    in.str(name);
    if (name.rfind("vtk/step_", 0) != 0 || name.find("..") != std::string::npos) in.bad("bad ParaView entry");
    c.writers.vtkEntries.emplace_back(t, std::move(name));
  }
  if (in.pos != in.end) in.bad("trailing bytes");
  checkRanges(c, static_cast<long>(n), path);
  return c;
}

}  // namespace rootsim
