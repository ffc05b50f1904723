// Scene files: TOML (toml++) -> validated values -> Model. Every error names file:line and the key.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "rootsim/scene.hpp"
#include "scene_schema.hpp"
#include "toml_guard.hpp"

namespace rootsim {

using namespace detail;

namespace {

const KeySpec* findKey(const std::string& section, const std::string& key) {
  for (const auto& k : schema())
    if (k.section == section && k.key == key) return &k;
  return nullptr;
}

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

std::string suggestSection(const std::string& section) {
  std::string best;
  int bestD = 1 << 30;
  for (const auto& s : sections()) {
    const int d = editDistance(section, s);
    if (d < bestD) { bestD = d; best = s; }
  }
  if (bestD <= std::max<int>(2, static_cast<int>(section.size()) / 3)) return " (did you mean [" + best + "]?)";
  return "";
}

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

// converts a TOML node to a value of the key's type, or returns the reason it cannot
std::string convert(const KeySpec& k, const toml::node& n, Value& out) {
  out = defaultValue(k);
  auto wrongType = [&] { return "must be " + std::string(typeName(k.type)) + " (got " + describeNode(n) + ")"; };
  switch (k.type) {
    case KeyType::Real:
      if (n.is_floating_point()) out.num = *n.value<double>();
      else if (n.is_integer()) out.num = static_cast<double>(*n.value<int64_t>());
      else return wrongType();
      return "";
    case KeyType::Integer:
      if (!n.is_integer()) return wrongType();
      out.num = static_cast<double>(*n.value<int64_t>());
      return "";
    case KeyType::Boolean:
      if (!n.is_boolean()) return wrongType();
      out.b = *n.value<bool>();
      return "";
    case KeyType::String:
      if (!n.is_string()) return wrongType();
      out.str = *n.value<std::string>();
      return "";
    case KeyType::Vector3: {
      const toml::array* a = n.as_array();
      if (!a || a->size() != 3) return wrongType();
      for (size_t i = 0; i < 3; ++i) {
        const toml::node& e = *a->get(i);
        if (e.is_floating_point()) out.vec[i] = *e.value<double>();
        else if (e.is_integer()) out.vec[i] = static_cast<double>(*e.value<int64_t>());
        else return wrongType();
      }
      return "";
    }
  }
  return "";
}

std::string where(const std::string& source, const toml::source_region& r) {
  return printable(source) + ":" + std::to_string(r.begin.line);
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
  Value v;
  std::string why;
  try {
    const toml::table t = toml::parse("v = " + text);
    if (t.size() != 1 || !t.get("v"))
      throw SceneError("--set " + ov + ": expected one value after '=' (got \"" + text + "\")");
    why = convert(*k, *t.get("v"), v);
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
  if (const std::string bad = nonAsciiOutsideComments(text); !bad.empty())
    throw SceneError(printable(sourceName) + ":" + bad);
  toml::table root;
  try {
    root = toml::parse(text, sourceName);
  } catch (const toml::parse_error& e) {
    throw SceneError(printable(sourceName) + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                     printable(std::string(e.description())));
  }
  Values values;
  for (const auto& k : schema()) values[k.full()] = defaultValue(k);
  for (auto&& [skey, snode] : root) {
    const std::string section(skey.str());
    bool known = false;
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
    for (auto&& [kkey, knode] : *t) {
      const std::string key(kkey.str());
      const KeySpec* k = findKey(section, key);
      const std::string loc = where(sourceName, kkey.source());
      if (!k) throw SceneError(loc + ": unknown key " + printable(section) + "." + printable(key) + suggestKey(section, key));
      Value v;
      std::string why = convert(*k, knode, v);
      if (why.empty()) why = checkValue(*k, v);
      if (!why.empty()) throw SceneError(loc + ": " + k->full() + " " + why);
      v.origin = loc;
      values[k->full()] = v;
    }
  }
  for (const auto& ov : overrides) applyOverride(ov, values);
  std::string name = std::filesystem::path(sourceName).stem().string();
  Scene sc;
  sc.model = buildModel(values, name);
  sc.path = sourceName;
  sc.resolvedToml = resolvedToml(values, name);
  return sc;
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

}  // namespace rootsim
