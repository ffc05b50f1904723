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

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};
template <class T>
struct IsMemory : std::false_type {};
template <class S>
struct IsMemory<Memory<S>> : std::true_type {};
// a list of structs with field lists (each written field by field)
template <class T>
constexpr bool kVectorOfFields = false;
template <class T>
constexpr bool kVectorOfFields<std::vector<T>> = HasFields<T>;
using VtkEntries = std::vector<std::pair<double, std::string>>;

// one field as its bytes (checkpoint.hpp: the payload); a struct with a field list field by field (no
// padding bytes in the file)
template <class T>
void put(Out& o, const T& v) {
  if constexpr (HasFields<T>) {
    visitFields(v, [&](const char*, const auto& f) { put(o, f); });
  } else if constexpr (IsMemory<T>::value) {
    forEachCarried(v, [&](const auto&, const auto& f) { put(o, f); });
  } else if constexpr (std::is_same_v<T, bool>) {
    o.pod(static_cast<std::uint8_t>(v));
  } else if constexpr (std::is_same_v<T, Eigen::Matrix3Xd>) {
    o.mat(v);
  } else if constexpr (std::is_same_v<T, Eigen::VectorXd>) {
    o.vec(v);
  } else if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, Mat3>) {
    o.raw(v.data(), sizeof(double) * T::SizeAtCompileTime);
  } else if constexpr (std::is_same_v<T, std::vector<Mat3>>) {
    o.mats(v);
  } else if constexpr (std::is_same_v<T, VtkEntries>) {
    o.count(v.size());
    for (const auto& [t, f] : v) {
      o.pod(t);
      o.str(f);
    }
  } else if constexpr (kVectorOfFields<T>) {
    o.count(v.size());
    for (const auto& e : v) put(o, e);
  } else if constexpr (IsVector<T>::value) {
    o.list(v);
  } else if constexpr (std::is_same_v<T, BandLU>) {
    o.pod(v.size());
    o.pod(v.kl());
    o.pod(v.ku());
    o.list(v.storage());
    o.list(v.pivots());
  } else {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>, "a field the checkpoint cannot write");
    o.pod(v);
  }
}

template <class T>
void get(In& in, T& v) {
  if constexpr (HasFields<T>) {
    visitFields(v, [&](const char*, auto& f) { get(in, f); });
  } else if constexpr (IsMemory<T>::value) {
    forEachCarried(v, [&](const auto&, auto& f) { get(in, f); });
  } else if constexpr (std::is_same_v<T, bool>) {
    v = in.pod<std::uint8_t>() != 0;
  } else if constexpr (std::is_same_v<T, Eigen::Matrix3Xd>) {
    in.mat(v);
  } else if constexpr (std::is_same_v<T, Eigen::VectorXd>) {
    in.vec(v);
  } else if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, Mat3>) {
    in.take(v.data(), sizeof(double) * T::SizeAtCompileTime);
  } else if constexpr (std::is_same_v<T, std::vector<Mat3>>) {
    in.mats(v);
  } else if constexpr (std::is_same_v<T, VtkEntries>) {
    const std::size_t entries = in.count(sizeof(double) + 8);
    v.clear();
    for (std::size_t i = 0; i < entries; ++i) {
      const auto t = in.pod<double>();
      std::string name;
      in.str(name);
      if (name.rfind("vtk/step_", 0) != 0 || name.find("..") != std::string::npos) in.bad("bad ParaView entry");
      v.emplace_back(t, std::move(name));
    }
  } else if constexpr (kVectorOfFields<T>) {
    // each element at least one byte: the count is bounded by what is left
    v.assign(in.count(1), typename T::value_type{});
    for (auto& e : v) get(in, e);
  } else if constexpr (IsVector<T>::value) {
    in.list(v);
  } else if constexpr (std::is_same_v<T, BandLU>) {
    const int n = in.pod<int>(), kl = in.pod<int>(), ku = in.pod<int>();
    std::vector<double> ab;
    std::vector<int> piv;
    in.list(ab);
    in.list(piv);
    v = BandLU{};
    // none (n = 0, nothing stored), or factors that fit
    if ((n != 0 || kl != 0 || ku != 0 || !ab.empty() || !piv.empty()) && !v.restore(n, kl, ku, ab, piv))
      in.bad("inconsistent Newton factors");
  } else {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>, "a field the checkpoint cannot read");
    v = in.pod<T>();
  }
}

