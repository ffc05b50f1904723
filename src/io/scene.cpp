// Scene files: TOML (toml++) -> validated values -> Model. Every error names file:line and the key.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "rootsim/contact.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/units.hpp"
#include "rootsim/scene.hpp"
#include "plate_scene.hpp"
#include "scene_schema.hpp"
#include "scene_toml.hpp"
#include "toml_guard.hpp"

namespace rootsim {

using namespace detail;

namespace detail {

std::string describeNode(const toml::node& n) {
  std::ostringstream os;
  if (n.is_string()) os << "the string \"" << printable(n.value_or(std::string())) << "\"";
  else if (n.is_integer()) os << "the integer " << n.value_or<int64_t>(0);
  else if (n.is_floating_point()) os << "the number " << formatNumber(n.value_or(0.0), false);
  else if (n.is_boolean()) os << (n.value_or(false) ? "true" : "false");
  else if (n.is_array()) os << "an array of " << n.as_array()->size();
  else if (n.is_table()) os << "a table";
  else os << "a date/time";
  return os.str();
}

namespace {

// the text of the number a node was parsed from (src: the text toml++ parsed), "" when not found
std::string sourceNumberText(const std::string& src, const toml::source_position& p) {
  std::size_t pos = 0;
  for (std::uint32_t l = 1; l < p.line; ++l) {
    pos = src.find('\n', pos);
    if (pos == std::string::npos) return "";
    ++pos;
  }
  pos += p.column > 0 ? p.column - 1 : 0;  // the text is ASCII (toml_guard.hpp): columns are bytes
  std::size_t e = pos;
  while (e < src.size() && (std::isalnum(static_cast<unsigned char>(src[e])) || std::strchr("+-._", src[e]))) ++e;
  return pos < src.size() ? src.substr(pos, e - pos) : "";
}

// a float written non-zero that a double holds only as 0 or as a subnormal (1e-400 reads as 0, while
// 1e400 is refused as infinite): "" when n is not one, else why ("(got 1e-400, which ...)")
std::string underflowed(const toml::node& n, const std::string& src) {
  if (!n.is_floating_point()) return "";
  const double d = *n.value<double>();
  if (!std::isfinite(d) || std::isnormal(d)) return "";
  const std::string text = sourceNumberText(src, n.source().begin);
  if (d == 0 && text.substr(0, text.find_first_of("eE")).find_first_of("123456789") == std::string::npos) return "";
  return "(got " + (text.empty() ? formatNumber(d, false) : printable(text)) + ", which a double holds only as " +
         formatNumber(d, false) + ": non-zero magnitudes below 2.2250738585072014e-308 underflow)";
}

}  // namespace

// converts a TOML node to a value of the key's type, or returns the reason it cannot; src is the text
// toml++ parsed n from (for the digits of a number that underflowed)
std::string convert(const KeySpec& k, const toml::node& n, Value& out, const std::string& src) {
  out = defaultValue(k);
  auto wrongType = [&] { return "must be " + std::string(typeName(k.type)) + " (got " + describeNode(n) + ")"; };
  const std::string range = rangeText(k);
  switch (k.type) {
    case KeyType::Real:
      if (n.is_floating_point()) out.num = *n.value<double>();
      else if (n.is_integer()) out.num = static_cast<double>(*n.value<int64_t>());
      else return wrongType();
      if (const std::string u = underflowed(n, src); !u.empty()) return "must be " + range + " " + u;
      return "";
    case KeyType::Integer: {
      if (!n.is_integer()) return wrongType();
      const std::int64_t i = *n.value<int64_t>();
      out.num = static_cast<double>(i);
      // values are doubles: an integer beyond 2^53 that one would round (9007199254740993 to ...992) is
      // refused with the key's range rather than silently changed (2^63 itself is beyond every key)
      if (out.num >= 9223372036854775808.0 || static_cast<std::int64_t>(out.num) != i)
        return "must be " + (range.empty() ? std::string("an integer of magnitude at most 2^53") : range) +
               " (got " + std::to_string(i) + ", more than a double holds exactly)";
      return "";
    }
    case KeyType::Boolean:
      if (!n.is_boolean()) return wrongType();
      out.b = *n.value<bool>();
      return "";
    case KeyType::String:
      if (!n.is_string()) return wrongType();
      out.str = *n.value<std::string>();
      return "";
    case KeyType::Vector3:
    case KeyType::Vector2: {
      const size_t size = k.type == KeyType::Vector3 ? 3 : 2;
      const toml::array* a = n.as_array();
      if (!a || a->size() != size) return wrongType();
      for (size_t i = 0; i < size; ++i) {
        const toml::node& e = *a->get(i);
        const std::string element = "element " + std::to_string(i + 1) + " of " + std::to_string(size);
        if (e.is_floating_point()) out.vec[i] = *e.value<double>();
        else if (e.is_integer()) out.vec[i] = static_cast<double>(*e.value<int64_t>());
        else return "must be " + std::string(typeName(k.type)) + ": " + element + " must be a number (got " + describeNode(e) + ")";
        if (const std::string u = underflowed(e, src); !u.empty())
          return "must be " + std::string(typeName(k.type)) + ": " + element + " " + u;
      }
      return "";
    }
  }
  return "";
}

Value readValue(const KeySpec& k, const toml::node& n, const std::string& loc, const std::string& shown,
                const std::string& src) {
  Value v;
  std::string why = convert(k, n, v, src);
  if (why.empty()) why = checkValue(k, v);
  if (!why.empty()) throw SceneError(loc + ": " + shown + " " + why);
  v.origin = loc;
  return v;
}

const KeySpec* findKey(const std::string& section, const std::string& key) {
  for (const auto& k : schema())
    if (k.section == section && k.key == key) return &k;
  return nullptr;
}

std::string where(const std::string& source, const toml::source_region& r) {
  return printable(source) + ":" + std::to_string(r.begin.line);
}

}  // namespace detail

namespace {

// " (did you mean ...?)" for a near miss, "" otherwise
std::string suggestKey(const std::string& section, const std::string& key) {
  std::string best;
  int bestD = 1 << 30;
  for (const auto& k : schema()) {
    // same section: compare keys; other sections: an exact key name elsewhere is a strong hint
    const int d = k.section == section ? editDistance(key, k.key) : (k.key == key ? 0 : 1 << 20);
    if (d < bestD) { bestD = d; best = k.full(); }
  }
  if (bestD <= std::max<int>(2, static_cast<int>(key.size()) / 3)) return " (did you mean " + best + "?)";
  return "";
}

// " (did you mean laterals.KEY?)" for a near miss among a plate section's keys, else the section's keys
std::string suggestPlateKey(const std::string& section, const std::string& key) {
  std::vector<std::string> keys;
  for (const KeySpec& k : plateSchema())
    if (k.section == section) keys.push_back(k.key);
  if (section == "population") keys.push_back("spread");
  const std::string near = closestName(key, keys);
  if (!near.empty()) return " (did you mean " + section + "." + near + "?)";
  std::string all;
  for (const std::string& k : keys) all += (all.empty() ? "" : ", ") + k;
  return " (" + section + " keys: " + all + ")";
}

std::string suggestSection(const std::string& section) {
  std::string best;
  int bestD = 1 << 30;
  std::vector<std::string> all = sections();
  for (const char* s : {"plate", "population", "laterals", "seedling", "obstacle"}) all.push_back(s);
  for (const auto& s : all) {
    const int d = editDistance(section, s);
    if (d < bestD) { bestD = d; best = s; }
  }
  if (bestD <= std::max<int>(2, static_cast<int>(section.size()) / 3)) return " (did you mean [" + best + "]?)";
  return "";
}

// a plate, checked when it is read: the roots it can grow (seedlings and their laterals, up to
// laterals.max_order) against caps::kPlateRoots, and a lateral's own scene as render and export will read
// it from roots/NAME/scene.toml (one scene check wherever a scene is read: the run refuses at its start
// what a later reader would refuse). loc names the [laterals] table.
void checkPlateRoots(const Scene& sc, const std::string& loc) {
  const PlateSpec& p = sc.plate;
  double roots = 0;
  bool any = false;
  for (const Seedling& sd : p.seedlings) {
    const Model& m = sd.model;
    const LateralParams& lp = lateralsOf(sd, p.params);
    any |= lp.enabled;
    double perSeedling = 1;
    if (lp.enabled && m.growth.enabled) {
      // the longest a root can grow (growth in its zone only, as the schema's element cap reckons it)
      const double t = m.growth.steps * m.growth.stepTime;
      const double parentLength = m.initial.length + t * m.growth.rate * m.growth.zoneLength;
      const double lateralLength = lp.initialLength + t * lp.rate * lp.zoneLength;
      // the sites along a root of length L: from laterals.first_mm every spacing_mm, up to L - apical_unbranched_mm
      auto sites = [&](double L) {
        const double room = L - lp.first - lp.apicalUnbranched;
        return room < 0 ? 0.0 : std::floor(room / lp.spacing) + 1;
      };
      double under = 1;  // a lateral and the roots it can carry, from the deepest order up
      for (int order = lp.maxOrder; order >= 2; --order) under = 1 + sites(lateralLength) * under;
      perSeedling = 1 + sites(parentLength) * under;
    }
    roots += perSeedling;
  }
  const LateralParams& lp = p.params.laterals;
  checkCount(loc + ": a plate of " + std::to_string(p.seedlings.size()) + " seedling(s) with laterals every " +
                 formatNumber(lp.spacing / units::mm, false) + " mm (laterals.spacing_mm) up to order " +
                 std::to_string(lp.maxOrder) + " (laterals.max_order)",
             roots, caps::kPlateRoots, "roots",
             "caps::kPlateRoots: every root is relaxed at every growth step; docs/outputs.md, Caps");
  if (!any) return;
  for (const Seedling& sd : p.seedlings) {
    if (!lateralsOf(sd, p.params).enabled) continue;
    Seedling lat = sd;
    lat.name = sd.name + ".1";
    lat.model = lateralModel(sd.model, lateralsOf(sd, p.params));
    const std::string file = "roots/" + lat.name + "/scene.toml";
    try {
      (void)parseScene(p.headToml + plateTableToml(p.params) + seedlingToml(lat, p.base), file);
    } catch (const SceneError& e) {
      throw SceneError(loc + ": [laterals] gives " + sd.name + "'s laterals a scene that render and export would refuse (" +
                       e.what() + "); change the [laterals] keys or the plate's");
    }
  }
}

// [[obstacle]] tables (docs/model.md, Contact and friction): one per obstacle, checked key by key like the
// sections; the first table is obstacle[1] in messages
struct ParsedObstacle {
  Obstacle o;
  std::string origin;     // file:line of the table's shape key (or its first key)
  std::string where;      // "obstacle[k]"
  std::string placeKey;   // the key that positions it (center_mm or from_mm), for overlap errors
  std::string placeOrigin;
};

std::vector<ParsedObstacle> parseObstacles(const std::string& sourceName, const toml::key& akey,
                                           const toml::node& anode) {
  std::vector<ParsedObstacle> out;
  const toml::array* arr = anode.as_array();
  if (!arr || !arr->is_array_of_tables())
    throw SceneError(where(sourceName, akey.source()) + ": obstacle must be an array of tables ([[obstacle]]), got " +
                     describeNode(anode));
  static const std::vector<std::string> keys = {"shape", "center_mm", "radius_mm", "from_mm", "to_mm", "thickness_mm"};
  int index = 0;
  for (const toml::node& tn : *arr) {
    ++index;
    const toml::table& t = *tn.as_table();
    ParsedObstacle po;
    po.where = "obstacle[" + std::to_string(index) + "]";
    const std::string tableLoc = sourceName + ":" + std::to_string(t.source().begin.line);
    auto fail = [&](const std::string& loc, const std::string& key, const std::string& why) {
      throw SceneError(loc + ": " + po.where + "." + key + " " + why);
    };
    // which keys are present, where
    std::map<std::string, const toml::node*> got;
    std::map<std::string, std::string> loc;
    for (auto&& [k, n] : t) {
      const std::string key(k.str());
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
        std::string best;
        int bestD = 1 << 30;
        for (const auto& c : keys)
          if (editDistance(key, c) < bestD) { bestD = editDistance(key, c); best = c; }
        throw SceneError(where(sourceName, k.source()) + ": unknown key " + po.where + "." + printable(key) +
                         (bestD <= 2 ? " (did you mean " + best + "?)" : " (obstacle keys: shape, center_mm, "
                                                                          "radius_mm, from_mm, to_mm, thickness_mm)"));
      }
      got[key] = &n;
      loc[key] = where(sourceName, k.source());
    }
    if (!got.count("shape")) throw SceneError(tableLoc + ": " + po.where + ".shape is missing (\"peg\" or \"wall\")");
    const toml::node& shapeNode = *got["shape"];
    const std::string shape = shapeNode.is_string() ? *shapeNode.value<std::string>() : std::string();
    if (shape != "peg" && shape != "wall")
      fail(loc["shape"], "shape", "must be one of \"peg\", \"wall\" (got " + (shapeNode.is_string() ? "\"" + printable(shape) + "\"" : describeNode(shapeNode)) + ")");
    po.origin = loc["shape"];
    const bool peg = shape == "peg";
    const std::vector<std::string> need = peg ? std::vector<std::string>{"center_mm", "radius_mm"}
                                              : std::vector<std::string>{"from_mm", "to_mm", "thickness_mm"};
    for (const auto& [key, n] : got) {
      if (key == "shape") continue;
      if (std::find(need.begin(), need.end(), key) == need.end())
        fail(loc[key], key, std::string("does not apply to a ") + shape + " (a " + shape + " takes " + need[0] +
                                ", " + need[1] + (peg ? "" : ", " + need[2]) + ")");
    }
    for (const auto& key : need)
      if (!got.count(key)) throw SceneError(po.origin + ": " + po.where + "." + key + " is missing (a " + shape + " needs it)");
    auto number = [&](const std::string& key, const toml::node& n) -> double {
      double x = 0;
      if (n.is_floating_point()) x = *n.value<double>();
      else if (n.is_integer()) x = static_cast<double>(*n.value<int64_t>());
      else fail(loc[key], key, "must be a number (got " + describeNode(n) + ")");
      if (!std::isfinite(x)) fail(loc[key], key, "must be finite (got " + formatNumber(x, false) + ")");
      return x;
    };
    auto point = [&](const std::string& key) -> Eigen::Vector2d {
      const toml::node& n = *got[key];
      const toml::array* a = n.as_array();
      if (!a || a->size() != 2) fail(loc[key], key, "must be an array of 2 numbers [lateral, downhill] (got " + describeNode(n) + ")");
      return Eigen::Vector2d(number(key, *a->get(0)), number(key, *a->get(1))) * units::mm;
    };
    auto positive = [&](const std::string& key) -> double {
      const double x = number(key, *got[key]);
      if (!(x > 0)) fail(loc[key], key, "must be > 0 (got " + formatNumber(x, false) + ")");
      return x * units::mm;
    };
    if (peg) {
      po.o.shape = Obstacle::Shape::Peg;
      po.o.from = po.o.to = point("center_mm");
      po.o.radius = positive("radius_mm");
      po.placeKey = "center_mm";
    } else {
      po.o.shape = Obstacle::Shape::Wall;
      po.o.from = point("from_mm");
      po.o.to = point("to_mm");
      po.o.radius = 0.5 * positive("thickness_mm");
      if (po.o.from == po.o.to) fail(loc["to_mm"], "to_mm", "must differ from from_mm (a wall of no length: use a peg)");
      po.placeKey = "from_mm";
    }
    po.placeOrigin = loc[po.placeKey];
    out.push_back(po);
  }
  return out;
}

// an obstacle must not overlap the initial root: the segment from the base's foot down the plate, of
// length L0 and radius R (plate coordinates, the seeded perturbation of 1e-6 R aside)
void checkObstacleClearance(const Model& m, const std::vector<ParsedObstacle>& obs) {
  const PlateFrame f = m.env.plane.frame();
  const Vec3 r0 = Vec3::Zero(), r1 = m.initial.length * f.downhill;
  for (const ParsedObstacle& po : obs) {
    const Vec3 b0 = po.o.from.x() * f.lateral + po.o.from.y() * f.downhill;
    const Vec3 b1 = po.o.to.x() * f.lateral + po.o.to.y() * f.downhill;
    double sa = 0, sb = 0;
    closestSegmentPoints(r0, r1, b0, b1, sa, sb);
    const double dist = ((r0 + sa * (r1 - r0)) - (b0 + sb * (b1 - b0))).norm();
    const double clear = dist - m.rod.radius - po.o.radius;
    if (clear < 0.0)
      throw SceneError(po.placeOrigin + ": " + po.where + "." + po.placeKey + " overlaps the initial root by " +
                       formatNumber(-clear / units::mm, false) + " mm (the root lies along [0, 0] to [0, " +
                       formatNumber(m.initial.length / units::mm, false) + "] mm with radius " +
                       formatNumber(m.rod.radius / units::mm, false) + " mm)");
  }
}

// an [[obstacle]] table's keys and their values in TOML syntax, in the order they are written
std::vector<std::pair<std::string, std::string>> obstacleKeys(const Obstacle& o) {
  auto pt = [](const Eigen::Vector2d& p) {
    return "[" + formatNumber(p.x() / units::mm, false) + ", " + formatNumber(p.y() / units::mm, false) + "]";
  };
  if (o.shape == Obstacle::Shape::Peg)
    return {{"shape", "\"peg\""}, {"center_mm", pt(o.from)}, {"radius_mm", formatNumber(o.radius / units::mm, false)}};
  return {{"shape", "\"wall\""},
          {"from_mm", pt(o.from)},
          {"to_mm", pt(o.to)},
          {"thickness_mm", formatNumber(2.0 * o.radius / units::mm, false)}};
}

std::string obstaclesToml(const std::vector<Obstacle>& obs) {
  std::ostringstream os;
  for (const Obstacle& o : obs) {
    os << "\n[[obstacle]]\n";
    for (const auto& [key, text] : obstacleKeys(o)) os << key << " = " << text << "\n";
  }
  return os.str();
}

void applyOverride(const std::string& ovRaw, Values& values) {
  const std::string ov = printable(ovRaw);
  // one key, one value: a newline would smuggle a second assignment past the parser (and past this check)
  if (ov != ovRaw) throw SceneError("--set " + ov + ": control characters (newline, tab, ...) are not allowed");
  const auto eq = ov.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set " + ov + ": expected section.key=value");
  const std::string full = ov.substr(0, eq), text = ov.substr(eq + 1);
  const auto dot = full.find('.');
  if (dot == std::string::npos)
    throw SceneError("--set " + ov + ": expected section.key=value (no section in \"" + full + "\")");
  const std::string section = full.substr(0, dot), key = full.substr(dot + 1);
  const KeySpec* k = findKey(section, key);
  if (!k) {
    bool sectionKnown = false;
    for (const auto& s : sections()) sectionKnown |= s == section;
    throw SceneError("--set " + ov + ": unknown key " + full +
                     (sectionKnown ? suggestKey(section, key) : suggestSection(section)));
  }
  if (!nonAsciiOutsideComments(text).empty())
    throw SceneError("--set " + ov + ": non-ASCII characters are not allowed (scene values are ASCII)");
  // the value is parsed as the TOML line "v = <value>": bounded like a file's text (toml_guard.hpp)
  if (const std::string bad = nestingBeyondLimits("v = " + text); !bad.empty())
    throw SceneError("--set " + ov + ":" + bad.substr(bad.find(':') + 1));
  Value v;
  std::string why;
  try {
    const std::string line = "v = " + text;
    const toml::table t = toml::parse(line);
    if (t.size() != 1 || !t.get("v"))
      throw SceneError("--set " + ov + ": expected one value after '=' (got \"" + text + "\")");
    why = convert(*k, *t.get("v"), v, line);
  } catch (const toml::parse_error&) {
    // a bare word is a string ("--set tropism.sensing=apical")
    if (k->type != KeyType::String)
      throw SceneError("--set " + ov + ": " + full + " must be " + typeName(k->type) + " (got \"" + text + "\")");
    v = defaultValue(*k);
    v.str = text;
  }
  if (why.empty()) why = checkValue(*k, v);
  if (!why.empty()) throw SceneError("--set " + ov + ": " + full + " " + why);
  v.origin = "--set " + full;
  values[full] = v;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides) {
  // non-ASCII text, nesting and key lengths are screened before toml++ sees the text (toml_guard.hpp)
  if (const std::string bad = screenToml(text); !bad.empty())
    throw SceneError(printable(sourceName) + ":" + bad);
  toml::table root;
  try {
    root = toml::parse(text, sourceName);
  } catch (const toml::parse_error& e) {
    throw SceneError(printable(sourceName) + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                     printable(std::string(e.description())));
  }
  // the model's keys and the plate's ([plate], [population], [laterals]), defaults filled in
  Values values, plateValues;
  for (const auto& k : schema()) values[k.full()] = defaultValue(k);
  for (const auto& k : plateSchema())
    if (isPlateSection(k.section)) plateValues[k.full()] = defaultValue(k);
  std::vector<ParsedObstacle> obstacles;
  for (auto&& [skey, snode] : root) {
    const std::string section(skey.str());
    if (section == "obstacle") {
      obstacles = parseObstacles(sourceName, skey, snode);
      continue;
    }
    if (section == "seedling") continue;  // readPlate, once the plate-wide values are known
    bool known = isPlateSection(section);
    for (const auto& s : sections()) known |= s == section;
    if (!known) {
      // a top-level key that belongs to a section ("beta = 0.2" without [tropism])
      throw SceneError(where(sourceName, skey.source()) + ": unknown section [" + printable(section) + "]" +
                       (snode.is_table() ? suggestSection(section) : suggestKey("", section)));
    }
    const toml::table* t = snode.as_table();
    if (!t)
      throw SceneError(where(sourceName, skey.source()) + ": " + printable(section) + " must be a table ([" + printable(section) +
                       "]), got " + describeNode(snode));
    const bool plate = isPlateSection(section);
    for (auto&& [kkey, knode] : *t) {
      const std::string key(kkey.str());
      if (section == "population" && key == "spread") continue;  // readPlate: a table of other keys
      const KeySpec* k = plate ? findPlateKey(section, key) : findKey(section, key);
      const std::string loc = where(sourceName, kkey.source());
      if (!k) throw SceneError(loc + ": unknown key " + printable(section) + "." + printable(key) +
                               (plate ? suggestPlateKey(section, key) : suggestKey(section, key)));
      (plate ? plateValues : values)[k->full()] = readValue(*k, knode, loc, k->full(), text);
    }
  }
  for (const auto& ov : overrides) applyOverride(ov, values);
  std::string name = std::filesystem::path(sourceName).stem().string();
  Scene sc;
  SceneParams params = buildParams(values, name);
  sc.model = std::move(params.model);
  sc.output = params.output;
  std::vector<Obstacle> obs;
  for (const ParsedObstacle& po : obstacles) obs.push_back(po.o);
  PlateTables plate = readPlate(root, sourceName, text, values, plateValues, name, obs);
  // a plate's obstacles are in plate coordinates, each seedling checks them against its own root
  if (plate.spec.seedlings.empty()) checkObstacleClearance(sc.model, obstacles);
  sc.model.env.obstacles = obs;
  sc.path = sourceName;
  const std::string head = resolvedToml(values, name) + obstaclesToml(obs);
  sc.resolvedToml = head + plate.toml;
  for (const std::string& t : plate.rootToml) sc.rootToml.push_back(head + t);
  sc.plate = std::move(plate.spec);
  sc.plate.headToml = head;
  if (sc.plate.seedlings.size() == 1) sc.model = sc.plate.seedlings.front().model;
  if (!sc.plate.seedlings.empty()) {
    const toml::node* lat = root.get("laterals");
    checkPlateRoots(sc, lat ? where(sourceName, lat->source()) : sourceName);
  }
  return sc;
}

const Model& singleRootModel(const Scene& sc, const std::string& what) {
  if (sc.plate.seedlings.size() > 1)
    throw SceneError(what + " is a plate of " + std::to_string(sc.plate.seedlings.size()) +
                     " roots; this command takes one root: pass its folder roots/NAME (docs/plate.md)");
  return sc.model;
}

std::string sceneKeyType(const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) return "";
  const KeySpec* k = findKey(key.substr(0, dot), key.substr(dot + 1));
  return k ? typeName(k->type) : "";
}

