#include "scene_schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"

namespace rootsim::detail {

const char* typeName(KeyType t) {
  switch (t) {
    case KeyType::Real: return "a number";
    case KeyType::Integer: return "an integer";
    case KeyType::Boolean: return "true or false";
    case KeyType::String: return "a string";
    case KeyType::Vector3: return "an array of 3 numbers";
    case KeyType::Vector2: return "an array of 2 numbers [lateral, downhill]";
  }
  return "?";
}

namespace {
constexpr double kInf = 1e300;

// a key's unit: the model's SI value is the scene value times factor (or divided by it, per = true:
// rates per hour), computed exactly as written here, in the one place both directions live
struct KeyUnit {
  double factor = 1;
  bool per = false;
};
constexpr KeyUnit kOne{};
constexpr KeyUnit kMm{units::mm};
constexpr KeyUnit kHour{units::hour};
constexpr KeyUnit kPerHour{units::hour, true};
constexpr KeyUnit kDeg{units::deg};
constexpr KeyUnit kMpa{units::mpa};

double toSi(double v, KeyUnit u) { return u.per ? v / u.factor : v * u.factor; }

std::size_t textLength(double x) {
  char buf[64];
  return static_cast<std::size_t>(std::to_chars(buf, buf + sizeof buf, x).ptr - buf);
}

// the scene value of an SI value x: of the doubles within 4 ulps of the plain conversion, the one whose
// toSi gives x back bitwise, with the shortest text (so 40 * deg reads back as 40, not
// 40.00000000000001, and loading the text gives x again); the plain conversion when none does (x is
// not the product of any double and the factor: a model that no scene file can hold exactly)
double fromSi(double x, KeyUnit u) {
  if (u.factor == 1.0) return x;
  const double q = u.per ? x * u.factor : x / u.factor;
  if (!std::isfinite(q)) return q;
  double best = q;
  std::size_t bestLen = 0;
  bool found = false;
  auto consider = [&](double y) {
    if (toSi(y, u) != x) return;
    const std::size_t len = textLength(y);
    if (!found || len < bestLen) best = y, bestLen = len, found = true;
  };
  // nearest to q first, so a tie in length goes to the closer value
  consider(q);
  double up = q, down = q;
  for (int i = 0; i < 4; ++i) {
    up = std::nextafter(up, kInf);
    down = std::nextafter(down, -kInf);
    consider(up);
    consider(down);
  }
  return best;
}

KeySpec make(const char* sec, const char* key, KeyType type, const char* doc) {
  KeySpec k;
  k.section = sec;
  k.key = key;
  k.type = type;
  k.doc = doc;
  return k;
}

// a key's field, both ways, into the KeySpec's pair for its owner: a root's Model, the plate's
// parameters, a root's lateral parameters or a seedling
template <class Target, class Set, class Get>
void bind(KeySpec& k, Set set, Get get) {
  if constexpr (std::is_same_v<Target, SceneParams>) k.set = set, k.get = get;
  else if constexpr (std::is_same_v<Target, PlateParams>) k.setPlate = set, k.getPlate = get;
  else if constexpr (std::is_same_v<Target, LateralParams>) k.setLaterals = set, k.getLaterals = get;
  else {
    static_assert(std::is_same_v<Target, Seedling>);
    k.setSeedling = set, k.getSeedling = get;
  }
}

// the keys by type: each names its field of its owner (a function returning a reference to it, called
// with a Target& to set and a const Target& to get); the default is the field of the owner's default
// (defaultModel(), PlateParams{}, LateralParams{}, Seedling{})
template <class Target = SceneParams, class Field>
KeySpec real(const char* sec, const char* key, Field field, KeyUnit u, double lo, bool loOpen, double hi, bool hiOpen,
             const char* doc) {
  KeySpec k = make(sec, key, KeyType::Real, doc);
  k.lo = lo; k.loOpen = loOpen; k.hi = hi; k.hiOpen = hiOpen;
  bind<Target>(k, [field, u](Target& m, const Value& v) { field(m) = toSi(v.num, u); },
               [field, u](const Target& m) {
                 Value v;
                 v.num = fromSi(field(m), u);
                 return v;
               });
  return k;
}
template <class Target = SceneParams, class Field>
KeySpec integer(const char* sec, const char* key, Field field, double lo, double hi, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Integer, doc);
  k.lo = lo; k.hi = hi;
  bind<Target>(k,
               [field](Target& m, const Value& v) {
                 auto& f = field(m);
                 f = static_cast<std::remove_reference_t<decltype(f)>>(v.num);
               },
               [field](const Target& m) {
                 Value v;
                 v.type = KeyType::Integer;
                 v.num = static_cast<double>(field(m));
                 return v;
               });
  return k;
}
template <class Target = SceneParams, class Field>
KeySpec boolean(const char* sec, const char* key, Field field, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Boolean, doc);
  bind<Target>(k, [field](Target& m, const Value& v) { field(m) = v.b; },
               [field](const Target& m) {
                 Value v;
                 v.type = KeyType::Boolean;
                 v.b = field(m);
                 return v;
               });
  return k;
}
// a string key naming one of an enum's values
template <class Target = SceneParams, class Field, class E>
KeySpec choice(const char* sec, const char* key, Field field, std::vector<std::pair<std::string, E>> names,
               const char* doc) {
  KeySpec k = make(sec, key, KeyType::String, doc);
  for (const auto& n : names) k.choices.push_back(n.first);
  bind<Target>(k,
               [field, names](Target& m, const Value& v) {
                 for (const auto& [text, e] : names)
                   if (text == v.str) field(m) = e;
               },
               [field, names](const Target& m) {
                 Value v;
                 v.type = KeyType::String;
                 for (const auto& [text, e] : names)
                   if (field(m) == e) v.str = text;
                 return v;
               });
  return k;
}
// a free string key, checked by its rule
template <class Target, class Field>
KeySpec text(const char* sec, const char* key, Field field, std::function<std::string(const Value&)> rule,
             const char* doc) {
  KeySpec k = make(sec, key, KeyType::String, doc);
  k.rule = std::move(rule);
  bind<Target>(k, [field](Target& m, const Value& v) { field(m) = v.str; },
               [field](const Target& m) {
                 Value v;
                 v.type = KeyType::String;
                 v.str = field(m);
                 return v;
               });
  return k;
}
template <class Field>
KeySpec vec3(const char* sec, const char* key, Field field, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Vector3, doc);
  k.set = [field](SceneParams& m, const Value& v) { field(m) = Vec3(v.vec[0], v.vec[1], v.vec[2]); };
  k.get = [field](const SceneParams& m) {
    Value v;
    v.type = KeyType::Vector3;
    const Vec3& x = field(m);
    v.vec = {x.x(), x.y(), x.z()};
    return v;
  };
  return k;
}
// a point of the plate [mm] (2 numbers: lateral, downhill) into a 2-vector [m]
template <class Target, class Field>
KeySpec point(const char* sec, const char* key, Field field, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Vector2, doc);
  bind<Target>(k, [field](Target& m, const Value& v) { field(m) = Eigen::Vector2d(v.vec[0], v.vec[1]) * units::mm; },
               [field](const Target& m) {
                 Value v;
                 v.type = KeyType::Vector2;
                 const Eigen::Vector2d& x = field(m);
                 v.vec = {fromSi(x.x(), kMm), fromSi(x.y(), kMm), 0.0};
                 return v;
               });
  return k;
}
// a number key whose default is another key's value of its section (KeySpec::defaultFollows): its field
// is optional, none reading as the leader's field
template <class Target, class Field, class Leader>
KeySpec following(const char* sec, const char* key, Field field, const char* leaderKey, Leader leader, KeyUnit u,
                  double lo, bool loOpen, double hi, bool hiOpen, const char* doc) {
  KeySpec k = make(sec, key, KeyType::Real, doc);
  k.lo = lo; k.loOpen = loOpen; k.hi = hi; k.hiOpen = hiOpen;
  k.defaultFollows = leaderKey;
  bind<Target>(k, [field, u](Target& m, const Value& v) { field(m) = toSi(v.num, u); },
               [field, leader, u](const Target& m) {
                 Value v;
                 v.num = fromSi(field(m).value_or(leader(m)), u);
                 return v;
               });
  return k;
}
// load.gravity: on is the standard acceleration straight down, off is none
KeySpec gravity(const char* doc) {
  KeySpec k = make("load", "gravity", KeyType::Boolean, doc);
  k.set = [](SceneParams& m, const Value& v) { m.model.env.gravity = v.b ? Vec3(0, 0, -9.81) : Vec3::Zero(); };
  k.get = [](const SceneParams& m) {
    Value v;
    v.type = KeyType::Boolean;
    v.b = m.model.env.gravity.squaredNorm() > 0;
    return v;
  };
  return k;
}
// each key's default: its getter applied to defaultModel()
std::vector<KeySpec> withDefaults(std::vector<KeySpec> keys) {
  const SceneParams d{defaultModel(), OutputParams{}};
  for (KeySpec& k : keys) {
    const Value v = k.get ? k.get(d)
                    : k.getPlate ? k.getPlate(PlateParams{})
                    : k.getLaterals ? k.getLaterals(LateralParams{})
                                    : k.getSeedling(Seedling{});
    k.defNum = v.num;
    k.defBool = v.b;
    k.defStr = v.str;
    k.defVec = v.vec;
  }
  return keys;
}
}  // namespace

