#pragma once
// internal: the table of every scene key, and the values a scene resolves to
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rootsim/model.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/output_params.hpp"

namespace rootsim::detail {

enum class KeyType { Real, Integer, Boolean, String, Vector3, Vector2 };
const char* typeName(KeyType t);

struct Value {
  KeyType type = KeyType::Real;
  double num = 0;
  bool b = false;
  std::string str;
  std::array<double, 3> vec{0, 0, 0};  // Vector2: the first two
  std::string origin;  // "file:line" or "--set" or "default"
};

// what a scene's keys set: the physics' model, and what the run writes ([output])
struct SceneParams {
  Model model;
  OutputParams output;
};

struct KeySpec {
  std::string section, key;
  KeyType type = KeyType::Real;
  double defNum = 0;                     // Real / Integer default
  bool defBool = false;
  std::string defStr;
  std::array<double, 3> defVec{0, 0, 0};
  double lo = -1e300, hi = 1e300;        // allowed range (numbers)
  bool loOpen = false, hiOpen = false;   // exclusive bounds
  std::vector<std::string> choices;      // allowed strings
  std::string doc;                       // meaning and unit
  // the key's field of the model or the output, both ways (the one place that knows key <-> field and
  // the unit): set writes a checked value into it; get reads the field back as the value that set turns
  // into the same field, bitwise (scene_schema.cpp, fromSi), so params -> values -> params is exact
  std::function<void(SceneParams&, const Value&)> set;
  std::function<Value(const SceneParams&)> get;
  // a plate key's field ([plate] and [population]: the plate's parameters; [laterals]: a root's lateral
  // parameters; [[seedling]]: the seedling), both ways like set and get; one of the pairs is set
  std::function<void(PlateParams&, const Value&)> setPlate;
  std::function<Value(const PlateParams&)> getPlate;
  std::function<void(LateralParams&, const Value&)> setLaterals;
  std::function<Value(const LateralParams&)> getLaterals;
  std::function<void(Seedling&, const Value&)> setSeedling;
  std::function<Value(const Seedling&)> getSeedling;
  // a rule of the key's own beyond its type and range (a name that is a folder): "" or why
  std::function<std::string(const Value&)> rule;
  // the key of its section whose value it takes when a scene leaves it out ("set_point_deg": a final
  // set-point angle that is not given is the initial one, no drift); "" for a fixed default
  std::string defaultFollows;
  std::string full() const { return section + "." + key; }
};

// the keys of a root's model, by section (sections())
const std::vector<KeySpec>& schema();
const std::vector<std::string>& sections();
// the plate's keys (docs/plate.md, Scenes): [plate], [population], [[seedling]] and [laterals], read and
// checked as the model's are (scene.cpp readValue); a [laterals] key is also a seedling's own
// ([seedling.set]) and varies in [population.spread]
const std::vector<KeySpec>& plateSchema();
const KeySpec* findPlateKey(const std::string& section, const std::string& key);

using Values = std::map<std::string, Value>;  // by "section.key"

Value defaultValue(const KeySpec& k);
// every plate key left at its default (origin "default") whose default follows another key
// (KeySpec::defaultFollows) takes that key's value, origin kept: a scene's values once its tables, sets
// and draws are read (again after each, so a key set later is followed)
void resolveFollowingDefaults(Values& v);
// checks range / choices; returns "" or the reason ("must be > 0 (got -1)")
std::string checkValue(const KeySpec& k, const Value& v);
// the accepted range of a number key as text: "in (0, 100]", ">= 0"; "" when unbounded
std::string rangeText(const KeySpec& k);
// builds the model and the output and checks relations between keys; throws SceneError with the origin
// of a key
SceneParams buildParams(const Values& v, const std::string& name);
// its model alone
Model buildModel(const Values& v, const std::string& name);
// every key's value read from a model and an output (each with the given origin, for error messages)
Values valuesOf(const SceneParams& p, const std::string& origin);
// a value in TOML syntax
std::string tomlText(const KeySpec& k, const Value& v);
std::string resolvedToml(const Values& v, const std::string& name);
std::string formatNumber(double x, bool integer);
// Levenshtein distance, for "did you mean"
int editDistance(const std::string& a, const std::string& b);

}  // namespace rootsim::detail