std::string closestName(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  int bestD = 1 << 30;
  for (const std::string& n : names)
    if (const int d = editDistance(word, n); d < bestD) bestD = d, best = n;
  return bestD <= std::max<int>(2, static_cast<int>(word.size()) / 3) ? best : std::string();
}

std::string sceneNumberProblem(const std::string& key, double value) {
  const auto dot = key.find('.');
  const KeySpec* k = dot == std::string::npos ? nullptr : findKey(key.substr(0, dot), key.substr(dot + 1));
  if (!k || (k->type != KeyType::Real && k->type != KeyType::Integer)) return "is not a number key of a scene";
  Value v;
  v.type = k->type;
  v.num = value;
  if (k->type == KeyType::Integer && std::isfinite(value) && value != std::floor(value)) return "must be an integer";
  return checkValue(*k, v);
}

Scene sceneOf(const Model& model, const OutputParams& output) {
  const std::string origin = "model " + printable(model.name);
  const Values values = valuesOf(SceneParams{model, output}, origin);
  for (const KeySpec& k : schema())
    if (const std::string why = checkValue(k, values.at(k.full())); !why.empty())
      throw SceneError(origin + ": " + k.full() + " " + why);
  Scene sc;
  SceneParams params = buildParams(values, model.name);
  sc.model = std::move(params.model);
  sc.output = params.output;
  std::vector<ParsedObstacle> obstacles;
  for (const Obstacle& o : model.env.obstacles) {
    ParsedObstacle po;
    po.o = o;
    po.where = "obstacle[" + std::to_string(obstacles.size() + 1) + "]";
    po.origin = po.placeOrigin = origin;
    po.placeKey = o.shape == Obstacle::Shape::Peg ? "center_mm" : "from_mm";
    obstacles.push_back(po);
  }
  checkObstacleClearance(sc.model, obstacles);
  sc.model.env.obstacles = model.env.obstacles;
  sc.resolvedToml = resolvedToml(values, model.name) + obstaclesToml(sc.model.env.obstacles);
  return sc;
}