const std::vector<std::string>& sections() {
  static const std::vector<std::string> s = {"root", "growth", "tropism", "plane", "adhesion",
                                             "self_contact", "friction", "solver", "load", "analysis",
                                             "output"};
  return s;
}

// every key, its field of the model or the output, its unit, range and meaning; its default is read from
// defaultModel() and OutputParams{} (the one source of defaults, model.hpp, output_params.hpp) through its getter.
// Ranges (each key's doc in `rootsim check` and scene.toml ends with it). Upper bounds are physical
// sanity, a generous factor beyond anything a root (or any plant organ) has: radius <= 100 mm, E <= 1e6
// MPa (diamond), growth rate <= 10 /h, step <= 10 h, growth zone <= 1 m, gains <= 100 (the paper uses
// < 2), |R tau| <= 10, springs <= 1e6 N/m. Beyond them a run diverges or exhausts the sub-step cap
// after minutes instead of being refused up front. The number of elements is capped
// separately (kMaxElements, buildParams).
// FIELD(rod.radius): the model's field as a reference, for a SceneParams& (set) and a const SceneParams&
// (get); OUTPUT(vtk): the output's
#define FIELD(path) [](auto& p) -> auto& { return p.model.path; }
#define OUTPUT(path) [](auto& p) -> auto& { return p.output.path; }
const std::vector<KeySpec>& schema() {
  static const std::vector<KeySpec> keys = withDefaults({
      real("root", "radius_mm", FIELD(rod.radius), kMm, 0, true, 100, false, "root radius R [mm]"),
      real("root", "initial_length_mm", FIELD(initial.length), kMm, 0, true, 1e4, false, "initial length L0 [mm]"),
      real("root", "initial_angle_deg", FIELD(initial.angle), kDeg, -180, false, 180, false,
           "initial direction in the plate from downhill, positive towards +lateral like theta [deg] (a one-root "
           "scene's; a plate's seedlings take their [[seedling]] angle_deg)"),
      real("root", "youngs_modulus_mpa", FIELD(rod.youngs), kMpa, 0, true, 1e6, false, "Young's modulus E [MPa]"),
      real("root", "element_length_mm", FIELD(initial.elementLength), kMm, 0, true, 1e3, false,
           "target element length h [mm]; elements longer than growth.split_factor * h are split"),
      real("root", "density_kg_per_m3", FIELD(rod.density), kOne, 0, true, 1e5, false,
           "density [kg/m^3] (physical-mass relaxation and weight only)"),
      boolean("growth", "enabled", FIELD(growth.enabled), "grow (false: mechanics only, one relaxation under [load])"),
      real("growth", "growth_zone_mm", FIELD(growth.zoneLength), kMm, 0, true, 1e3, false, "growth-zone length Lgz [mm]"),
      real("growth", "rate_per_h", FIELD(growth.rate), kPerHour, 0, true, 10, false, "relative growth rate in the zone [1/h]"),
      integer("growth", "steps", FIELD(growth.steps), 0, 1e7, "number of growth steps"),
      real("growth", "step_h", FIELD(growth.stepTime), kHour, 0, true, 10, false, "growth step [h]"),
      real("growth", "split_factor", FIELD(growth.splitFactor), kOne, 1.2, false, 10, false,
           "split an element when it grows past this many target lengths h"),
      real("tropism", "beta", FIELD(tropism.beta), kOne, 0, false, 100, false, "gravitropic gain beta"),
      real("tropism", "gamma", FIELD(tropism.gamma), kOne, 0, false, 100, false, "proprioceptive gain gamma"),
      choice("tropism", "sensing", FIELD(tropism.sensing),
             std::vector<std::pair<std::string, Sensing>>{{"local", Sensing::Local}, {"apical", Sensing::Apical}},
             "where gravity is sensed"),
      real("tropism", "twist_r_tau", FIELD(tropism.rTau), kOne, -10, false, 10, false, "intrinsic twist R*tau (dimensionless)"),
      real("tropism", "circumnutation_gain", FIELD(tropism.cnGain), kOne, 0, false, 100, false, "circumnutation gain lambda_cn"),
      real("tropism", "circumnutation_period_h", FIELD(tropism.cnPeriod), kHour, 0, true, 1e4, false, "circumnutation period [h]"),
      boolean("plane", "enabled", FIELD(env.plane.enabled), "the tilted plate is present"),
      real("plane", "alpha_deg", FIELD(env.plane.alpha), kDeg, 0, false, 90, false,
           "plate tilt from the vertical [deg]; also sets the start direction when the plate is off"),
      // the default deviates from the paper's 100 N/m: see Plane::k (environment.hpp)
      real("plane", "k_n_per_m", FIELD(env.plane.k), kOne, 0, false, 1e6, false,
           "contact penalty spring per element [N/m] (paper: 100; see docs/model.md, Environment)"),
      real("plane", "damping_kg_per_s", FIELD(env.plane.c), kOne, 0, false, 1e3, false,
           "contact normal damping per element [kg/s] (physical-mass relaxation only)"),
      boolean("adhesion", "enabled", FIELD(env.adhesion), "pin material that leaves the growth zone"),
      real("adhesion", "k_n_per_m", FIELD(env.kAdhesion), kOne, 0, false, 1e6, false, "adhesion spring [N/m]"),
      boolean("self_contact", "enabled", FIELD(env.selfContact.enabled),
              "the root cannot pass through itself: elements repel when closer than 2R (docs/model.md, Contact "
              "and friction)"),
      real("self_contact", "k_n_per_m", FIELD(env.selfContact.k), kOne, 0, true, 1e6, false,
           "self-contact penalty spring per element pair [N/m] (damping: plane.damping_kg_per_s)"),
      boolean("friction", "enabled", FIELD(env.friction.enabled),
              "Coulomb friction on the plate and obstacles, with stick points (docs/model.md, Contact and "
              "friction)"),
      real("friction", "mu_static", FIELD(env.friction.muStatic), kOne, 0, false, 100, false,
           "static friction coefficient across the root's axis"),
      real("friction", "mu_kinetic", FIELD(env.friction.muKinetic), kOne, 0, false, 100, false,
           "kinetic friction coefficient across the root's axis (at most mu_static)"),
      real("friction", "axial_ratio", FIELD(env.friction.axialRatio), kOne, 0, false, 100, false,
           "friction along the root's in-plane axis / across it (root hairs anchor sideways: < 1)"),
      real("friction", "slip_weakening_mm", FIELD(env.friction.slipWeakening), kMm, 0, false, 1e3, false,
           "slip over which friction falls from mu_static to mu_kinetic [mm] (0: at once; see docs/contact.md)"),
      choice("solver", "kind", FIELD(solver.kind),
             std::vector<std::pair<std::string, SolverKind>>{{"newton", SolverKind::Newton}, {"dynamic", SolverKind::Dynamic}},
             "newton: quasi-static Newton with a banded Jacobian (docs/model.md, Newton solver); dynamic: the "
             "paper's explicit damped relaxation"),
      real("solver", "window_mm", FIELD(solver.window), kMm, 0, false, 1e4, false,
           "newton: solve for the nodes within this length behind the growth zone, the zone, contacts and "
           "the twist of the adhered mature root (0: the whole rod; see docs/numerics.md)"),
      integer("solver", "newton_max_iterations", FIELD(solver.newtonMaxIterations), 1, 100000,
              "Newton iterations before a growth step continues with the explicit relaxation (snaps)"),
      choice("solver", "mass", FIELD(solver.mass),
             std::vector<std::pair<std::string, MassModel>>{{"scaled", MassModel::Scaled}, {"physical", MassModel::Physical}},
             "scaled: per-dof fictitious masses (fast); physical: density and dt from the stiffest spring"),
      choice("solver", "damping", FIELD(solver.damping),
             std::vector<std::pair<std::string, Damping>>{{"fire", Damping::Fire}, {"viscous", Damping::Viscous}},
             "FIRE or viscous damping of the pseudo-dynamics"),
      real("solver", "damping_per_s", FIELD(solver.viscousRate), kOne, 0, true, 1e9, false, "viscous damping rate [1/s] (damping = \"viscous\")"),
      real("solver", "force_tol", FIELD(solver.forceTol), kOne, 0, true, 1, false,
           "equilibrium: residual force < force_tol * B1/Lref^2 and couple < force_tol * B1/Lref "
           "(Lref = growth zone, or the rod when not growing)"),
      real("solver", "speed_tol", FIELD(solver.speedTol), kOne, 0, true, 1, false,
           "equilibrium: node displacement per sub-step < speed_tol * R, rotation < speed_tol rad"),
      boolean("solver", "stability_check", FIELD(solver.stabilityCheck),
              "check each growth step's equilibrium (inertia of the stiffness matrix) and leave saddle "
              "points along their unstable mode"),
      integer("solver", "max_substeps", FIELD(solver.maxSubsteps), 1, 1e12, "sub-step cap per relaxation; hitting it is an error"),
      integer("solver", "seed", FIELD(initial.seed), 0, 9.007199254740992e15, "seed of the initial lateral perturbation"),
      real("solver", "perturbation", FIELD(initial.perturbation), kOne, 0, false, 1, false, "initial lateral perturbation amplitude / R"),
      vec3("load", "tip_force_n", FIELD(env.tipForce), "dead load on the tip node, lab frame [N]"),
      vec3("load", "tip_torque_nm", FIELD(env.tipTorque), "couple on the tip element, lab frame [N m]"),
      choice("load", "base", FIELD(env.base),
             std::vector<std::pair<std::string, BaseCondition>>{{"clamped", BaseCondition::Clamped}, {"free", BaseCondition::Free}},
             "base boundary condition"),
      gravity("weight of the root (negligible for real roots)"),
      // the thresholds of the shape analysis are positive: at 0 rounding noise of a straight root (a swing of
      // 1e-26 mm, a mean angle of 1e-15 deg) was called waving or skewing
      real("analysis", "skew_threshold_deg", FIELD(analysis.skewThresholdDeg), kOne, 1e-3, false, 90, false, "|<theta>| above this is skewing [deg]"),
      real("analysis", "coil_turn_deg", FIELD(analysis.coilTurnDeg), kOne, 0, true, 3600, false,
           "planar tangent turning through more than this is coiling [deg]"),
      real("analysis", "wave_min_amplitude_r", FIELD(analysis.waveMinAmplitude), kOne, 1e-3, false, 1e3, false,
           "hysteresis of the lateral turning points in R (a lateral peak-to-peak below it counts as straight)"),
      real("analysis", "skew_min_waves", FIELD(analysis.skewMinWaves), kOne, 0, false, 1e4, false,
           "a waving root is called skewing only over at least this many full waves"),
      integer("output", "every_steps", OUTPUT(everySteps), 1, 1e9, "snapshot and time-series row every N growth steps"),
      boolean("output", "trajectory", OUTPUT(trajectory),
              "write the trajectory (what `rootsim render` reads; format: output.trajectory_format)"),
      choice("output", "trajectory_format", OUTPUT(trajectoryFormat),
             std::vector<std::pair<std::string, TrajectoryFormat>>{
                 {"binary", TrajectoryFormat::Binary}, {"csv", TrajectoryFormat::Csv}, {"both", TrajectoryFormat::Both}},
             "binary: trajectory.bin (raw doubles, docs/outputs.md); csv: trajectory.csv (text); both: the two"),
      boolean("output", "vtk", OUTPUT(vtk), "write ParaView snapshots (vtk/*.vtp, zlib-compressed binary, + trajectory.pvd)"),
      real("output", "checkpoint_every_s", OUTPUT(checkpointEvery), kOne, 0, false, 1e6, false,
           "wall time between checkpoints of a growing run (DIR.partial/checkpoint.bin, for --resume) [s]; "
           "0: after every growth step"),
  });
  return keys;
}
#undef FIELD
#undef OUTPUT

