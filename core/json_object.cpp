#include "core/json_object.hpp"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal {

// A value as messages show it: its JSON text, shortened (a value may be a 10 MB string or array).
static std::string shown(const nlohmann::json& v) { return shorten(v.dump()); }

JsonObject::JsonObject(const nlohmann::json& j, std::string where, std::string path)
    : j_(j), where_(std::move(where)), path_(std::move(path)) {
  if (!j_.is_object())
    throw InputError(
        fmt::format("{}: {} must be a JSON object, got {}", where_, path_.empty() ? "the file" : path_, shown(j_)));
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  // Paths of nested keys run long (axles[0].suspension.upper_arm.chassis_back): shortened only past
  // what any of ours needs, as a user's misspelt key may be a string of any length.
  throw InputError(fmt::format("{}: key '{}': {}", where_, shorten(key_path(key), 120), what));
}

const nlohmann::json& JsonObject::raw(const std::string& key) {
  if (!j_.contains(key)) fail(key, "is required but missing");
  used_.insert(key);
  return j_.at(key);
}

static std::string range_text(double lo, double hi, bool lo_open, bool hi_open) {
  return fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
}

double JsonObject::number(const std::string& key, double lo, double hi, bool lo_open, bool hi_open) {
  const nlohmann::json& v = raw(key);
  if (!v.is_number()) fail(key, fmt::format("value {} is not a number", shown(v)));
  const double x = v.get<double>();
  const bool ok = std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  if (!ok)
    fail(key, fmt::format("value {} is outside the allowed range {}", shown(v), range_text(lo, hi, lo_open, hi_open)));
  return x;
}

double JsonObject::number(const std::string& key, const Range& r, bool whole) {
  const nlohmann::json& v = raw(key);
  if (!v.is_number()) fail(key, fmt::format("value {} is not a number", shown(v)));
  if (whole && !v.is_number_integer()) fail(key, fmt::format("value {} is not a whole number", shown(v)));
  const double x = v.get<double>();
  if (!(std::isfinite(x) && r.contains(x)))
    fail(key, fmt::format("value {} is outside the allowed range {}", shown(v), r.text()));
  return x;
}

double JsonObject::number_or(const std::string& key, double fallback, double lo, double hi, bool lo_open,
                             bool hi_open) {
  return has(key) ? number(key, lo, hi, lo_open, hi_open) : fallback;
}

long JsonObject::integer_or(const std::string& key, long fallback, long lo, long hi) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_number_integer()) fail(key, fmt::format("value {} is not an integer", shown(v)));
  // A value above the long range arrives unsigned; get<long>() would wrap it to a negative number.
  const bool beyond = v.is_number_unsigned() && (hi < 0 || v.get<std::uint64_t>() > std::uint64_t(hi));
  const long x = beyond ? hi : v.get<long>();
  if (beyond || x < lo || x > hi)
    fail(key, fmt::format("value {} is outside the allowed range [{}, {}]", shown(v), lo, hi));
  return x;
}

bool JsonObject::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_boolean()) fail(key, fmt::format("value {} is not true or false", shown(v)));
  return v.get<bool>();
}

static std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string JsonObject::string_or(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& allowed) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_string()) fail(key, fmt::format("value {} is not a string", shown(v)));
  const std::string s = v.get<std::string>();
  if (!allowed.empty()) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == s;
    if (!ok) fail(key, fmt::format("value {} is not one of: {}", shown(v), joined(allowed)));
  }
  return s;
}

Vec3<double> JsonObject::vec3_or(const std::string& key, Vec3<double> fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    fail(key, fmt::format("value {} is not an array of three numbers", shown(v)));
  const Vec3<double> r{v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
  if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z)) fail(key, "values must be finite");
  return r;
}

std::vector<std::string> JsonObject::strings_or(const std::string& key, const std::vector<std::string>& allowed) {
  if (!has(key)) return {};
  const nlohmann::json& v = raw(key);
  if (!v.is_array()) fail(key, fmt::format("value {} is not an array of names", shown(v)));
  std::vector<std::string> out;
  for (const auto& e : v) {
    if (!e.is_string()) fail(key, fmt::format("entry {} is not a string", shown(e)));
    const std::string s = e.get<std::string>();
    bool ok = allowed.empty();
    for (const auto& a : allowed) ok = ok || a == s;
    if (!ok) fail(key, fmt::format("unknown name {}; known: {}", shown(e), joined(allowed)));
    out.push_back(s);
  }
  return out;
}

JsonObject JsonObject::object(const std::string& key) {
  const nlohmann::json& v = raw(key);
  if (!v.is_object()) fail(key, fmt::format("value {} is not a JSON object", shown(v)));
  return JsonObject(v, where_, key_path(key));
}

void JsonObject::finish() const {
  for (auto it = j_.begin(); it != j_.end(); ++it)
    if (!used_.count(it.key())) fail(it.key(), "unknown key (misspelled, or not valid here)");
}

}  // namespace terracal
