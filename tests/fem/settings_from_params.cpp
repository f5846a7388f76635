#include "settings_from_params.hpp"

#include <stdexcept>
#include <string>

#include "scenario/schema_check.hpp"

namespace rumble::test {

fem::FemSettings settings_from(const nlohmann::json& params) {
  static const scenario::SchemaChecker checker(fem::settings_schema());
  std::string refused;
  for (const scenario::SchemaIssue& issue : checker.check(params))
    refused += "\n  params" + issue.pointer + ": " + issue.message;
  if (!refused.empty())
    throw std::invalid_argument("the FEM schema refuses " + params.dump() + ":" + refused);
  return fem::read_settings(params.dump());
}

fem::FemSettings soil_settings(double E, double nu, double rho, const nlohmann::json& more) {
  nlohmann::json params = {{"E", E}, {"nu", nu}, {"rho", rho}};
  params.merge_patch(more);
  return settings_from(std::move(params));
}

}  // namespace rumble::test
