#include "bayes/json_state.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace terracal::bayes {

using nlohmann::json;

json encode_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

double decode_double(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::invalid_argument("checkpoint: '" + s + "' is not a number");
}

json vector_to_json(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(encode_double(v[i]));
  return out;
}

Eigen::VectorXd vector_from_json(const json& j, Eigen::Index expected_size) {
  if (!j.is_array() || static_cast<Eigen::Index>(j.size()) != expected_size)
    throw std::invalid_argument("checkpoint: expected a vector of " + std::to_string(expected_size) + " numbers");
  Eigen::VectorXd v(expected_size);
  for (Eigen::Index i = 0; i < expected_size; ++i) v[i] = decode_double(j[i]);
  return v;
}

json matrix_to_json(const Eigen::MatrixXd& m) {
  json out = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) out.push_back(vector_to_json(m.row(r).transpose()));
  return out;
}

Eigen::MatrixXd matrix_from_json(const json& j, Eigen::Index rows, Eigen::Index cols) {
  if (!j.is_array() || static_cast<Eigen::Index>(j.size()) != rows)
    throw std::invalid_argument("checkpoint: expected a matrix of " + std::to_string(rows) + " rows");
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) m.row(r) = vector_from_json(j[r], cols).transpose();
  return m;
}

json vectors_to_json(const std::vector<Eigen::VectorXd>& vs) {
  json out = json::array();
  for (const auto& v : vs) out.push_back(vector_to_json(v));
  return out;
}

std::vector<Eigen::VectorXd> vectors_from_json(const json& j, std::size_t count, Eigen::Index size) {
  if (!j.is_array() || j.size() != count)
    throw std::invalid_argument("checkpoint: expected " + std::to_string(count) + " vectors");
  std::vector<Eigen::VectorXd> out;
  for (const auto& e : j) out.push_back(vector_from_json(e, size));
  return out;
}

json stats_to_json(const ChainStats& s) {
  return {{"iterations", s.iterations}, {"accepted", s.accepted}, {"failed_evaluations", s.failed_evaluations}};
}

ChainStats stats_from_json(const json& j) {
  ChainStats s;
  s.iterations = j.at("iterations").get<long>();
  s.accepted = j.at("accepted").get<long>();
  s.failed_evaluations = j.at("failed_evaluations").get<long>();
  return s;
}

}  // namespace terracal::bayes