namespace {
// a seedling's name is a folder of the run directory
std::string folderName(const Value& v) {
  const std::string& s = v.str;
  const bool ok = !s.empty() && s.size() <= 64 && s != "." && s != ".." && std::all_of(s.begin(), s.end(), [](char c) {
                    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
                  });
  return ok ? "" : "must be 1-64 letters, digits, '_', '-' or '.' (got \"" + printable(s) + "\")";
}
// a genotype is a label in CSV and JSON: printable, no quotes or backslashes
std::string label(const Value& v) {
  const std::string& s = v.str;
  const bool ok = s.size() <= 64 && std::all_of(s.begin(), s.end(), [](char c) { return c >= 32 && c < 127 && c != '"' && c != '\\'; });
  return ok ? "" : "must be at most 64 printable characters without quotes or backslashes (got \"" + printable(s) + "\")";
}
}  // namespace

// the plate's keys: [plate] and [population] (the plate's parameters), [[seedling]] (each seedling's
// place and direction; its `set` and the spread of [population] are tables of other keys, read in
// plate_scene.cpp), [laterals] (every root's lateral parameters, a seedling's own in its set). Ranges:
// a plate up to 1 m; lateral lengths up to 1 m and delays up to 1000 h; the lateral's root keys as the
// root's ([root], [growth], [tropism]).
#define FIELD(path) [](auto& m) -> auto& { return m.path; }
namespace {
std::vector<std::pair<std::string, SetPointDrift>> driftLaws() {
  return {{"linear", SetPointDrift::Linear}, {"exponential", SetPointDrift::Exponential}};
}
}  // namespace
const std::vector<KeySpec>& plateSchema() {
  static const std::vector<KeySpec> keys = withDefaults({
      real<PlateParams>("plate", "width_mm", FIELD(width), kMm, 0, true, 1000, false,
                        "lateral extent of the plate from its origin, its uphill-left corner [mm]"),
      real<PlateParams>("plate", "length_mm", FIELD(length), kMm, 0, true, 1000, false, "downhill extent of the plate [mm]"),
      integer<PlateParams>("population", "seed", FIELD(populationSeed), 0, 9.007199254740992e15,
                           "the seed of the draws of [population.spread] (one stream, seedling by seedling)"),
      text<Seedling>("seedling", "name", FIELD(name), folderName,
                     "required, unique: the root's folder roots/NAME of the run (letters, digits, _ - .)"),
      text<Seedling>("seedling", "genotype", FIELD(genotype), label, "a label plate.csv groups by (\"\": none)"),
      point<Seedling>("seedling", "position_mm", FIELD(position),
                      "required: its base's foot [lateral, downhill] from the plate's origin [mm]"),
      real<Seedling>("seedling", "angle_deg", FIELD(model.initial.angle), kDeg, -180, false, 180, false,
                     "initial direction from downhill in the plate, positive towards +lateral like theta [deg]"),
      real<Seedling>("seedling", "set_point_deg", FIELD(model.tropism.setPoint), kDeg, 0, false, 180, true,
                     "gravitropic set-point angle [deg] (0: the primary root's law); at the start of the run, "
                     "when it drifts"),
      following<Seedling>("seedling", "set_point_final_deg", FIELD(model.tropism.setPointFinal), "set_point_deg",
                          FIELD(model.tropism.setPoint), kDeg, 0, false, 180, true,
                          "the set-point angle it drifts to with its age (the run's time) [deg]"),
      choice<Seedling>("seedling", "set_point_drift", FIELD(model.tropism.setPointDrift), driftLaws(),
                       "how the set-point angle drifts: linearly, reaching set_point_final_deg at set_point_drift_h, "
                       "or exponentially, set_point_drift_h the time constant"),
      real<Seedling>("seedling", "set_point_drift_h", FIELD(model.tropism.setPointDriftTime), kHour, 0, true, 1e4, false,
                     "the drift's time: linear, to reach set_point_final_deg; exponential, its time constant [h]"),
      boolean<LateralParams>("laterals", "enabled", FIELD(enabled), "grow lateral roots"),
      real<LateralParams>("laterals", "first_mm", FIELD(first), kMm, 0, false, 1000, false,
                          "the first site, from the parent's base along its rest arc length [mm]"),
      real<LateralParams>("laterals", "spacing_mm", FIELD(spacing), kMm, 0, true, 1000, false, "between sites [mm]"),
      real<LateralParams>("laterals", "apical_unbranched_mm", FIELD(apicalUnbranched), kMm, 0, false, 1000, false,
                          "a site emerges once the parent's tip is this far beyond it [mm]"),
      real<LateralParams>("laterals", "delay_h", FIELD(delay), kHour, 0, false, 1000, false,
                          "and this long after that (the parent's tip advancing at rate_per_h * growth_zone_mm) [h]"),
      real<LateralParams>("laterals", "delay_spread_h", FIELD(delaySpread), kHour, 0, false, 1000, false,
                          "each site's delay is delay_h plus a normal draw of this sd, drawn again while negative, "
                          "from the site's own stream (laterals.seed, the root, the site) [h]"),
      choice<LateralParams>("laterals", "sides", FIELD(alternate),
                            std::vector<std::pair<std::string, bool>>{{"alternate", true}, {"random", false}},
                            "alternate (+lateral side of the parent's tangent first) or random (drawn from seed)"),
      integer<LateralParams>("laterals", "seed", FIELD(seed), 0, 9.007199254740992e15,
                             "the seed of the sides' draws and of each site's delay (delay_spread_h)"),
      real<LateralParams>("laterals", "insertion_deg", FIELD(insertion), kDeg, 0, true, 180, false,
                          "the lateral's initial angle from the parent's tangent (or from downhill) [deg]"),
      choice<LateralParams>("laterals", "insertion_from", FIELD(fromParent),
                            std::vector<std::pair<std::string, bool>>{{"parent", true}, {"downhill", false}},
                            "what insertion_deg is measured from: the parent's tangent at the site, or downhill in the plate"),
      real<LateralParams>("laterals", "radius_mm", FIELD(radius), kMm, 0, true, 100, false, "the lateral's radius [mm]"),
      real<LateralParams>("laterals", "rate_per_h", FIELD(rate), kPerHour, 0, true, 10, false,
                          "its relative growth rate in the zone [1/h]"),
      real<LateralParams>("laterals", "growth_zone_mm", FIELD(zoneLength), kMm, 0, true, 1000, false, "its growth zone [mm]"),
      real<LateralParams>("laterals", "initial_length_mm", FIELD(initialLength), kMm, 0, true, 1000, false,
                          "its length at emergence (at least two elements of root.element_length_mm) [mm]"),
      real<LateralParams>("laterals", "beta", FIELD(beta), kOne, 0, false, 100, false, "its gravitropic gain beta"),
      real<LateralParams>("laterals", "gamma", FIELD(gamma), kOne, 0, false, 100, false, "its proprioceptive gain gamma"),
      real<LateralParams>("laterals", "twist_r_tau", FIELD(rTau), kOne, -10, false, 10, false, "its intrinsic twist R*tau"),
      real<LateralParams>("laterals", "set_point_deg", FIELD(setPoint), kDeg, 0, false, 180, false,
                          "its gravitropic set-point angle [deg]; at its emergence, when it drifts"),
      following<LateralParams>("laterals", "set_point_final_deg", FIELD(setPointFinal), "set_point_deg", FIELD(setPoint), kDeg,
                               0, false, 180, false,
                               "the set-point angle it drifts to with its age (the time since it emerged) [deg]"),
      choice<LateralParams>("laterals", "set_point_drift", FIELD(setPointDrift), driftLaws(),
                            "how the set-point angle drifts: linearly, reaching set_point_final_deg at "
                            "set_point_drift_h, or exponentially, set_point_drift_h the time constant"),
      real<LateralParams>("laterals", "set_point_drift_h", FIELD(setPointDriftTime), kHour, 0, true, 1e4, false,
                          "the drift's time: linear, to reach set_point_final_deg; exponential, its time constant [h]"),
      integer<LateralParams>("laterals", "max_order", FIELD(maxOrder), 1, 4,
                             "laterals of laterals up to this order (1: laterals of the primary only)"),
  });
  return keys;
}
#undef FIELD