std::vector<SceneValue> sceneValues(const Model& model, const OutputParams& output) {
  std::vector<SceneValue> out;
  const Values values = valuesOf(SceneParams{model, output}, "model " + printable(model.name));
  for (const auto& sec : sections())
    for (const KeySpec& k : schema())
      if (k.section == sec) out.push_back({k.full(), tomlText(k, values.at(k.full()))});
  for (std::size_t i = 0; i < model.env.obstacles.size(); ++i)
    for (const auto& [key, text] : obstacleKeys(model.env.obstacles[i]))
      out.push_back({"obstacle[" + std::to_string(i + 1) + "]." + key, text});
  return out;
}

std::string readSceneFile(const std::string& path, const std::string& kind) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (!fs::exists(st)) throw SceneError(printable(path) + ": no such " + kind);
  if (fs::is_directory(st)) throw SceneError(printable(path) + ": is a directory, expected a " + kind);
  // a device, FIFO or socket would be read forever or block: only regular files of sane size
  if (!fs::is_regular_file(st)) throw SceneError(printable(path) + ": not a regular file, expected a " + kind);
  constexpr std::uintmax_t kMaxSceneBytes = 1u << 20;
  if (fs::file_size(path, ec) > kMaxSceneBytes)
    throw SceneError(printable(path) + ": larger than 1 MiB; a " + kind + " is a few hundred bytes of TOML");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(printable(path) + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  return parseScene(readSceneFile(path), path, overrides);
}

std::vector<std::string> sceneFileKeys(const std::string& path) {
  const std::string text = readSceneFile(path);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(detail::where(path, e.source()) + ": " + std::string(e.description()));
  }
  std::vector<std::string> keys;
  for (const auto& [section, node] : root)
    if (const toml::table* t = node.as_table())
      for (const auto& [key, value] : *t) keys.push_back(std::string(section.str()) + "." + std::string(key.str()));
  return keys;
}

}  // namespace rootsim
