// The plate tables of a scene (docs/plate.md, Scenes): [plate], [population] and [[seedling]] with its
// [seedling.set]. Every error names file:line and the key.
#include "plate_scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

#include "rootsim/contact.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"
#include "scene_toml.hpp"

namespace rootsim::detail {

namespace {

// the keys a seedling may set for itself: its root, growth and tropism (growth.steps, growth.step_h and
// growth.enabled are the plate's: all roots grow in the same steps), and its perturbation
std::string whyNotSeedlingKey(const KeySpec& k) {
  if (k.full() == "growth.steps" || k.full() == "growth.step_h" || k.full() == "growth.enabled")
    return "is the plate's (every root grows in the same steps): set it in [growth]";
  if (k.full() == "root.initial_angle_deg") return "is a one-root scene's: a seedling's direction is its angle_deg";
  if (k.section == "root" || k.section == "growth" || k.section == "tropism") return "";
  if (k.full() == "solver.seed" || k.full() == "solver.perturbation") return "";
  return "is the plate's (a seedling sets root.*, growth.* and tropism.* keys, solver.seed and "
         "solver.perturbation): set it in [" + k.section + "]";
}

double number(const toml::node& n, const std::string& loc, const std::string& key) {
  double x = 0;
  if (n.is_floating_point()) x = *n.value<double>();
  else if (n.is_integer()) x = static_cast<double>(*n.value<int64_t>());
  else throw SceneError(loc + ": " + key + " must be a number (got " + describeNode(n) + ")");
  if (!std::isfinite(x)) throw SceneError(loc + ": " + key + " must be finite");
  return x;
}

std::string suggestFrom(const std::string& key, const std::vector<std::string>& keys) {
  std::string best;
  int bestD = 1 << 30;
  for (const auto& c : keys)
    if (editDistance(key, c) < bestD) { bestD = editDistance(key, c); best = c; }
  return bestD <= 2 ? " (did you mean " + best + "?)" : "";
}

std::string suggestSchemaKey(const std::string& full) {
  std::vector<std::string> keys;
  for (const KeySpec& k : schema()) keys.push_back(k.full());
  return suggestFrom(full, keys);
}

// a scene key named in a seedling's set or in [population.spread]: the schema's entry, checked
const KeySpec& seedlingKey(const std::string& full, const std::string& loc, const std::string& where) {
  const auto dot = full.find('.');
  const KeySpec* k = dot == std::string::npos ? nullptr : findKey(full.substr(0, dot), full.substr(dot + 1));
  if (!k) throw SceneError(loc + ": unknown key " + where + "." + printable(full) + suggestSchemaKey(full));
  if (const std::string why = whyNotSeedlingKey(*k); !why.empty())
    throw SceneError(loc + ": " + where + "." + full + " " + why);
  return *k;
}

struct Spread {
  enum class Law { Normal, Uniform } law = Law::Normal;
  double width = 0;  // sd or half width, in the key's unit
  std::string loc;
};

// a normal number from two uniforms of the stream (Box-Muller, the cosine branch)
double normalDraw(std::uint64_t& state) {
  const double u1 = 0.5 * (1.0 - splitmixUniform(state));  // (0, 1]
  const double u2 = 0.5 * (splitmixUniform(state) + 1.0);  // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double draw(const Spread& s, std::uint64_t& state) {
  return s.law == Spread::Law::Normal ? s.width * normalDraw(state) : s.width * splitmixUniform(state);
}


// a length in a message [m -> "0.15 mm"]
std::string mmText(double m) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g mm", m / units::mm);
  return b;
}

std::string mm2(const Eigen::Vector2d& p) {
  return "[" + formatNumber(p.x() / units::mm, false) + ", " + formatNumber(p.y() / units::mm, false) + "]";
}

// the initial root of a seedling in plate coordinates (lateral, downhill) [m]: its base and its tip
struct Segment2 {
  Vec3 a, b;
};
Segment2 initialSegment(const Eigen::Vector2d& pos, double angle, double length) {
  const Vec3 a(pos.x(), pos.y(), 0.0);
  return {a, a + length * Vec3(std::sin(angle), std::cos(angle), 0.0)};
}
double segmentDistance(const Segment2& p, const Segment2& q) {
  double sa = 0, sb = 0;
  closestSegmentPoints(p.a, p.b, q.a, q.b, sa, sb);
  return ((p.a + sa * (p.b - p.a)) - (q.a + sb * (q.b - q.a))).norm();
}

struct ParsedSeedling {
  Seedling sd;
  double angleDeg = 0;
  double setPointDeg = 0;
  std::string where, loc, positionLoc;
  std::map<std::string, Value> set;  // by full key: the seedling's own values (drawn ones included)
};

}  // namespace