const KeySpec* findPlateKey(const std::string& section, const std::string& key) {
  for (const KeySpec& k : plateSchema())
    if (k.section == section && k.key == key) return &k;
  return nullptr;
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

void resolveFollowingDefaults(Values& v) {
  for (const KeySpec& k : plateSchema()) {
    if (k.defaultFollows.empty()) continue;
    const auto mine = v.find(k.full());
    if (mine == v.end() || mine->second.origin != "default") continue;
    const Value& leader = v.at(k.section + "." + k.defaultFollows);
    mine->second.num = leader.num;
  }
}

std::string formatNumber(double x, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(x));
  return shortestNumber(x);
}

std::string rangeText(const KeySpec& k) {
  std::ostringstream e;
  if (k.lo > -kInf && k.hi < kInf)
    e << "in " << (k.loOpen ? "(" : "[") << numberText(k.lo) << ", " << numberText(k.hi) << (k.hiOpen ? ")" : "]");
  else if (k.lo > -kInf)
    e << (k.loOpen ? "> " : ">= ") << numberText(k.lo);
  else if (k.hi < kInf)
    e << (k.hiOpen ? "< " : "<= ") << numberText(k.hi);
  return e.str();
}

std::string checkValue(const KeySpec& k, const Value& v) {
  std::ostringstream os;
  auto range = [&](double x) -> std::string {
    if (!std::isfinite(x)) return "must be finite (got " + numberText(x) + ")";
    const bool low = k.loOpen ? x <= k.lo : x < k.lo;
    const bool high = k.hiOpen ? x >= k.hi : x > k.hi;
    if (low || high) return "must be " + rangeText(k) + " (got " + numberText(x) + ")";
    return "";
  };
  switch (k.type) {
    case KeyType::Real:
    case KeyType::Integer:
      return range(v.num);
    case KeyType::Vector3:
    case KeyType::Vector2:
      for (double x : v.vec)
        if (!std::isfinite(x)) return "must have finite components";
      return "";
    case KeyType::String: {
      if (k.rule) return k.rule(v);
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

Model buildModel(const Values& v, const std::string& name) { return buildParams(v, name).model; }

SceneParams buildParams(const Values& v, const std::string& name) {
  auto num = [&](const char* k) { return v.at(k).num; };
  SceneParams p{defaultModel(), OutputParams{}};
  Model& m = p.model;
  m.name = name;
  for (const KeySpec& k : schema()) k.set(p, v.at(k.full()));
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
    const std::string shown = x == std::floor(x) && x < 1e15 ? formatNumber(x, true) : numberText(x);
    throw SceneError(v.at(key).origin + ": " + key + " = " + shown + ": " + what + "; at most " +
                     numberText(kMaxElements) + " elements are allowed");
  };
  const double h = num("root.element_length_mm");
  auto count = [](double x) { return x < 1e15 ? formatNumber(std::ceil(x), true) : numberText(x); };
  const double initialElements = num("root.initial_length_mm") / h;
  if (initialElements > kMaxElements)
    capError({"root.initial_length_mm", "root.element_length_mm"},
             "root.initial_length_mm / root.element_length_mm = " + numberText(num("root.initial_length_mm")) + " mm / " +
                 numberText(h) + " mm = " + count(initialElements) + " elements at the start");
  if (m.growth.enabled) {
    const double grown = num("root.initial_length_mm") +
                         num("growth.steps") * num("growth.step_h") * num("growth.rate_per_h") * num("growth.growth_zone_mm");
    const double finalElements = grown / h;
    if (finalElements > kMaxElements)
      capError({"growth.steps", "growth.step_h", "growth.rate_per_h", "growth.growth_zone_mm", "root.element_length_mm",
                "root.initial_length_mm"},
               "the root grows to " + numberText(grown) +
                   " mm (root.initial_length_mm + growth.steps * growth.step_h * growth.rate_per_h * "
                   "growth.growth_zone_mm) = " + count(finalElements) + " elements of root.element_length_mm = " +
                   numberText(h) + " mm");
  }
  if (!m.env.plane.enabled && m.env.base == BaseCondition::Free && !m.growth.enabled &&
      (m.env.tipForce.norm() > 0 || m.env.gravity.norm() > 0))
    relationError(v, "load.base", "= \"free\" with a net load has no equilibrium; clamp the base");
  return p;
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
    case KeyType::Vector2: return "[" + formatNumber(x.vec[0], false) + ", " + formatNumber(x.vec[1], false) + "]";
  }
  return "";
}

Values valuesOf(const SceneParams& p, const std::string& origin) {
  Values values;
  for (const KeySpec& k : schema()) {
    Value x = k.get(p);
    x.origin = origin;
    values[k.full()] = x;
  }
  return values;
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

namespace rootsim {

std::string plateKeysMarkdown(const std::string& section) {
  std::string md = "| key | default | range | meaning |\n|---|---|---|---|\n";
  for (const detail::KeySpec& k : detail::plateSchema()) {
    if (k.section != section) continue;
    const detail::Value d = detail::defaultValue(k);
    std::string def = k.type == detail::KeyType::Vector2 ? "required" : detail::tomlText(k, d);
    if (k.full() == "seedling.name") def = "required";
    if (!k.defaultFollows.empty()) def = "as `" + k.defaultFollows + "`";
    std::string range = detail::rangeText(k);
    if (!k.choices.empty())
      for (size_t i = 0; i < k.choices.size(); ++i) range += (i ? ", " : "") + ("`\"" + k.choices[i] + "\"`");
    const bool plain = def == "required" || !k.defaultFollows.empty();
    md += "| `" + k.key + "` | " + (plain ? def : "`" + def + "`") + " | " + range + " | " + k.doc + " |\n";
  }
  return md;
}

std::vector<std::string> plateKeys(const std::string& section) {
  std::vector<std::string> keys;
  for (const detail::KeySpec& k : detail::plateSchema())
    if (k.section == section) keys.push_back(k.key);
  return keys;
}

}  // namespace rootsim
