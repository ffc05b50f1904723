#include "scene_schema.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "rootsim/errors.hpp"
#include "rootsim/scene.hpp"

namespace rootsim::detail {

const char* typeName(KeyType t) {
  switch (t) {
    case KeyType::Real: return "a number";
    case KeyType::Integer: return "an integer";
    case KeyType::Boolean: return "true or false";
    case KeyType::String: return "a string";
    case KeyType::Vector3: return "an array of 3 numbers";
  }
  return "?";
}

namespace {
constexpr double kInf = 1e300;
KeySpec make(const char* sec, const char* key, KeyType type) {
  KeySpec k;
  k.section = sec;
  k.key = key;
  k.type = type;
  return k;
}
KeySpec real(const char* sec, const char* key, double def, double lo, bool loOpen, double hi, bool hiOpen,
             const char* doc) {
  KeySpec k = make(sec, key, KeyType::Real);
  k.defNum = def; k.lo = lo; k.loOpen = loOpen; k.hi = hi; k.hiOpen = hiOpen; k.doc = doc;
  return k;
}
KeySpec integer(const char* sec, const char* key, double def, double lo, double hi, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Integer);
  k.defNum = def; k.lo = lo; k.hi = hi; k.doc = doc;
  return k;
}
KeySpec boolean(const char* sec, const char* key, bool def, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Boolean);
  k.defBool = def; k.doc = doc;
  return k;
}
KeySpec choice(const char* sec, const char* key, const char* def, std::vector<std::string> choices,
               const char* doc) {
  KeySpec k = make(sec, key, KeyType::String);
  k.defStr = def; k.choices = std::move(choices); k.doc = doc;
  return k;
}
KeySpec vec3(const char* sec, const char* key, const Vec3& def, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Vector3);
  k.defVec = {def.x(), def.y(), def.z()};
  k.doc = doc;
  return k;
}
}  // namespace

const std::vector<std::string>& sections() {
  static const std::vector<std::string> s = {"root", "growth", "tropism", "plane", "adhesion",
                                             "self_contact", "friction", "solver", "load", "analysis",
                                             "output"};
  return s;
}