bool isPlateTable(const std::string& section) {
  return section == "plate" || section == "population" || section == "seedling" || section == "laterals";
}

PlateTables parsePlateTables(const toml::table& root, const std::string& sourceName, const std::string& text,
                             const Values& base, const std::string& name, const std::vector<Obstacle>& obstacles) {
  PlateTables out;
  const toml::node* plateNode = root.get("plate");
  const toml::node* popNode = root.get("population");
  const toml::node* seedNode = root.get("seedling");
  const toml::node* latNode0 = root.get("laterals");
  if (!plateNode && !popNode && !seedNode && !latNode0) return out;
  auto locOf = [&](const toml::node& n) { return where(sourceName, n.source()); };
  if (!seedNode) {
    const toml::node& n = plateNode ? *plateNode : (popNode ? *popNode : *latNode0);
    throw SceneError(locOf(n) + ": [" + std::string(plateNode ? "plate" : (popNode ? "population" : "laterals")) +
                     "] without any [[seedling]]: a plate needs at least one seedling (docs/plate.md)");
  }

  // [plate]
  PlateParams& pp = out.spec.params;
  if (plateNode) {
    const toml::table* t = plateNode->as_table();
    if (!t) throw SceneError(locOf(*plateNode) + ": plate must be a table ([plate]), got " + describeNode(*plateNode));
    for (auto&& [k, n] : *t) {
      const std::string key(k.str()), loc = where(sourceName, k.source());
      if (key == "width_mm" || key == "length_mm") {
        const double x = number(n, loc, "plate." + key);
        if (!(x > 0 && x <= 1000))
          throw SceneError(loc + ": plate." + key + " must be in (0, 1000] mm (got " + formatNumber(x, false) + ")");
        (key == "width_mm" ? pp.width : pp.length) = x * units::mm;
      } else {
        throw SceneError(loc + ": unknown key plate." + printable(key) + suggestFrom(key, {"width_mm", "length_mm"}) +
                         " (plate keys: width_mm, length_mm)");
      }
    }
  }

  // [population]
  std::uint64_t popSeed = 1;
  std::map<std::string, Spread> spreads;  // by key ("tropism.beta", "angle_deg"): drawn in this order
  if (popNode) {
    const toml::table* t = popNode->as_table();
    if (!t) throw SceneError(locOf(*popNode) + ": population must be a table ([population]), got " + describeNode(*popNode));
    for (auto&& [k, n] : *t) {
      const std::string key(k.str()), loc = where(sourceName, k.source());
      if (key == "seed") {
        if (!n.is_integer() || *n.value<int64_t>() < 0)
          throw SceneError(loc + ": population.seed must be an integer >= 0 (got " + describeNode(n) + ")");
        popSeed = static_cast<std::uint64_t>(*n.value<int64_t>());
      } else if (key == "spread") {
        const toml::table* st = n.as_table();
        if (!st) throw SceneError(loc + ": population.spread must be a table (got " + describeNode(n) + ")");
        for (auto&& [sk, sn] : *st) {
          const std::string full(sk.str()), sloc = where(sourceName, sk.source());
          if (full != "angle_deg") {
            const KeySpec& ks = seedlingKey(full, sloc, "population.spread");
            if (ks.type != KeyType::Real)
              throw SceneError(sloc + ": population.spread." + full + ": only number keys vary (it is " + typeName(ks.type) + ")");
          }
          const toml::table* law = sn.as_table();
          if (!law || law->size() != 1 || !(law->get("normal_sd") || law->get("uniform_half_width")))
            throw SceneError(sloc + ": population.spread." + full + " must be { normal_sd = S } or { uniform_half_width = W } (got " +
                             describeNode(sn) + ")");
          Spread s;
          s.loc = sloc;
          s.law = law->get("normal_sd") ? Spread::Law::Normal : Spread::Law::Uniform;
          const std::string lawKey = s.law == Spread::Law::Normal ? "normal_sd" : "uniform_half_width";
          s.width = number(*law->get(lawKey), sloc, "population.spread." + full + "." + lawKey);
          if (!(s.width > 0))
            throw SceneError(sloc + ": population.spread." + full + "." + lawKey + " must be > 0 (got " + formatNumber(s.width, false) + ")");
          spreads[full] = s;
        }
      } else {
        throw SceneError(loc + ": unknown key population." + printable(key) + suggestFrom(key, {"seed", "spread"}) +
                         " (population keys: seed, spread)");
      }
    }
  }

  // [laterals]
  if (const toml::node* latNode = root.get("laterals")) {
    const toml::table* t = latNode->as_table();
    if (!t) throw SceneError(locOf(*latNode) + ": laterals must be a table ([laterals]), got " + describeNode(*latNode));
    LateralParams& lp = pp.laterals;
    static const std::vector<std::string> latKeys = {
        "enabled", "first_mm", "spacing_mm", "apical_unbranched_mm", "delay_h", "sides", "seed", "insertion_deg",
        "radius_mm", "rate_per_h", "growth_zone_mm", "initial_length_mm", "beta", "gamma", "twist_r_tau",
        "set_point_deg", "max_order"};
    for (auto&& [k, node] : *t) {
      const toml::node& n = node;  // (a lambda below reads it: clang captures no structured binding)
      const std::string key(k.str()), loc = where(sourceName, k.source()), full = "laterals." + key;
      // a number in (lo, hi] (or [lo, hi] when closedLo), times its unit
      auto num = [&](double lo, double hi, bool closedLo, double unit) {
        const double x = number(n, loc, full);
        if (!(closedLo ? x >= lo : x > lo) || !(x <= hi))
          throw SceneError(loc + ": " + full + " must be in " + (closedLo ? "[" : "(") + significantText(lo) + ", " + significantText(hi) +
                           "] (got " + significantText(x) + ")");
        return x * unit;
      };
      if (key == "enabled") {
        if (!n.is_boolean()) throw SceneError(loc + ": " + full + " must be true or false (got " + describeNode(n) + ")");
        lp.enabled = *n.value<bool>();
      } else if (key == "sides") {
        const std::string v = n.is_string() ? *n.value<std::string>() : std::string();
        if (v != "alternate" && v != "random")
          throw SceneError(loc + ": " + full + " must be one of \"alternate\", \"random\" (got " + describeNode(n) + ")");
        lp.alternate = v == "alternate";
      } else if (key == "seed" || key == "max_order") {
        if (!n.is_integer()) throw SceneError(loc + ": " + full + " must be an integer (got " + describeNode(n) + ")");
        const std::int64_t v = *n.value<int64_t>();
        if (key == "seed") {
          if (v < 0) throw SceneError(loc + ": " + full + " must be >= 0 (got " + std::to_string(v) + ")");
          lp.seed = static_cast<std::uint64_t>(v);
        } else {
          if (v < 1 || v > 4) throw SceneError(loc + ": " + full + " must be in [1, 4] (got " + std::to_string(v) + ")");
          lp.maxOrder = static_cast<int>(v);
        }
      } else if (key == "first_mm") lp.first = num(0, 1000, true, units::mm);
      else if (key == "spacing_mm") lp.spacing = num(0, 1000, false, units::mm);
      else if (key == "apical_unbranched_mm") lp.apicalUnbranched = num(0, 1000, true, units::mm);
      else if (key == "delay_h") lp.delay = num(0, 1000, true, units::hour);
      else if (key == "insertion_deg") lp.insertion = num(0, 180, false, units::deg);
      else if (key == "radius_mm") lp.radius = num(0, 100, false, units::mm);
      else if (key == "rate_per_h") lp.rate = num(0, 10, false, 1.0 / units::hour);
      else if (key == "growth_zone_mm") lp.zoneLength = num(0, 1000, false, units::mm);
      else if (key == "initial_length_mm") lp.initialLength = num(0, 1000, false, units::mm);
      else if (key == "beta") lp.beta = num(0, 100, true, 1.0);
      else if (key == "gamma") lp.gamma = num(0, 100, true, 1.0);
      else if (key == "twist_r_tau") lp.rTau = num(-10, 10, true, 1.0);
      else if (key == "set_point_deg") lp.setPoint = num(0, 180, true, units::deg);
      else
        throw SceneError(loc + ": unknown key laterals." + printable(key) + suggestFrom(key, latKeys) + " (laterals keys: " +
                         [] {
                           std::string all;
                           for (const auto& c : latKeys) all += (all.empty() ? "" : ", ") + c;
                           return all;
                         }() + ")");
    }
    // a lateral of at least two elements of the plate's element length
    const double h = base.at("root.element_length_mm").num * units::mm;
    if (lp.initialLength < 2.0 * h)
      throw SceneError(locOf(*latNode) + ": laterals.initial_length_mm " + formatNumber(lp.initialLength / units::mm, false) +
                       " mm is shorter than two elements of root.element_length_mm = " + formatNumber(h / units::mm, false) + " mm");
    // two successive sites may put laterals on one side (sides = "random"): their bases must not overlap
    if (lp.spacing < 2.0 * lp.radius)
      throw SceneError(locOf(*latNode) + ": laterals.spacing_mm " + formatNumber(lp.spacing / units::mm, false) +
                       " mm is less than a lateral's diameter, 2 * laterals.radius_mm = " +
                       formatNumber(2.0 * lp.radius / units::mm, false) + " mm (two laterals on one side would overlap)");
  }

  // [[seedling]]
  const toml::array* arr = seedNode->as_array();
  if (!arr || !arr->is_array_of_tables())
    throw SceneError(locOf(*seedNode) + ": seedling must be an array of tables ([[seedling]]), got " + describeNode(*seedNode));
  static const std::vector<std::string> keys = {"name", "genotype", "position_mm", "angle_deg", "set_point_deg", "set"};
  std::vector<ParsedSeedling> seeds;
  std::uint64_t stream = popSeed;
  for (const toml::node& tn : *arr) {
    const toml::table& t = *tn.as_table();
    ParsedSeedling ps;
    ps.where = "seedling[" + std::to_string(seeds.size() + 1) + "]";
    ps.loc = sourceName + ":" + std::to_string(t.source().begin.line);
    bool havePosition = false;
    for (auto&& [k, n] : t) {
      const std::string key(k.str()), loc = where(sourceName, k.source());
      if (std::find(keys.begin(), keys.end(), key) == keys.end())
        throw SceneError(loc + ": unknown key " + ps.where + "." + printable(key) + suggestFrom(key, keys) +
                         " (seedling keys: name, genotype, position_mm, angle_deg, set_point_deg, set)");
      if (key == "name" || key == "genotype") {
        if (!n.is_string()) throw SceneError(loc + ": " + ps.where + "." + key + " must be a string (got " + describeNode(n) + ")");
        const std::string v = *n.value<std::string>();
        if (key == "name") {
          // a name is a folder of the run directory
          const bool ok = !v.empty() && v.size() <= 64 && v != "." && v != ".." &&
                          std::all_of(v.begin(), v.end(), [](char c) {
                            return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
                          });
          if (!ok)
            throw SceneError(loc + ": " + ps.where + ".name must be 1-64 letters, digits, '_', '-' or '.' (got \"" +
                             printable(v) + "\")");
        } else {
          // a label in CSV and JSON: printable, no quotes or backslashes
          const bool ok = v.size() <= 64 && std::all_of(v.begin(), v.end(), [](char c) {
                            return c >= 32 && c < 127 && c != '"' && c != '\\';
                          });
          if (!ok)
            throw SceneError(loc + ": " + ps.where + ".genotype must be at most 64 printable characters without quotes "
                             "or backslashes (got \"" + printable(v) + "\")");
        }
        (key == "name" ? ps.sd.name : ps.sd.genotype) = v;
      } else if (key == "position_mm") {
        const toml::array* a = n.as_array();
        if (!a || a->size() != 2)
          throw SceneError(loc + ": " + ps.where + ".position_mm must be an array of 2 numbers [lateral, downhill] (got " +
                           describeNode(n) + ")");
        ps.sd.position = Eigen::Vector2d(number(*a->get(0), loc, ps.where + ".position_mm"),
                                         number(*a->get(1), loc, ps.where + ".position_mm")) * units::mm;
        ps.positionLoc = loc;
        havePosition = true;
      } else if (key == "set_point_deg") {
        ps.setPointDeg = number(n, loc, ps.where + ".set_point_deg");
        if (!(ps.setPointDeg >= 0 && ps.setPointDeg < 180))
          throw SceneError(loc + ": " + ps.where + ".set_point_deg must be in [0, 180) (got " + formatNumber(ps.setPointDeg, false) + ")");
      } else if (key == "angle_deg") {
        ps.angleDeg = number(n, loc, ps.where + ".angle_deg");
        if (!(std::abs(ps.angleDeg) <= 180))
          throw SceneError(loc + ": " + ps.where + ".angle_deg must be in [-180, 180] (got " + formatNumber(ps.angleDeg, false) + ")");
      } else {  // set
        const toml::table* st = n.as_table();
        if (!st) throw SceneError(loc + ": " + ps.where + ".set must be a table ([seedling.set]), got " + describeNode(n));
        auto one = [&](const std::string& full, const toml::node& vn, const std::string& vloc) {
          const KeySpec& ks = seedlingKey(full, vloc, ps.where + ".set");
          Value v;
          std::string why = convert(ks, vn, v, text);
          if (why.empty()) why = checkValue(ks, v);
          if (!why.empty()) throw SceneError(vloc + ": " + ps.where + ".set." + full + " " + why);
          v.origin = vloc;
          ps.set[full] = v;
        };
        for (auto&& [sk, sn] : *st) {
          const std::string skey(sk.str()), sloc = where(sourceName, sk.source());
          if (const toml::table* sub = sn.as_table()) {  // [seedling.set.tropism] beta = 0.3
            for (auto&& [k2, n2] : *sub) one(skey + "." + std::string(k2.str()), n2, where(sourceName, k2.source()));
          } else {
            one(skey, sn, sloc);  // "tropism.beta" = 0.3
          }
        }
      }
    }
    if (ps.sd.name.empty()) throw SceneError(ps.loc + ": " + ps.where + ".name is missing (each seedling is named)");
    if (!havePosition) throw SceneError(ps.loc + ": " + ps.where + ".position_mm is missing");
    for (const ParsedSeedling& o : seeds) {
      if (o.sd.name == ps.sd.name)
        throw SceneError(ps.loc + ": " + ps.where + ".name \"" + ps.sd.name + "\" is taken by " + o.where);
      // a lateral root is named after its parent, NAME.K: no seedling may take such a name
      for (const auto& [a, b] : {std::pair<const std::string*, const std::string*>{&o.sd.name, &ps.sd.name},
                                  std::pair<const std::string*, const std::string*>{&ps.sd.name, &o.sd.name}}) {
        const std::string& n = *b;
        if (pp.laterals.enabled && n.size() > a->size() + 1 && n.compare(0, a->size() + 1, *a + ".") == 0 &&
            std::all_of(n.begin() + static_cast<long>(a->size()) + 1, n.end(), [](char c) { return c >= '0' && c <= '9'; }))
          throw SceneError(ps.loc + ": " + ps.where + ".name: \"" + n + "\" is the name of a lateral root of " + *a +
                           " ([laterals] names them NAME.1, NAME.2, ...)");
      }
    }
    // population: each seedling draws its keys in turn from one seeded stream
    for (const auto& entry : spreads) {
      const std::string& full = entry.first;  // (named: the lambdas below read them)
      const Spread& s = entry.second;
      auto redraw = [&](const std::function<bool(double)>& accept, double centre) {
        for (int tries = 0; tries < 1000; ++tries) {
          const double x = centre + draw(s, stream);
          if (accept(x)) return x;
        }
        throw SceneError(s.loc + ": population.spread." + full + ": 1000 draws for " + ps.where +
                         " all fell outside the key's range; narrow the spread");
      };
      if (full == "angle_deg") {
        ps.angleDeg = redraw([](double x) { return std::abs(x) <= 180; }, ps.angleDeg);
        continue;
      }
      const auto dot = full.find('.');
      const KeySpec& ks = *findKey(full.substr(0, dot), full.substr(dot + 1));
      Value v = ps.set.count(full) ? ps.set[full] : base.at(full);
      const double centre = v.num;
      v.num = redraw([&](double x) { Value trial = v; trial.num = x; return checkValue(ks, trial).empty(); }, centre);
      v.origin = s.loc + " (drawn)";
      ps.set[full] = v;
    }
    seeds.push_back(std::move(ps));
  }

  // each seedling's model, and its place on the plate
  std::vector<Segment2> initial;
  for (ParsedSeedling& ps : seeds) {
    Values v = base;
    for (const auto& [full, val] : ps.set) {
      v[full] = val;
      const auto dot = full.find('.');
      const KeySpec& ks = *findKey(full.substr(0, dot), full.substr(dot + 1));
      const std::string was = tomlText(ks, base.at(full)), now = tomlText(ks, val);
      if (now != was) ps.sd.overrides.push_back(full + "=" + now);
    }
    Model m;
    try {
      m = buildModel(v, name);
    } catch (const SceneError& e) {
      throw SceneError(std::string(e.what()) + " (in " + ps.where + ", " + ps.sd.name + ")");
    }
    m.initial.angle = ps.angleDeg * units::deg;
    m.tropism.setPoint = ps.setPointDeg * units::deg;
    const double R = m.rod.radius;
    const Segment2 seg = initialSegment(ps.sd.position, m.initial.angle, m.initial.length);
    // on the plate, whole: base and initial tip at least R inside every edge
    for (const Vec3& p : {seg.a, seg.b})
      if (p.x() < R || p.x() > pp.width - R || p.y() < R || p.y() > pp.length - R)
        throw SceneError(ps.positionLoc + ": " + ps.where + ".position_mm " + mm2(ps.sd.position) + " puts " + ps.sd.name +
                         "'s initial root off the plate (the plate spans [0, " + formatNumber(pp.width / units::mm, false) +
                         "] x [0, " + formatNumber(pp.length / units::mm, false) + "] mm; the root, of radius " +
                         formatNumber(R / units::mm, false) + " mm, must lie at least that far inside)");
    for (size_t j = 0; j < initial.size(); ++j) {
      const double Rj = seeds[j].sd.model.rod.radius;
      const double d = segmentDistance(seg, initial[j]);
      if (d < R + Rj)
        throw SceneError(ps.positionLoc + ": " + ps.where + ".position_mm " + mm2(ps.sd.position) + ": " + ps.sd.name +
                         "'s initial root comes within " + mmText(d) + " of " +
                         seeds[j].where + " (" + seeds[j].sd.name + "), closer than their radii's sum " + mmText(R + Rj));
    }
    for (size_t o = 0; o < obstacles.size(); ++o) {
      const Obstacle& ob = obstacles[o];
      const Segment2 os{Vec3(ob.from.x(), ob.from.y(), 0), Vec3(ob.to.x(), ob.to.y(), 0)};
      const double d = segmentDistance(seg, os);
      if (d < R + ob.radius)
        throw SceneError(ps.positionLoc + ": " + ps.where + ".position_mm " + mm2(ps.sd.position) + ": " + ps.sd.name +
                         "'s initial root overlaps obstacle[" + std::to_string(o + 1) + "] (obstacles of a plate are in "
                         "plate coordinates, from the plate's origin)");
    }
    initial.push_back(seg);
    // the obstacles in the root's own frame (its base's foot at the origin)
    m.env.obstacles = obstacles;
    for (Obstacle& ob : m.env.obstacles) {
      ob.from -= ps.sd.position;
      ob.to -= ps.sd.position;
    }
    ps.sd.model = m;
  }

  // the resolved text: the plate, the laterals, then each seedling with its final values. The drawn
  // values stand in each seedling's set: the resolved text loads to the same plate without drawing
  // again, and round-trips (no [population] in it)
  out.spec.base = buildModel(base, name);
  out.spec.base.env.obstacles = obstacles;
  const std::string plate = plateTableToml(pp);
  std::string all = plate;
  if (root.get("laterals")) all += lateralsToml(pp.laterals);
  for (ParsedSeedling& ps : seeds) {
    const std::string table = seedlingToml(ps.sd, out.spec.base);
    all += table;
    out.rootToml.push_back(plate + table);
    out.spec.seedlings.push_back(std::move(ps.sd));
  }
  out.toml = all;
  return out;
}