// the first field whose bytes differ (through the same field lists), as a dotted name
template <class T>
std::string difference(const T& a, const T& b, const std::string& name) {
  std::string d;
  if constexpr (HasFields<T>) {
    forEachField<T>([&](const auto& f) {
      if (d.empty()) d = difference(a.*f.member, b.*f.member, name + "." + f.name);
    });
  } else if constexpr (kVectorOfFields<T>) {
    if (a.size() != b.size()) return name + ".size";
    for (size_t i = 0; i < a.size() && d.empty(); ++i) d = difference(a[i], b[i], name + "[" + std::to_string(i) + "]");
  } else if constexpr (IsMemory<T>::value) {
    forEachCarried(a, b, [&](const auto& f, const auto& va, const auto& vb) {
      if (d.empty()) d = difference(va, vb, name + "." + f.name);
    });
  } else {
    Out oa, ob;
    put(oa, a);
    put(ob, b);
    if (oa.b != ob.b) d = name;
  }
  return d;
}

// A checkpoint whose checksum matches may still be forged or written by a bug: every count and
// position is checked against its range and against the run's own files it describes (a negative
// frame count resumed to other output). Files shorter than the checkpoint says are left to the caller
// (resuming refuses them naming the file).
[[noreturn]] void refuseField(const fs::path& path, const std::string& field, const std::string& why) {
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

// one root's part of a checkpoint (what its folder dir holds: the run directory's top for a scene of one
// root), written after growth step `step` (the run's; a plate's lateral has grown fewer of its own)
void checkRanges(const RodState& state, const SimulationCarry& carry, const RunWatch& watch, const WriterPositions& w,
                 int step, long elements, const fs::path& path, const fs::path& dir, const std::string& who) {
  auto refuse = [&](const fs::path& p, const std::string& field, const std::string& why) {
    refuseField(p, who + field, why);
  };
  auto num = [](auto v) { return std::to_string(v); };
  const SimulationProgress& k = carry.progress;
  const Memory<NewtonWorkspace>& nw = carry.newton;
  const Memory<ContactWorkspace>& cw = carry.contact;
  const SparseMemory& sparse = get<&NewtonWorkspace::sparse>(nw);
  // a checkpoint is written after a growth step (1, 2, ...): every output step so far left at most one
  // snapshot (and time-series row), the initial state's included
  if (step < 1) refuse(path, "growth step", num(step) + " out of range (>= 1)");
  const long maxFrames = static_cast<long>(step) + 1;
  if (!(std::isfinite(state.time) && state.time >= 0))
    refuse(path, "rod time", "out of range (finite, >= 0)");
  for (const auto& [name, v] : {std::pair<const char*, long>{"total substeps", k.totalSubsteps},
                                {"total iterations", k.totalIterations},
                                {"slip events", k.slipEvents},
                                {"contact list builds", get<&ContactWorkspace::builds>(cw)},
                                {"max substeps", watch.maxSubsteps},
                                {"max self-contacts", watch.maxSelfContacts},
                                {"Newton negative eigenvalues", get<&NewtonWorkspace::negative>(nw)},
                                {"Newton factors dofs", get<&NewtonWorkspace::factorsDofs>(nw)},
                                {"Newton factors first block", get<&NewtonWorkspace::factorsFirstBlock>(nw)},
                                {"Newton first free node", get<&NewtonWorkspace::firstFreeNode>(nw)},
                                {"Newton mature age", get<&NewtonWorkspace::matureAge>(nw)},
                                {"sparse lower bandwidth", sparse.kl},
                                {"sparse upper bandwidth", sparse.ku}})
    if (v < 0) refuse(path, name, num(v) + " out of range (>= 0)");
  if (get<&NewtonWorkspace::firstFreeNode>(nw) > elements + 1)
    refuse(path, "Newton first free node", num(get<&NewtonWorkspace::firstFreeNode>(nw)) + " out of range (0 .. " + num(elements + 1) + ")");
  if (sparse.n < -1)  // -1: no sparse pattern
    refuse(path, "sparse pattern size", num(sparse.n) + " out of range (>= -1)");
  if (get<&ContactWorkspace::builtElements>(cw) < -1)  // -1: no contact list built
    refuse(path, "contact list elements", num(get<&ContactWorkspace::builtElements>(cw)) + " out of range (>= -1)");
  if (w.trajectoryFrames < 0 || w.trajectoryFrames > maxFrames)
    refuse(path, "trajectory frame count", num(w.trajectoryFrames) + " out of range (0 .. " + num(maxFrames) +
                                               ": at most one per growth step up to " + num(step) + ", and the initial one)");
  if (static_cast<long>(w.vtkEntries.size()) > maxFrames)
    refuse(path, "ParaView entry count", num(w.vtkEntries.size()) + " out of range (0 .. " + num(maxFrames) + ")");
  for (const auto& [t, name] : w.vtkEntries)
    if (!(std::isfinite(t) && t >= 0)) refuse(path, "ParaView entry time", "out of range (finite, >= 0 h)");
  // the run's own files agree (where they hold what the checkpoint says: shorter ones are refused by
  // the caller, naming the file)
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

namespace {

// the header, the payload and its checksum, written atomically
void writeFramed(const fs::path& path, RunLayout layout, std::uint64_t hash, int step, const std::string& payload) {
  Out h;
  h.raw(kMagic, sizeof kMagic);
  h.pod(kCheckpointVersion);
  h.pod(static_cast<std::uint32_t>(layout));
  h.pod(hash);
  h.pod(static_cast<std::int32_t>(step));
  h.pod(std::uint32_t{0});
  h.pod(static_cast<std::uint64_t>(payload.size()));
  h.b += payload;
  h.pod(fnv1a(payload.data(), payload.size()));
  writeFileAtomic(path, h.b);
}

std::string readBytes(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path.string() + ": cannot open the checkpoint");
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// checks the header and the checksum; leaves `in` at the payload, its end before the checksum
void readHeader(In& in, RunLayout layout, std::uint64_t& hash, int& step) {
  const std::string& b = in.b;
  if (b.size() < kHeaderBytes + 8 || std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
    in.bad("not a rootsim checkpoint, or truncated");
  in.pos = sizeof kMagic;
  const auto version = in.pod<std::uint32_t>();
  // an older rootsim's checkpoint is not misread: its payload was laid out otherwise (a single root's
  // had its own before a root ran as a plate of one)
  if (version < kCheckpointVersion)
    throw SceneError(in.file + ": checkpoint from an older rootsim (version " + std::to_string(version) +
                     ", this rootsim reads version " + std::to_string(kCheckpointVersion) +
                     "): rerun with --force to discard it and start again");
  if (version != kCheckpointVersion)
    in.bad("version " + std::to_string(version) + ", this rootsim reads version " + std::to_string(kCheckpointVersion));
  const auto k = in.pod<std::uint32_t>();
  if (k != static_cast<std::uint32_t>(layout))
    in.bad(k == static_cast<std::uint32_t>(RunLayout::Plate)     ? "a plate's checkpoint, this scene is one root"
           : k == static_cast<std::uint32_t>(RunLayout::OneRoot) ? "one root's checkpoint, this scene is a plate"
                                                                 : "kind " + std::to_string(k) + " unknown");
  hash = in.pod<std::uint64_t>();
  step = in.pod<std::int32_t>();
  in.pod<std::uint32_t>();
  const auto payload = in.pod<std::uint64_t>();
  if (payload != b.size() - kHeaderBytes - 8) in.bad("length " + std::to_string(b.size()) + " does not match its header");
  std::uint64_t sum = 0;
  std::memcpy(&sum, b.data() + b.size() - 8, 8);
  if (sum != fnv1a(b.data() + kHeaderBytes, payload)) in.bad("checksum mismatch");
  in.end = b.size() - 8;
}

// a root's state and carry, checked against each other (a checksum collision aside, a writer
// bug); its growth step is its own (`step`: a plate's laterals count theirs from their emergence)
long checkRoot(const In& in, const RodState& s, const SimulationCarry& k, int step) {
  // the fields must agree on the element count (each along its nodes, elements or Voronoi domains)
  const long n = s.l0.size();
  if (n < 1) in.bad("rod state with no element");
  if (const char* off = fieldOffElementCount(s))
    in.bad(std::string("rod state fields disagree on the element count: ") + off + " does not fit " +
           std::to_string(n) + " elements");
  const Memory<NewtonWorkspace>& nw = k.newton;
  const auto& mode = get<&NewtonWorkspace::mode>(nw);
  const int modeSize = get<&NewtonWorkspace::modeSize>(nw);
  const auto& matureK = get<&NewtonWorkspace::matureK>(nw);
  const int matureValid = get<&NewtonWorkspace::matureValid>(nw);
  if ((step >= 0 && k.progress.step != step) || k.progress.step < 0 || modeSize < 0 ||
      static_cast<std::size_t>(modeSize) > mode.size() || matureValid < 0 ||
      3 * static_cast<std::size_t>(matureValid) > matureK.size())
    in.bad("inconsistent solver state");
  for (const auto& [i, j] : get<&ContactWorkspace::pairs>(k.contact))
    if (i < 0 || j < 0 || i >= n || j >= n) in.bad("contact pair out of range");
  // banded factors in use are there (get() checked that stored ones fit)
  if (get<&NewtonWorkspace::factorsValid>(nw) && !get<&NewtonWorkspace::sparseActive>(nw) &&
      get<&NewtonWorkspace::lu>(nw).size() < 1)
    in.bad("inconsistent Newton factors");
  return n;
}

}  // namespace

void writeCheckpoint(const fs::path& path, const RunCheckpoint& c) {
  static_assert(std::is_trivially_copyable_v<ZoneObservables>);
  Out o;
  put(o, c.acc);
  put(o, c.plate);
  put(o, c.roots);
  writeFramed(path, c.layout, c.sceneHash, c.step, o.b);
}

RunCheckpoint readCheckpoint(const fs::path& path, RunLayout layout, const std::vector<std::string>& seedlingNames) {
  RunCheckpoint c;
  c.layout = layout;
  const std::string b = readBytes(path);
  In in{b, 0, b.size(), path.string()};
  readHeader(in, layout, c.sceneHash, c.step);
  get(in, c.acc);
  get(in, c.plate);
  get(in, c.roots);
  const PlateCarry& p = c.plate;
  const std::size_t roots = p.roots.size();
  // every root's state and carry checked as a single root's (a lateral counts its steps from its emergence)
  std::vector<long> elements;
  for (std::size_t r = 0; r < roots; ++r)
    elements.push_back(checkRoot(in, p.roots[r].state, p.roots[r].carry, r < seedlingNames.size() ? c.step : -1));
  if (in.pos != in.end) in.bad("trailing bytes");
  // the plate's bookkeeping fits its seedlings: every lateral after its parent, one root each
  const std::size_t seedlings = seedlingNames.size();
  if (p.last.step != c.step) in.bad("the plate's step disagrees with the header");
  if (roots != seedlings + p.laterals.size() || p.nextSite.size() != roots || c.roots.size() != roots)
    in.bad(std::to_string(roots) + " roots for " + std::to_string(seedlings) + " seedlings and " +
           std::to_string(p.laterals.size()) + " laterals");
  if (layout == RunLayout::OneRoot && roots != 1) in.bad(std::to_string(roots) + " roots for a scene of one root");
  std::vector<std::string> names = seedlingNames;
  for (std::size_t i = 0; i < p.laterals.size(); ++i) {
    const LateralBirth& lb = p.laterals[i];
    if (lb.parent < 0 || static_cast<std::size_t>(lb.parent) >= seedlings + i || lb.site < 0 ||
        lb.site >= p.nextSite[static_cast<std::size_t>(lb.parent)] || p.roots[seedlings + i].carry.progress.step > c.step)
      in.bad("lateral " + std::to_string(i + 1) + " does not fit its parent");
    names.push_back(lateralName(names[static_cast<std::size_t>(lb.parent)], lb.site));
  }
  for (int v : p.nextSite)
    if (v < 0) in.bad("a root's next lateral site is negative");
  const auto& sparse = get<&CoupledWorkspace::sparse>(p.coupled);
  if (sparse.n < -1 || sparse.kl < 0 || sparse.ku < 0) in.bad("the coupled system's sparse pattern is out of range");
  const RunAccumulators& a = c.acc;
  if (!(std::isfinite(a.wallBefore) && a.wallBefore >= 0))
    refuseField(path, "earlier wall time", "out of range (finite, >= 0 s)");
  if (a.maxSweeps < 1 || !(std::isnan(a.minGap) || a.minGap >= 0) ||
      (layout == RunLayout::OneRoot && a.seriesBytes != 0))
    in.bad("the plate's accumulators are out of range");
  // each root's part against its folder: the run directory itself for a scene of one root
  const fs::path dir = path.parent_path();
  for (std::size_t r = 0; r < roots; ++r) {
    const bool top = layout == RunLayout::OneRoot;
    checkRanges(p.roots[r].state, p.roots[r].carry, c.roots[r].watch, c.roots[r].writers, c.step, elements[r], path,
                top ? dir : dir / "roots" / names[r], top ? "" : "root " + names[r] + ": ");
  }
  return c;
}

}  // namespace rootsim

namespace rootsim {

std::string checkpointDifference(const RunCheckpoint& a, const RunCheckpoint& b) {
  if (a.sceneHash != b.sceneHash) return "sceneHash";
  if (a.step != b.step) return "step";
  if (a.layout != b.layout) return "layout";
  std::string d = difference(a.acc, b.acc, "acc");
  if (d.empty()) d = difference(a.plate, b.plate, "plate");
  if (d.empty()) d = difference(a.roots, b.roots, "roots");
  return d;
}
std::string carryDifference(const SimulationCarry& a, const SimulationCarry& b) { return difference(a, b, "carry"); }
std::string stateDifference(const RodState& a, const RodState& b) { return difference(a, b, "state"); }

}  // namespace rootsim