// every key, its unit, range and meaning; its default is read from defaultModel() (the one source of
// defaults, include/rootsim/model.hpp), converted to the key's unit.
// Ranges (each key's doc in `rootsim check` and scene.toml ends with it). Upper bounds are physical
// sanity, a generous factor beyond anything a root (or any plant organ) has: radius <= 100 mm, E <= 1e6
// MPa (diamond), growth rate <= 10 /h, step <= 10 h, growth zone <= 1 m, gains <= 100 (the paper uses
// < 2), |R tau| <= 10, springs <= 1e6 N/m. Beyond them a run diverges or exhausts the sub-step cap
// after minutes instead of being refused up front (issue 15). The number of elements is capped
// separately (kMaxElements, buildModel).
const std::vector<KeySpec>& schema() {
  using units::mm;
  using units::hour;
  static const Model d = defaultModel();
  static const std::vector<KeySpec> keys = {
      real("root", "radius_mm", d.rod.radius / mm, 0, true, 100, false, "root radius R [mm]"),
      real("root", "initial_length_mm", d.initial.length / mm, 0, true, 1e4, false, "initial length L0 [mm]"),
      real("root", "youngs_modulus_mpa", d.rod.youngs / units::mpa, 0, true, 1e6, false, "Young's modulus E [MPa]"),
      real("root", "element_length_mm", d.initial.elementLength / mm, 0, true, 1e3, false,
           "target element length h [mm]; elements longer than growth.split_factor * h are split"),
      real("root", "density_kg_per_m3", d.rod.density, 0, true, 1e5, false,
           "density [kg/m^3] (physical-mass relaxation and weight only)"),
      boolean("growth", "enabled", d.growth.enabled, "grow (false: mechanics only, one relaxation under [load])"),
      real("growth", "growth_zone_mm", d.growth.zoneLength / mm, 0, true, 1e3, false, "growth-zone length Lgz [mm]"),
      real("growth", "rate_per_h", d.growth.rate * hour, 0, true, 10, false, "relative growth rate in the zone [1/h]"),
      integer("growth", "steps", d.growth.steps, 0, 1e7, "number of growth steps"),
      real("growth", "step_h", d.growth.stepTime / hour, 0, true, 10, false, "growth step [h]"),
      real("growth", "split_factor", d.growth.splitFactor, 1.2, false, 10, false,
           "split an element when it grows past this many target lengths h"),
      real("tropism", "beta", d.tropism.beta, 0, false, 100, false, "gravitropic gain beta"),
      real("tropism", "gamma", d.tropism.gamma, 0, false, 100, false, "proprioceptive gain gamma"),
      choice("tropism", "sensing", d.tropism.sensing == Sensing::Local ? "local" : "apical", {"local", "apical"}, "where gravity is sensed"),
      real("tropism", "twist_r_tau", d.tropism.rTau, -10, false, 10, false, "intrinsic twist R*tau (dimensionless)"),
      real("tropism", "circumnutation_gain", d.tropism.cnGain, 0, false, 100, false, "circumnutation gain lambda_cn"),
      real("tropism", "circumnutation_period_h", d.tropism.cnPeriod / hour, 0, true, 1e4, false, "circumnutation period [h]"),
      boolean("plane", "enabled", d.env.plane.enabled, "the tilted plate is present"),
      real("plane", "alpha_deg", d.env.plane.alpha / units::deg, 0, false, 90, false,
           "plate tilt from the vertical [deg]; also sets the start direction when the plate is off"),
      // the default deviates from the paper's 100 N/m: see Plane::k (environment.hpp)
      real("plane", "k_n_per_m", d.env.plane.k, 0, false, 1e6, false,
           "contact penalty spring per element [N/m] (paper: 100; see README)"),
      real("plane", "damping_kg_per_s", d.env.plane.c, 0, false, 1e3, false,
           "contact normal damping per element [kg/s] (physical-mass relaxation only)"),
      boolean("adhesion", "enabled", d.env.adhesion, "pin material that leaves the growth zone"),
      real("adhesion", "k_n_per_m", d.env.kAdhesion, 0, false, 1e6, false, "adhesion spring [N/m]"),
      boolean("self_contact", "enabled", d.env.selfContact.enabled,
              "the root cannot pass through itself: elements repel when closer than 2R (MODEL.md section 11)"),
      real("self_contact", "k_n_per_m", d.env.selfContact.k, 0, true, 1e6, false,
           "self-contact penalty spring per element pair [N/m] (damping: plane.damping_kg_per_s)"),
      boolean("friction", "enabled", d.env.friction.enabled,
              "Coulomb friction on the plate and obstacles, with stick points (MODEL.md section 11)"),
      real("friction", "mu_static", d.env.friction.muStatic, 0, false, 100, false,
           "static friction coefficient across the root's axis"),
      real("friction", "mu_kinetic", d.env.friction.muKinetic, 0, false, 100, false,
           "kinetic friction coefficient across the root's axis (at most mu_static)"),
      real("friction", "axial_ratio", d.env.friction.axialRatio, 0, false, 100, false,
           "friction along the root's in-plane axis / across it (root hairs anchor sideways: < 1)"),
      real("friction", "slip_weakening_mm", d.env.friction.slipWeakening / mm, 0, false, 1e3, false,
           "slip over which friction falls from mu_static to mu_kinetic [mm] (0: at once; see README)"),
      choice("solver", "kind", d.solver.kind == SolverKind::Newton ? "newton" : "dynamic", {"newton", "dynamic"},
             "newton: quasi-static Newton with a banded Jacobian (MODEL.md section 12); dynamic: the paper's "
             "explicit damped relaxation"),
      real("solver", "window_mm", d.solver.window / mm, 0, false, 1e4, false,
           "newton: solve for the nodes within this length behind the growth zone, the zone, contacts and "
           "the twist of the adhered mature root (0: the whole rod; see README)"),
      integer("solver", "newton_max_iterations", d.solver.newtonMaxIterations, 1, 100000,
              "Newton iterations before a growth step continues with the explicit relaxation (snaps)"),
      choice("solver", "mass", d.solver.mass == MassModel::Scaled ? "scaled" : "physical", {"scaled", "physical"},
             "scaled: per-dof fictitious masses (fast); physical: density and dt from the stiffest spring"),
      choice("solver", "damping", d.solver.damping == Damping::Fire ? "fire" : "viscous", {"fire", "viscous"}, "FIRE or viscous damping of the pseudo-dynamics"),
      real("solver", "damping_per_s", d.solver.viscousRate, 0, true, 1e9, false, "viscous damping rate [1/s] (damping = \"viscous\")"),
      real("solver", "force_tol", d.solver.forceTol, 0, true, 1, false,
           "equilibrium: residual force < force_tol * B1/Lref^2 and couple < force_tol * B1/Lref "
           "(Lref = growth zone, or the rod when not growing)"),
      real("solver", "speed_tol", d.solver.speedTol, 0, true, 1, false,
           "equilibrium: node displacement per sub-step < speed_tol * R, rotation < speed_tol rad"),
      boolean("solver", "stability_check", d.solver.stabilityCheck,
              "check each growth step's equilibrium (inertia of the stiffness matrix) and leave saddle "
              "points along their unstable mode"),
      integer("solver", "max_substeps", static_cast<double>(d.solver.maxSubsteps), 1, 1e12, "sub-step cap per relaxation; hitting it is an error"),
      integer("solver", "seed", static_cast<double>(d.initial.seed), 0, 9.007199254740992e15, "seed of the initial lateral perturbation"),
      real("solver", "perturbation", d.initial.perturbation, 0, false, 1, false, "initial lateral perturbation amplitude / R"),
      vec3("load", "tip_force_n", d.env.tipForce, "dead load on the tip node, lab frame [N]"),
      vec3("load", "tip_torque_nm", d.env.tipTorque, "couple on the tip element, lab frame [N m]"),
      choice("load", "base", d.env.base == BaseCondition::Clamped ? "clamped" : "free", {"clamped", "free"}, "base boundary condition"),
      boolean("load", "gravity", d.env.gravity.squaredNorm() > 0, "weight of the root (negligible for real roots)"),
      real("analysis", "skew_threshold_deg", d.analysis.skewThresholdDeg, 0, false, 90, false, "|<theta>| above this is skewing [deg]"),
      real("analysis", "coil_turn_deg", d.analysis.coilTurnDeg, 0, true, 3600, false,
           "planar tangent turning through more than this is coiling [deg]"),
      real("analysis", "wave_min_amplitude_r", d.analysis.waveMinAmplitude, 0, false, 1e3, false,
           "hysteresis of the lateral turning points in R (a lateral peak-to-peak below it counts as straight)"),
      real("analysis", "skew_min_waves", d.analysis.skewMinWaves, 0, false, 1e4, false,
           "a waving root is called skewing only over at least this many full waves"),
      integer("output", "every_steps", d.output.everySteps, 1, 1e9, "snapshot and time-series row every N growth steps"),
      boolean("output", "trajectory", d.output.trajectory,
              "write the trajectory (what `rootsim render` reads; format: output.trajectory_format)"),
      choice("output", "trajectory_format",
             d.output.trajectoryFormat == TrajectoryFormat::Binary ? "binary"
             : d.output.trajectoryFormat == TrajectoryFormat::Csv  ? "csv"
                                                                    : "both",
             {"binary", "csv", "both"},
             "binary: trajectory.bin (raw doubles, docs/outputs.md); csv: trajectory.csv (text); both: the two"),
      boolean("output", "vtk", d.output.vtk, "write ParaView snapshots (vtk/*.vtp, zlib-compressed binary, + trajectory.pvd)"),
      real("output", "checkpoint_every_s", d.output.checkpointEvery, 0, false, 1e6, false,
           "wall time between checkpoints of a growing run (DIR.partial/checkpoint.bin, for --resume) [s]; "
           "0: after every growth step"),
  };
  return keys;
}