std::string plateTableToml(const PlateParams& pp) {
  return "\n[plate]\nwidth_mm = " + formatNumber(pp.width / units::mm, false) +
         "\nlength_mm = " + formatNumber(pp.length / units::mm, false) + "\n";
}

std::string lateralsToml(const LateralParams& lp) {
  std::ostringstream os;
  auto n = [](double x) { return formatNumber(x, false); };
  os << "\n[laterals]\nenabled = " << (lp.enabled ? "true" : "false") << "\nfirst_mm = " << n(lp.first / units::mm)
     << "\nspacing_mm = " << n(lp.spacing / units::mm) << "\napical_unbranched_mm = " << n(lp.apicalUnbranched / units::mm)
     << "\ndelay_h = " << n(lp.delay / units::hour) << "\nsides = \"" << (lp.alternate ? "alternate" : "random")
     << "\"\nseed = " << lp.seed << "\ninsertion_deg = " << n(lp.insertion / units::deg)
     << "\nradius_mm = " << n(lp.radius / units::mm) << "\nrate_per_h = " << n(lp.rate * units::hour)
     << "\ngrowth_zone_mm = " << n(lp.zoneLength / units::mm) << "\ninitial_length_mm = " << n(lp.initialLength / units::mm)
     << "\nbeta = " << n(lp.beta) << "\ngamma = " << n(lp.gamma) << "\ntwist_r_tau = " << n(lp.rTau)
     << "\nset_point_deg = " << n(lp.setPoint / units::deg) << "\nmax_order = " << lp.maxOrder << "\n";
  return os.str();
}

