#pragma once
// summary.json (docs/outputs.md): a minimal JSON object builder, and the theory block.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <memory>

#include "rootsim/theory.hpp"

namespace rootsim {

// minimal JSON object builder (numbers: NaN and infinities become null)
class Json {
 public:
  Json& num(const std::string& key, double v);
  Json& integer(const std::string& key, long long v);
  Json& str(const std::string& key, const std::string& v);
  Json& strings(const std::string& key, const std::vector<std::string>& v);  // an array of strings
  Json& boolean(const std::string& key, bool v);
  Json& object(const std::string& key, const Json& v);
  Json& array(const std::string& key, const std::vector<Json>& v);   // an array of objects
  std::string dump(int indent = 0) const;

 private:
  struct Item {
    std::string key, raw;           // raw JSON text of a scalar value
    std::shared_ptr<Json> child;    // or a nested object
    std::vector<Json> elems;        // or an array of objects (isArray)
    bool isArray = false;
  };
  std::vector<Item> items_;
};

// the theory block of summary.json and `rootsim check`
Json theoryJson(const Theory& t);

}  // namespace rootsim