Value defaultValue(const KeySpec& k) {
  Value v;
  v.type = k.type;
  v.num = k.defNum;
  v.b = k.defBool;
  v.str = k.defStr;
  v.vec = k.defVec;
  v.origin = "default";
  return v;
}

std::string formatNumber(double x, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(x));
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

namespace {
// shortest text of a number for messages ("0", "-0.1", "1e+300")
std::string pretty(double x) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
}  // namespace

std::string rangeText(const KeySpec& k) {
  std::ostringstream e;
  if (k.lo > -kInf && k.hi < kInf)
    e << "in " << (k.loOpen ? "(" : "[") << pretty(k.lo) << ", " << pretty(k.hi) << (k.hiOpen ? ")" : "]");
  else if (k.lo > -kInf)
    e << (k.loOpen ? "> " : ">= ") << pretty(k.lo);
  else if (k.hi < kInf)
    e << (k.hiOpen ? "< " : "<= ") << pretty(k.hi);
  return e.str();
}

std::string checkValue(const KeySpec& k, const Value& v) {
  std::ostringstream os;
  auto range = [&](double x) -> std::string {
    if (!std::isfinite(x)) return "must be finite (got " + pretty(x) + ")";
    const bool low = k.loOpen ? x <= k.lo : x < k.lo;
    const bool high = k.hiOpen ? x >= k.hi : x > k.hi;
    if (low || high) return "must be " + rangeText(k) + " (got " + pretty(x) + ")";
    return "";
  };
  switch (k.type) {
    case KeyType::Real:
    case KeyType::Integer:
      return range(v.num);
    case KeyType::Vector3:
      for (double x : v.vec)
        if (!std::isfinite(x)) return "must have finite components";
      return "";
    case KeyType::String: {
      for (const auto& c : k.choices)
        if (c == v.str) return "";
      os << "must be one of";
      for (size_t i = 0; i < k.choices.size(); ++i) os << (i ? ", " : " ") << '"' << k.choices[i] << '"';
      os << " (got \"" << printable(v.str) << "\")";
      return os.str();
    }
    case KeyType::Boolean:
      return "";
  }
  return "";
}

