#include "audio_propagation/arrival_errors_file.h"

#include <stdexcept>

#include "grid/yaml_fields.h"
#include "package_data/package_data.h"

namespace audio_propagation {

ranging::ArrivalErrors LoadArrivalErrors(const std::string& path, const std::string& expected_profile) {
  const grid::YamlFields root = grid::YamlFields::Load(path, "arrival error table");
  root.ExpectOnlyKeys({"profile", "command", "rooms", "packets_sent", "packets_timed", "snr_db", "min_drr_db", "quantiles_s"});
  const std::string profile = root.String("profile");
  if (!expected_profile.empty() && profile != expected_profile) {
    root.Fail("profile", "the table is for '" + profile + "', but the link runs '" + expected_profile + "'");
  }
  const char* shape = "a list of signed errors (s) at evenly spaced probabilities from 0 to 1, ascending";
  if (!root.Has("quantiles_s")) root.Fail("quantiles_s", std::string("missing; expected ") + shape);
  const YAML::Node seq = root.node()["quantiles_s"];
  if (!seq.IsSequence()) root.Fail("quantiles_s", std::string("expected ") + shape);
  ranging::ArrivalErrors errors;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    try {
      errors.quantiles.push_back(seq[i].as<double>());
    } catch (const YAML::Exception&) {
      root.Fail("quantiles_s[" + std::to_string(i) + "]", "expected a number");
    }
  }
  try {
    ranging::ValidateArrivalErrors(errors);
  } catch (const std::invalid_argument& e) {
    root.Fail("quantiles_s", e.what());
  }
  return errors;
}

std::string ShippedArrivalErrors(const std::string& profile) {
  return package_data::DataFile("tables/" + profile + "_arrival.yaml");
}

}  // namespace audio_propagation
