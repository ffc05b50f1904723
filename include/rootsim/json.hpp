#pragma once
// the JSON files rootsim writes (summary.json, analysis.json, compare.json, fit.json, a GLB's JSON chunk;
// docs/outputs.md): nlohmann-json holds the document and escapes its strings; jsonText lays it out with
// rootsim's numbers (numberText, the shortest round-trip text), which nlohmann's dump does not write
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "rootsim/theory.hpp"

namespace rootsim {

// a JSON object built key by key, in insertion order (numbers: NaN and infinities become null; a key given
// twice keeps its first place and its last value)
class Json {
 public:
  Json();
  Json(const Json& other);
  Json(Json&& other) noexcept;
  Json& operator=(const Json& other);
  Json& operator=(Json&& other) noexcept;
  ~Json();

  Json& num(const std::string& key, double v);
  Json& integer(const std::string& key, long long v);
  Json& str(const std::string& key, const std::string& v);
  Json& strings(const std::string& key, const std::vector<std::string>& v);  // an array of strings
  Json& boolean(const std::string& key, bool v);
  Json& object(const std::string& key, const Json& v);
  Json& array(const std::string& key, const std::vector<Json>& v);   // an array of objects
  // the text: members one a line, indented by two spaces per level, the whole indented by `indent`
  std::string dump(int indent = 0) const;
  const nlohmann::ordered_json& value() const { return *doc_; }

 private:
  std::unique_ptr<nlohmann::ordered_json> doc_;
};

// the text of a JSON value: indent >= 0, one member or element a line (2 more spaces a level, the
// closing bracket at `indent`); indent < 0, compact (no spaces). Floating-point numbers as numberText
// (non-finite ones as null), strings escaped by nlohmann-json (invalid UTF-8 replaced by U+FFFD)
std::string jsonText(const nlohmann::ordered_json& v, int indent = 0);

// the theory block of summary.json and `rootsim check`
Json theoryJson(const Theory& t);

}  // namespace rootsim
