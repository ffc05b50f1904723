// The plate of a scene (docs/plate.md, Scenes): [[seedling]] tables with their [seedling.set],
// [population.spread] and each seedling's model; the keys are plateSchema's and schema()'s, read by
// readValue. Every error names file:line and the key.
#include "plate_scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "rootsim/contact.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"
#include "scene_toml.hpp"

namespace rootsim::detail {

namespace {

// the model keys a seedling may set for itself: its root, growth and tropism (growth.steps, growth.step_h
// and growth.enabled are the plate's: all roots grow in the same steps), and its perturbation; and its
// laterals' keys but the sides' seed (one stream draws every root's sides)
std::string whyNotSeedlingKey(const KeySpec& k) {
  if (k.full() == "growth.steps" || k.full() == "growth.step_h" || k.full() == "growth.enabled")
    return "is the plate's (every root grows in the same steps): set it in [growth]";
  if (k.full() == "root.initial_angle_deg") return "is a one-root scene's: a seedling's direction is its angle_deg";
  if (k.full() == "laterals.seed") return "is the plate's (one stream draws every root's sides): set it in [laterals]";
  if (k.section == "root" || k.section == "growth" || k.section == "tropism" || k.section == "laterals") return "";
  if (k.full() == "solver.seed" || k.full() == "solver.perturbation") return "";
  return "is the plate's (a seedling sets root.*, growth.*, tropism.* and laterals.* keys, solver.seed and "
         "solver.perturbation): set it in [" + k.section + "]";
}

// the keys a seedling's set or [population.spread] may name: the model's and the laterals' by
// "section.key", and in the spread the seedling's own angle_deg and set_point_deg
std::vector<std::string> ownKeyNames(bool seedlingKeys) {
  std::vector<std::string> names;
  for (const KeySpec& k : schema()) names.push_back(k.full());
  for (const KeySpec& k : plateSchema())
    if (k.section == "laterals" || (seedlingKeys && k.section == "seedling" && k.type == KeyType::Real))
      names.push_back(k.section == "seedling" ? k.key : k.full());
  return names;
}

// a key named in a seedling's set or in [population.spread] (where: "seedling[1].set"): the schema's
// entry, checked; its full name ("tropism.beta", "laterals.delay_h", "seedling.angle_deg")
const KeySpec& ownKey(const std::string& written, const std::string& loc, const std::string& where, bool spread) {
  const KeySpec* k = nullptr;
  if (spread && written.find('.') == std::string::npos) k = findPlateKey("seedling", written);
  if (k && k->type != KeyType::Real) k = nullptr;
  if (const auto dot = written.find('.'); !k && dot != std::string::npos) {
    const std::string section = written.substr(0, dot), key = written.substr(dot + 1);
    k = section == "laterals" ? findPlateKey(section, key) : findKey(section, key);
  }
  if (!k) {
    const std::string near = closestName(written, ownKeyNames(spread));
    throw SceneError(loc + ": unknown key " + where + "." + printable(written) +
                     (near.empty() ? "" : " (did you mean " + near + "?)"));
  }
  if (k->section != "seedling")
    if (const std::string why = whyNotSeedlingKey(*k); !why.empty()) throw SceneError(loc + ": " + where + "." + written + " " + why);
  return *k;
}

struct Spread {
  enum class Law { Normal, Uniform } law = Law::Normal;
  double width = 0;  // sd or half width, in the key's unit
  std::string loc;
  std::string full;  // the key's full name
};

double draw(const Spread& s, std::uint64_t& state) {
  return s.law == Spread::Law::Normal ? s.width * splitmixNormal(state) : s.width * splitmixUniform(state);
}

// [population.spread]: by the key as written (drawn in that order, alphabetical)
std::map<std::string, Spread> readSpreads(const toml::node& n, const std::string& sourceName, const std::string& loc) {
  std::map<std::string, Spread> spreads;
  const toml::table* st = n.as_table();
  if (!st) throw SceneError(loc + ": population.spread must be a table (got " + describeNode(n) + ")");
  for (auto&& [sk, sn] : *st) {
    const std::string written(sk.str()), sloc = where(sourceName, sk.source());
    const KeySpec& ks = ownKey(written, sloc, "population.spread", true);
    if (ks.type != KeyType::Real)
      throw SceneError(sloc + ": population.spread." + written + ": only number keys vary (it is " + typeName(ks.type) + ")");
    const toml::table* law = sn.as_table();
    if (!law || law->size() != 1 || !(law->get("normal_sd") || law->get("uniform_half_width")))
      throw SceneError(sloc + ": population.spread." + written + " must be { normal_sd = S } or { uniform_half_width = W } (got " +
                       describeNode(sn) + ")");
    Spread s;
    s.loc = sloc;
    s.full = ks.full();
    s.law = law->get("normal_sd") ? Spread::Law::Normal : Spread::Law::Uniform;
    // the width: a number > 0 in the key's unit
    KeySpec width = ks;
    width.lo = 0, width.loOpen = true, width.hi = 1e300, width.hiOpen = false;
    const std::string lawKey = s.law == Spread::Law::Normal ? "normal_sd" : "uniform_half_width";
    s.width = readValue(width, *law->get(lawKey), sloc, "population.spread." + written + "." + lawKey, "").num;
    spreads[written] = s;
  }
  return spreads;
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

// the relations between a root's lateral keys and its model, as buildModel checks the model's; the
// message names the origin of the key (values: its model's and laterals' keys by full name)
void checkLaterals(const Values& v, const std::string& tableLoc, const std::string& suffix) {
  auto origin = [&](const char* key) {
    const std::string& o = v.at(key).origin;
    return o == "default" ? tableLoc : o;
  };
  auto mm = [&](const char* key) { return formatNumber(v.at(key).num, false); };
  const double h = v.at("root.element_length_mm").num;
  // a lateral of at least two elements of the root's element length
  if (v.at("laterals.initial_length_mm").num < 2.0 * h)
    throw SceneError(origin("laterals.initial_length_mm") + ": laterals.initial_length_mm " + mm("laterals.initial_length_mm") +
                     " mm is shorter than two elements of root.element_length_mm = " + formatNumber(h, false) + " mm" + suffix);
  // two successive sites may put laterals on one side (sides = "random"): their bases must not overlap
  if (v.at("laterals.spacing_mm").num < 2.0 * v.at("laterals.radius_mm").num)
    throw SceneError(origin("laterals.spacing_mm") + ": laterals.spacing_mm " + mm("laterals.spacing_mm") +
                     " mm is less than a lateral's diameter, 2 * laterals.radius_mm = " +
                     formatNumber(2.0 * v.at("laterals.radius_mm").num, false) +
                     " mm (two laterals on one side would overlap)" + suffix);
}

struct ParsedSeedling {
  std::string where, loc;
  Values values;          // its own: the plate's keys, the seedling's table, its set and its draws
  std::set<std::string> set;  // the model and lateral keys its set gives or [population] draws
};

}  // namespace

bool isPlateSection(const std::string& section) {
  return section == "plate" || section == "population" || section == "laterals";
}

PlateTables readPlate(const toml::table& root, const std::string& sourceName, const std::string& text,
                      const Values& base, const Values& plate, const std::string& name,
                      const std::vector<Obstacle>& obstacles) {
  PlateTables out;
  const toml::node* plateNode = root.get("plate");
  const toml::node* popNode = root.get("population");
  const toml::node* seedNode = root.get("seedling");
  const toml::node* latNode = root.get("laterals");
  if (!plateNode && !popNode && !seedNode && !latNode) return out;
  auto locOf = [&](const toml::node& n) { return where(sourceName, n.source()); };
  if (!seedNode) {
    const toml::node& n = plateNode ? *plateNode : (popNode ? *popNode : *latNode);
    throw SceneError(locOf(n) + ": [" + std::string(plateNode ? "plate" : (popNode ? "population" : "laterals")) +
                     "] without any [[seedling]]: a plate needs at least one seedling (docs/plate.md)");
  }
  const std::string latLoc = latNode ? locOf(*latNode) : sourceName;

  // the plate's parameters and its laterals, as read
  PlateParams& pp = out.spec.params;
  Values plateWide = base;
  for (const auto& [key, v] : plate) plateWide[key] = v;
  resolveFollowingDefaults(plateWide);
  for (const KeySpec& k : plateSchema()) {
    if (k.setPlate) k.setPlate(pp, plateWide.at(k.full()));
    if (k.setLaterals) k.setLaterals(pp.laterals, plateWide.at(k.full()));
  }
  if (latNode) checkLaterals(plateWide, latLoc, "");

  std::map<std::string, Spread> spreads;
  if (popNode)
    if (const toml::table* t = popNode->as_table())
      if (const toml::node* sp = t->get("spread")) spreads = readSpreads(*sp, sourceName, locOf(*sp));

  // [[seedling]]: each table's keys, then its set
  const toml::array* arr = seedNode->as_array();
  if (!arr || !arr->is_array_of_tables())
    throw SceneError(locOf(*seedNode) + ": seedling must be an array of tables ([[seedling]]), got " + describeNode(*seedNode));
  std::vector<std::string> tableKeys;
  for (const KeySpec& k : plateSchema())
    if (k.section == "seedling") tableKeys.push_back(k.key);
  tableKeys.push_back("set");
  std::vector<ParsedSeedling> seeds;
  std::uint64_t stream = pp.populationSeed;
  for (const toml::node& tn : *arr) {
    const toml::table& t = *tn.as_table();
    ParsedSeedling ps;
    ps.where = "seedling[" + std::to_string(seeds.size() + 1) + "]";
    ps.loc = sourceName + ":" + std::to_string(t.source().begin.line);
    ps.values = plateWide;
    for (const KeySpec& k : plateSchema())
      if (k.section == "seedling") ps.values[k.full()] = defaultValue(k);
    for (auto&& [k, n] : t) {
      const std::string key(k.str()), loc = where(sourceName, k.source());
      if (key == "set") {
        const toml::table* st = n.as_table();
        if (!st) throw SceneError(loc + ": " + ps.where + ".set must be a table ([seedling.set]), got " + describeNode(n));
        auto one = [&](const std::string& written, const toml::node& vn, const std::string& vloc) {
          const KeySpec& ks = ownKey(written, vloc, ps.where + ".set", false);
          ps.values[ks.full()] = readValue(ks, vn, vloc, ps.where + ".set." + written, text);
          ps.set.insert(ks.full());
        };
        for (auto&& [sk, sn] : *st) {
          const std::string skey(sk.str()), sloc = where(sourceName, sk.source());
          if (const toml::table* sub = sn.as_table()) {  // [seedling.set.tropism] beta = 0.3
            for (auto&& [k2, n2] : *sub) one(skey + "." + std::string(k2.str()), n2, where(sourceName, k2.source()));
          } else {
            one(skey, sn, sloc);  // "tropism.beta" = 0.3
          }
        }
        continue;
      }
      const KeySpec* ks = findPlateKey("seedling", key);
      if (!ks) {
        const std::string near = closestName(key, tableKeys);
        std::string all;
        for (const std::string& c : tableKeys) all += (all.empty() ? "" : ", ") + c;
        throw SceneError(loc + ": unknown key " + ps.where + "." + printable(key) +
                         (near.empty() ? " (seedling keys: " + all + ")" : " (did you mean " + ps.where + "." + near + "?)"));
      }
      ps.values[ks->full()] = readValue(*ks, n, loc, ps.where + "." + key, text);
    }
    resolveFollowingDefaults(ps.values);  // before the draws: a spread key's centre is its value
    const std::string seedName = ps.values.at("seedling.name").str;
    if (ps.values.at("seedling.name").origin == "default")
      throw SceneError(ps.loc + ": " + ps.where + ".name is missing (each seedling is named)");
    if (ps.values.at("seedling.position_mm").origin == "default")
      throw SceneError(ps.loc + ": " + ps.where + ".position_mm is missing");
    for (const ParsedSeedling& o : seeds) {
      const std::string& other = o.values.at("seedling.name").str;
      if (other == seedName) throw SceneError(ps.loc + ": " + ps.where + ".name \"" + seedName + "\" is taken by " + o.where);
      // a lateral root is named after its parent, NAME.K: no seedling may take such a name
      for (const auto& [a, b] : {std::pair<const ParsedSeedling*, const ParsedSeedling*>{&o, &ps},
                                  std::pair<const ParsedSeedling*, const ParsedSeedling*>{&ps, &o}}) {
        const std::string& parent = a->values.at("seedling.name").str;
        const std::string& n = b->values.at("seedling.name").str;
        if (a->values.at("laterals.enabled").b && n.size() > parent.size() + 1 &&
            n.compare(0, parent.size() + 1, parent + ".") == 0 &&
            std::all_of(n.begin() + static_cast<long>(parent.size()) + 1, n.end(), [](char c) { return c >= '0' && c <= '9'; }))
          throw SceneError(ps.loc + ": " + ps.where + ".name: \"" + n + "\" is the name of a lateral root of " + parent +
                           " ([laterals] names them NAME.1, NAME.2, ...)");
      }
    }
    // population: each seedling draws its keys in turn from one seeded stream, around its own value
    for (const auto& [written, s] : spreads) {
      const KeySpec& ks = ownKey(written, s.loc, "population.spread", true);
      Value v = ps.values.at(s.full);
      const double centre = v.num;
      int tries = 0;
      for (;; ++tries) {
        if (tries == 1000)
          throw SceneError(s.loc + ": population.spread." + written + ": 1000 draws for " + ps.where +
                           " all fell outside the key's range; narrow the spread");
        v.num = centre + draw(s, stream);
        if (checkValue(ks, v).empty()) break;
      }
      v.origin = s.loc + " (drawn)";
      ps.values[s.full] = v;
      if (ks.section != "seedling") ps.set.insert(s.full);
    }
    resolveFollowingDefaults(ps.values);
    seeds.push_back(std::move(ps));
  }

  // each seedling's model, laterals and place on the plate
  out.spec.base = buildModel(base, name);
  out.spec.base.env.obstacles = obstacles;
  std::vector<Segment2> initial;
  for (size_t i = 0; i < seeds.size(); ++i) {
    ParsedSeedling& ps = seeds[i];
    Seedling sd;
    const std::string suffix = " (in " + ps.where + ", " + ps.values.at("seedling.name").str + ")";
    try {
      sd.model = buildModel(ps.values, name);
    } catch (const SceneError& e) {
      throw SceneError(std::string(e.what()) + suffix);
    }
    // (a plate without [laterals] checks the laterals a seedling turns on for itself)
    if (latNode || ps.values.at("laterals.enabled").b) checkLaterals(ps.values, latLoc, suffix);
    sd.laterals = LateralParams{};
    for (const KeySpec& k : plateSchema()) {
      if (k.setSeedling) k.setSeedling(sd, ps.values.at(k.full()));
      if (k.setLaterals) k.setLaterals(*sd.laterals, ps.values.at(k.full()));
    }
    // the keys that differ from the plate's, for the summary
    for (const std::string& full : ps.set) {
      const auto dot = full.find('.');
      const KeySpec* ks = full.compare(0, dot, "laterals") == 0 ? findPlateKey("laterals", full.substr(dot + 1))
                                                                : findKey(full.substr(0, dot), full.substr(dot + 1));
      const std::string was = tomlText(*ks, plateWide.at(full)), now = tomlText(*ks, ps.values.at(full));
      if (now != was) sd.overrides.push_back(full + "=" + now);
    }
    const Model& m = sd.model;
    const double R = m.rod.radius;
    const std::string positionLoc = ps.values.at("seedling.position_mm").origin;
    const Segment2 seg = initialSegment(sd.position, m.initial.angle, m.initial.length);
    // on the plate, whole: base and initial tip at least R inside every edge
    for (const Vec3& p : {seg.a, seg.b})
      if (p.x() < R || p.x() > pp.width - R || p.y() < R || p.y() > pp.length - R)
        throw SceneError(positionLoc + ": " + ps.where + ".position_mm " + mm2(sd.position) + " puts " + sd.name +
                         "'s initial root off the plate (the plate spans [0, " + formatNumber(pp.width / units::mm, false) +
                         "] x [0, " + formatNumber(pp.length / units::mm, false) + "] mm; the root, of radius " +
                         formatNumber(R / units::mm, false) + " mm, must lie at least that far inside)");
    for (size_t j = 0; j < initial.size(); ++j) {
      const Seedling& o = out.spec.seedlings[j];
      const double Rj = o.model.rod.radius;
      const double d = segmentDistance(seg, initial[j]);
      if (d < R + Rj)
        throw SceneError(positionLoc + ": " + ps.where + ".position_mm " + mm2(sd.position) + ": " + sd.name +
                         "'s initial root comes within " + mmText(d) + " of " + seeds[j].where + " (" + o.name +
                         "), closer than their radii's sum " + mmText(R + Rj));
    }
    for (size_t o = 0; o < obstacles.size(); ++o) {
      const Obstacle& ob = obstacles[o];
      const Segment2 os{Vec3(ob.from.x(), ob.from.y(), 0), Vec3(ob.to.x(), ob.to.y(), 0)};
      const double d = segmentDistance(seg, os);
      if (d < R + ob.radius)
        throw SceneError(positionLoc + ": " + ps.where + ".position_mm " + mm2(sd.position) + ": " + sd.name +
                         "'s initial root overlaps obstacle[" + std::to_string(o + 1) + "] (obstacles of a plate are in "
                         "plate coordinates, from the plate's origin)");
    }
    initial.push_back(seg);
    // the obstacles in the root's own frame (its base's foot at the origin)
    sd.model.env.obstacles = obstacles;
    for (Obstacle& ob : sd.model.env.obstacles) {
      ob.from -= sd.position;
      ob.to -= sd.position;
    }
    out.spec.seedlings.push_back(std::move(sd));
  }

  // the resolved text: the plate, the laterals, then each seedling with its final values. The drawn
  // values stand in each seedling's set: the resolved text loads to the same plate without drawing
  // again, and round-trips (no [population] in it)
  const std::string plateText = plateTableToml(pp);
  std::string all = plateText;
  if (latNode) all += lateralsToml(pp.laterals);
  for (const Seedling& sd : out.spec.seedlings) {
    all += seedlingToml(sd, out.spec.base, &pp.laterals);
    out.rootToml.push_back(plateText + seedlingToml(sd, out.spec.base));
  }
  out.toml = all;
  return out;
}

// a table of the plate's keys of one section, from an owner's values
template <class Owner, class Get>
std::string tableToml(const char* section, const Owner& owner, Get get) {
  std::string os = std::string("\n[") + section + "]\n";
  for (const KeySpec& k : plateSchema())
    if (k.section == section) os += k.key + " = " + tomlText(k, (k.*get)(owner)) + "\n";
  return os;
}

std::string plateTableToml(const PlateParams& pp) { return tableToml("plate", pp, &KeySpec::getPlate); }

std::string lateralsToml(const LateralParams& lp) { return tableToml("laterals", lp, &KeySpec::getLaterals); }

std::string seedlingToml(const Seedling& sd, const Model& base, const LateralParams* plateLaterals) {
  std::string os = "\n[[seedling]]\n";
  for (const KeySpec& k : plateSchema()) {
    if (k.section != "seedling") continue;
    const Value v = k.getSeedling(sd);
    // the optional keys at their default are left out (a following key's default: its leader's value)
    const bool optional = k.key == "genotype" || k.key.rfind("set_point_", 0) == 0;
    const KeySpec* leader = k.defaultFollows.empty() ? nullptr : findPlateKey(k.section, k.defaultFollows);
    const std::string def = leader ? tomlText(*leader, leader->getSeedling(sd)) : tomlText(k, defaultValue(k));
    if (optional && tomlText(k, v) == def) continue;
    os += k.key + " = " + tomlText(k, v) + "\n";
  }
  // its keys that differ from the plate's
  // (a seedling's keys are its model's: what the run writes is the plate's)
  const Values mine = valuesOf(SceneParams{sd.model, {}}, ""), plates = valuesOf(SceneParams{base, {}}, "");
  std::string set;
  for (const KeySpec& k : schema()) {
    if (!whyNotSeedlingKey(k).empty()) continue;
    const std::string a = tomlText(k, mine.at(k.full())), b = tomlText(k, plates.at(k.full()));
    if (a != b) set += "\"" + k.full() + "\" = " + a + "\n";
  }
  if (plateLaterals)
    for (const KeySpec& k : plateSchema()) {
      if (!k.getLaterals) continue;
      const std::string a = tomlText(k, k.getLaterals(sd.laterals ? *sd.laterals : *plateLaterals)),
                        b = tomlText(k, k.getLaterals(*plateLaterals));
      if (a != b) set += "\"" + k.full() + "\" = " + a + "\n";
    }
  if (!set.empty()) os += "\n[seedling.set]\n" + set;
  return os;
}

}  // namespace rootsim::detail
