// summary.json's builder (json.hpp).
#include "rootsim/json.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "rootsim/number_text.hpp"


namespace rootsim {

namespace {
std::string jsonEscape(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') { o += '\\'; o += c; }
    else if (c == '\n') o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); o += b; }
    else o += c;
  }
  return o + "\"";
}
}  // namespace


Json& Json::num(const std::string& key, double v) {
  items_.push_back({key, std::isfinite(v) ? numberText(v) : "null", nullptr, {}, false});
  return *this;
}
Json& Json::integer(const std::string& key, long long v) {
  items_.push_back({key, std::to_string(v), nullptr, {}, false});
  return *this;
}
Json& Json::str(const std::string& key, const std::string& v) {
  items_.push_back({key, jsonEscape(v), nullptr, {}, false});
  return *this;
}
Json& Json::strings(const std::string& key, const std::vector<std::string>& v) {
  std::string raw = "[";
  for (std::size_t i = 0; i < v.size(); ++i) raw += (i ? ", " : "") + jsonEscape(v[i]);
  items_.push_back({key, raw + "]", nullptr, {}, false});
  return *this;
}
Json& Json::boolean(const std::string& key, bool v) {
  items_.push_back({key, v ? "true" : "false", nullptr, {}, false});
  return *this;
}
Json& Json::object(const std::string& key, const Json& v) {
  items_.push_back({key, "", std::make_shared<Json>(v), {}, false});
  return *this;
}
Json& Json::array(const std::string& key, const std::vector<Json>& v) {
  Item it{key, "", nullptr, {}, true};
  it.elems = v;
  it.isArray = true;
  items_.push_back(std::move(it));
  return *this;
}
std::string Json::dump(int indent) const {
  const std::string pad(static_cast<size_t>(indent + 2), ' ');
  std::string o = "{\n";
  for (size_t i = 0; i < items_.size(); ++i) {
    const Item& it = items_[i];
    std::string value = it.child ? it.child->dump(indent + 2) : it.raw;
    if (it.isArray) {
      const std::string inner(static_cast<size_t>(indent + 4), ' ');
      value = it.elems.empty() ? "[]" : "[\n";
      for (size_t k = 0; k < it.elems.size(); ++k)
        value += inner + it.elems[k].dump(indent + 4) + (k + 1 < it.elems.size() ? ",\n" : "\n");
      if (!it.elems.empty()) value += pad + "]";
    }
    o += pad + jsonEscape(it.key) + ": " + value;
    o += i + 1 < items_.size() ? ",\n" : "\n";
  }
  return o + std::string(static_cast<size_t>(indent), ' ') + "}";
}

Json theoryJson(const Theory& t) {
  Json j;
  j.num("effective_gain_beta_Lgz_over_R", t.effectiveGain)
      .num("T0_h", t.T0 / units::hour)
      .num("max_kappa_per_mm_eq8", t.maxKappa * units::mm)
      .num("wavelength_mm_eq9", t.wavelength / units::mm)
      .num("amplitude_mm_eq10", t.amplitude / units::mm)
      .num("alpha_straight_to_waving_deg_eq12", t.alphaStraightToWave / units::deg)
      .num("alpha_waving_to_coiling_deg_eq13", t.alphaWaveToCoil / units::deg)
      .num("omega_per_h_eq5", t.omega * units::hour)
      .num("omega_T0", t.omegaT0)
      .num("skew_deg_eq14_small_omegaT0", t.skewSmall / units::deg)
      .num("skew_deg_eq15_large_omegaT0", t.skewLarge / units::deg);
  return j;
}

}  // namespace rootsim