int editDistance(const std::string& a, const std::string& b) {
  std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

namespace {
[[noreturn]] void relationError(const Values& v, const std::string& key, const std::string& what) {
  throw SceneError(v.at(key).origin + ": " + key + " " + what);
}
}  // namespace

Model buildModel(const Values& v, const std::string& name) {
  auto num = [&](const char* k) { return v.at(k).num; };
  auto flag = [&](const char* k) { return v.at(k).b; };
  auto str = [&](const char* k) { return v.at(k).str; };
  auto vec = [&](const char* k) { const auto& a = v.at(k).vec; return Vec3(a[0], a[1], a[2]); };
  using units::mm;
  using units::hour;
  Model m = defaultModel();
  m.name = name;
  m.rod.radius = num("root.radius_mm") * mm;
  m.rod.youngs = num("root.youngs_modulus_mpa") * units::mpa;
  m.rod.density = num("root.density_kg_per_m3");
  m.initial.length = num("root.initial_length_mm") * mm;
  m.initial.elementLength = num("root.element_length_mm") * mm;
  m.initial.perturbation = num("solver.perturbation");
  m.initial.seed = static_cast<std::uint64_t>(num("solver.seed"));
  m.growth.enabled = flag("growth.enabled");
  m.growth.zoneLength = num("growth.growth_zone_mm") * mm;
  m.growth.rate = num("growth.rate_per_h") / hour;
  m.growth.steps = static_cast<int>(num("growth.steps"));
  m.growth.stepTime = num("growth.step_h") * hour;
  m.growth.splitFactor = num("growth.split_factor");
  m.tropism.beta = num("tropism.beta");
  m.tropism.gamma = num("tropism.gamma");
  m.tropism.sensing = str("tropism.sensing") == "apical" ? Sensing::Apical : Sensing::Local;
  m.tropism.rTau = num("tropism.twist_r_tau");
  m.tropism.cnGain = num("tropism.circumnutation_gain");
  m.tropism.cnPeriod = num("tropism.circumnutation_period_h") * hour;
  m.env.plane.enabled = flag("plane.enabled");
  m.env.plane.alpha = num("plane.alpha_deg") * units::deg;
  m.env.plane.k = num("plane.k_n_per_m");
  m.env.plane.c = num("plane.damping_kg_per_s");
  m.env.selfContact.enabled = flag("self_contact.enabled");
  m.env.selfContact.k = num("self_contact.k_n_per_m");
  m.env.friction.enabled = flag("friction.enabled");
  m.env.friction.muStatic = num("friction.mu_static");
  m.env.friction.muKinetic = num("friction.mu_kinetic");
  m.env.friction.axialRatio = num("friction.axial_ratio");
  m.env.friction.slipWeakening = num("friction.slip_weakening_mm") * mm;
  m.env.adhesion = flag("adhesion.enabled");
  m.env.kAdhesion = num("adhesion.k_n_per_m");
  m.env.tipForce = vec("load.tip_force_n");
  m.env.tipTorque = vec("load.tip_torque_nm");
  m.env.base = str("load.base") == "free" ? BaseCondition::Free : BaseCondition::Clamped;
  m.env.gravity = flag("load.gravity") ? Vec3(0, 0, -9.81) : Vec3::Zero();
  m.solver.kind = str("solver.kind") == "newton" ? SolverKind::Newton : SolverKind::Dynamic;
  m.solver.window = num("solver.window_mm") * mm;
  m.solver.newtonMaxIterations = static_cast<int>(num("solver.newton_max_iterations"));
  m.solver.mass = str("solver.mass") == "physical" ? MassModel::Physical : MassModel::Scaled;
  m.solver.damping = str("solver.damping") == "viscous" ? Damping::Viscous : Damping::Fire;
  m.solver.viscousRate = num("solver.damping_per_s");
  m.solver.forceTol = num("solver.force_tol");
  m.solver.speedTol = num("solver.speed_tol");
  m.solver.maxSubsteps = static_cast<long>(num("solver.max_substeps"));
  m.solver.stabilityCheck = flag("solver.stability_check");
  m.analysis.skewThresholdDeg = num("analysis.skew_threshold_deg");
  m.analysis.coilTurnDeg = num("analysis.coil_turn_deg");
  m.analysis.waveMinAmplitude = num("analysis.wave_min_amplitude_r");
  m.analysis.skewMinWaves = num("analysis.skew_min_waves");
  m.output.everySteps = static_cast<int>(num("output.every_steps"));
  m.output.trajectory = flag("output.trajectory");
  m.output.vtk = flag("output.vtk");
  m.output.trajectoryFormat = str("output.trajectory_format") == "csv"    ? TrajectoryFormat::Csv
                              : str("output.trajectory_format") == "both" ? TrajectoryFormat::Both
                                                                          : TrajectoryFormat::Binary;
  m.output.checkpointEvery = num("output.checkpoint_every_s");
  completeModel(m);

  // relations between keys
  if (m.initial.elementLength * 2 > m.initial.length * (1 + 1e-12))
    relationError(v, "root.element_length_mm",
                  "must be at most half of root.initial_length_mm (got " +
                      formatNumber(num("root.element_length_mm"), false) + " mm for a " +
                      formatNumber(num("root.initial_length_mm"), false) + " mm root)");
  if (m.growth.enabled) {
    const double perZone = m.growth.zoneLength / m.initial.elementLength;
    if (perZone < 10.0 - 1e-9)
      relationError(v, "root.element_length_mm",
                    "must give at least 10 elements in the growth zone (got " + formatNumber(perZone, false) +
                        " = growth.growth_zone_mm / root.element_length_mm)");
    if (m.env.tipForce.norm() > 0 || m.env.tipTorque.norm() > 0)
      relationError(v, "load.tip_force_n", "and load.tip_torque_nm apply to mechanics-only scenes "
                                           "(growth.enabled = false)");
    if (m.env.base == BaseCondition::Free)
      relationError(v, "load.base", "= \"free\" applies to mechanics-only scenes (a growing root is clamped)");
  }
  if (m.env.friction.muKinetic > m.env.friction.muStatic)
    relationError(v, "friction.mu_kinetic", "must be at most friction.mu_static (got " +
                                                formatNumber(m.env.friction.muKinetic, false) + " > " +
                                                formatNumber(m.env.friction.muStatic, false) + ")");
  // the work one scene may ask for: memory and time grow with the number of elements, at the start and
  // after growing (growth adds rate * step * zone length per step). Without this cap
  // root.initial_length_mm = 1e4 grew to GBs and root.element_length_mm = 1e-12 never finished.
  // The error names the first of the keys involved that --set gave, else that the scene file gave.
  auto capError = [&](std::initializer_list<const char*> keys, const std::string& what) {
    const char* key = nullptr;
    for (const char* k : keys)
      if (!key && v.at(k).origin.rfind("--set", 0) == 0) key = k;
    for (const char* k : keys)
      if (!key && v.at(k).origin != "default") key = k;
    if (!key) key = *keys.begin();
    const double x = num(key);
    const std::string shown = x == std::floor(x) && x < 1e15 ? formatNumber(x, true) : pretty(x);
    throw SceneError(v.at(key).origin + ": " + key + " = " + shown + ": " + what + "; at most " +
                     pretty(kMaxElements) + " elements are allowed");
  };
  const double h = num("root.element_length_mm");
  auto count = [](double x) { return x < 1e15 ? formatNumber(std::ceil(x), true) : pretty(x); };
  const double initialElements = num("root.initial_length_mm") / h;
  if (initialElements > kMaxElements)
    capError({"root.initial_length_mm", "root.element_length_mm"},
             "root.initial_length_mm / root.element_length_mm = " + pretty(num("root.initial_length_mm")) + " mm / " +
                 pretty(h) + " mm = " + count(initialElements) + " elements at the start");
  if (m.growth.enabled) {
    const double grown = num("root.initial_length_mm") +
                         num("growth.steps") * num("growth.step_h") * num("growth.rate_per_h") * num("growth.growth_zone_mm");
    const double finalElements = grown / h;
    if (finalElements > kMaxElements)
      capError({"growth.steps", "growth.step_h", "growth.rate_per_h", "growth.growth_zone_mm", "root.element_length_mm",
                "root.initial_length_mm"},
               "the root grows to " + pretty(grown) +
                   " mm (root.initial_length_mm + growth.steps * growth.step_h * growth.rate_per_h * "
                   "growth.growth_zone_mm) = " + count(finalElements) + " elements of root.element_length_mm = " +
                   pretty(h) + " mm");
  }
  if (!m.env.plane.enabled && m.env.base == BaseCondition::Free && !m.growth.enabled &&
      (m.env.tipForce.norm() > 0 || m.env.gravity.norm() > 0))
    relationError(v, "load.base", "= \"free\" with a net load has no equilibrium; clamp the base");
  return m;
}

std::string tomlText(const KeySpec& k, const Value& x) {
  switch (k.type) {
    case KeyType::Real: return formatNumber(x.num, false);
    case KeyType::Integer: return formatNumber(x.num, true);
    case KeyType::Boolean: return x.b ? "true" : "false";
    case KeyType::String: return "\"" + x.str + "\"";
    case KeyType::Vector3:
      return "[" + formatNumber(x.vec[0], false) + ", " + formatNumber(x.vec[1], false) + ", " +
             formatNumber(x.vec[2], false) + "]";
  }
  return "";
}

std::string resolvedToml(const Values& v, const std::string& name) {
  std::ostringstream os;
  os << "# rootsim resolved scene: " << name << "\n# every key with its value; defaults filled in\n";
  for (const auto& sec : sections()) {
    os << "\n[" << sec << "]\n";
    for (const auto& k : schema()) {
      if (k.section != sec) continue;
      const std::string val = tomlText(k, v.at(k.full()));
      os << k.key << " = " << val;
      const size_t pad = k.key.size() + 3 + val.size();
      os << std::string(pad < 40 ? 40 - pad : 1, ' ') << "# " << k.doc;
      if (k.type == KeyType::Real || k.type == KeyType::Integer) os << "; " << rangeText(k);
      os << "\n";
    }
  }
  return os.str();
}

}  // namespace rootsim::detail
