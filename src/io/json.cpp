// the JSON files' builder and layout (json.hpp).
#include "rootsim/json.hpp"

#include <cmath>
#include <cstdint>
#include <utility>

#include <nlohmann/json.hpp>

#include "rootsim/number_text.hpp"


namespace rootsim {

namespace {
using OJ = nlohmann::ordered_json;

// a scalar's text: numbers as numberText (what the CSV files write), the rest as nlohmann-json writes it
std::string scalarText(const OJ& v) {
  if (v.is_number_float()) {
    const double x = v.get<double>();
    return std::isfinite(x) ? numberText(x) : "null";
  }
  return v.dump(-1, ' ', false, OJ::error_handler_t::replace);
}

void write(const OJ& v, int indent, std::string& o) {
  const bool pretty = indent >= 0;
  const std::string pad = pretty ? std::string(static_cast<size_t>(indent) + 2, ' ') : std::string();
  const char* next = pretty ? ",\n" : ",";
  if (v.is_object()) {
    o += pretty ? "{\n" : "{";
    size_t i = 0;
    for (const auto& [key, member] : v.items()) {
      o += pad + scalarText(OJ(key)) + (pretty ? ": " : ":");
      write(member, pretty ? indent + 2 : indent, o);
      o += ++i < v.size() ? next : (pretty ? "\n" : "");
    }
    o += (pretty ? std::string(static_cast<size_t>(indent), ' ') : std::string()) + "}";
  } else if (v.is_array()) {
    if (v.empty()) { o += "[]"; return; }
    o += pretty ? "[\n" : "[";
    for (size_t i = 0; i < v.size(); ++i) {
      o += pad;
      write(v[i], pretty ? indent + 2 : indent, o);
      o += i + 1 < v.size() ? next : (pretty ? "\n" : "");
    }
    o += (pretty ? std::string(static_cast<size_t>(indent), ' ') : std::string()) + "]";
  } else {
    o += scalarText(v);
  }
}
}  // namespace

std::string jsonText(const OJ& v, int indent) {
  std::string o;
  write(v, indent, o);
  return o;
}

Json::Json() : doc_(std::make_unique<OJ>(OJ::object())) {}
Json::Json(const Json& other) : doc_(std::make_unique<OJ>(*other.doc_)) {}
Json::Json(Json&& other) noexcept : doc_(std::make_unique<OJ>(OJ::object())) { doc_.swap(other.doc_); }
Json& Json::operator=(const Json& other) {
  if (this != &other) *doc_ = *other.doc_;
  return *this;
}
Json& Json::operator=(Json&& other) noexcept {
  doc_.swap(other.doc_);
  return *this;
}
Json::~Json() = default;

Json& Json::num(const std::string& key, double v) {
  (*doc_)[key] = std::isfinite(v) ? OJ(v) : OJ(nullptr);
  return *this;
}
Json& Json::integer(const std::string& key, long long v) {
  (*doc_)[key] = static_cast<std::int64_t>(v);
  return *this;
}
Json& Json::str(const std::string& key, const std::string& v) {
  (*doc_)[key] = v;
  return *this;
}
Json& Json::strings(const std::string& key, const std::vector<std::string>& v) {
  OJ a = OJ::array();
  for (const std::string& s : v) a.push_back(s);
  (*doc_)[key] = std::move(a);
  return *this;
}
Json& Json::boolean(const std::string& key, bool v) {
  (*doc_)[key] = v;
  return *this;
}
Json& Json::object(const std::string& key, const Json& v) {
  (*doc_)[key] = *v.doc_;
  return *this;
}
Json& Json::array(const std::string& key, const std::vector<Json>& v) {
  OJ a = OJ::array();
  for (const Json& e : v) a.push_back(*e.doc_);
  (*doc_)[key] = std::move(a);
  return *this;
}
std::string Json::dump(int indent) const { return jsonText(*doc_, indent < 0 ? 0 : indent); }

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