std::string seedlingToml(const Seedling& sd, const Model& base) {
  std::ostringstream os;
  os << "\n[[seedling]]\nname = \"" << sd.name << "\"\n";
  if (!sd.genotype.empty()) os << "genotype = \"" << sd.genotype << "\"\n";
  os << "position_mm = " << mm2(sd.position) << "\nangle_deg = " << formatNumber(sd.model.initial.angle / units::deg, false) << "\n";
  if (sd.model.tropism.setPoint != 0.0) os << "set_point_deg = " << formatNumber(sd.model.tropism.setPoint / units::deg, false) << "\n";
  // its keys that differ from the plate's
  // (a seedling's keys are its model's: what the run writes is the plate's)
  const Values mine = valuesOf(SceneParams{sd.model, {}}, ""), plates = valuesOf(SceneParams{base, {}}, "");
  std::string set;
  for (const KeySpec& k : schema()) {
    if (!whyNotSeedlingKey(k).empty()) continue;
    const std::string a = tomlText(k, mine.at(k.full())), b = tomlText(k, plates.at(k.full()));
    if (a != b) set += "\"" + k.full() + "\" = " + a + "\n";
  }
  if (!set.empty()) os << "\n[seedling.set]\n" << set;
  return os.str();
}

}  // namespace rootsim::detail
