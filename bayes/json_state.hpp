#pragma once
// Sampler checkpoints as JSON. nlohmann::json writes doubles in their shortest round-trip form,
// so a dump/parse cycle restores them bit for bit; it cannot write infinities (it writes null),
// and a log density may be -inf, so scalars go through encode_double/decode_double.
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "bayes/target.hpp"

namespace terracal::bayes {

nlohmann::json encode_double(double v);  // a number, or "inf" / "-inf" / "nan"
double decode_double(const nlohmann::json& j);

nlohmann::json vector_to_json(const Eigen::VectorXd& v);
Eigen::VectorXd vector_from_json(const nlohmann::json& j, Eigen::Index expected_size);

nlohmann::json matrix_to_json(const Eigen::MatrixXd& m);  // list of rows
Eigen::MatrixXd matrix_from_json(const nlohmann::json& j, Eigen::Index rows, Eigen::Index cols);

nlohmann::json vectors_to_json(const std::vector<Eigen::VectorXd>& vs);
std::vector<Eigen::VectorXd> vectors_from_json(const nlohmann::json& j, std::size_t count, Eigen::Index size);

nlohmann::json stats_to_json(const ChainStats& s);
ChainStats stats_from_json(const nlohmann::json& j);

}  // namespace terracal::bayes
