#pragma once
// Strict reading of a JSON object for configs: every key is taken once, typed and range-checked,
// and keys nobody took are an error ("unknown key"), so a misspelling never passes silently.
// Messages name the file, the key path, the value and the allowed range.
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/range.hpp"
#include "core/vec.hpp"

namespace terracal {

class JsonObject {
 public:
  JsonObject(const nlohmann::json& j, std::string where, std::string path);
  bool has(const std::string& key) const { return j_.contains(key); }
  // A number within [lo, hi] (open bounds when lo_open/hi_open).
  double number(const std::string& key, double lo, double hi, bool lo_open = false, bool hi_open = false);
  double number_or(const std::string& key, double fallback, double lo, double hi, bool lo_open = false,
                   bool hi_open = false);
  // A number within the range r (a whole number when `whole`).
  double number(const std::string& key, const Range& r, bool whole = false);
  double number_or(const std::string& key, double fallback, const Range& r) {
    return has(key) ? number(key, r) : fallback;
  }
  long integer_or(const std::string& key, long fallback, long lo, long hi);
  bool boolean_or(const std::string& key, bool fallback);
  std::string string_or(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed);
  Vec3<double> vec3_or(const std::string& key, Vec3<double> fallback);
  std::vector<std::string> strings_or(const std::string& key, const std::vector<std::string>& allowed);
  JsonObject object(const std::string& key);
  const nlohmann::json& raw(const std::string& key);  // marks the key as used
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // Throws for the first key that was never taken.
  void finish() const;
  const std::string& where() const { return where_; }

 private:
  const nlohmann::json& j_;
  std::string where_, path_;
  std::set<std::string> used_;
};

}  // namespace terracal
