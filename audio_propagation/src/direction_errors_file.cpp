#include "audio_propagation/direction_errors_file.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "grid/yaml_fields.h"
#include "package_data/package_data.h"

namespace audio_propagation {

namespace {

constexpr double kRad = M_PI / 180.0;

std::vector<DirectionSample> Samples(const grid::YamlFields& cell, const char* array) {
  const char* shape = "a list of [true bearing (deg), estimate (deg, or .nan for none), confidence (0..1)]";
  if (!cell.Has(array)) cell.Fail(array, std::string("missing; expected ") + shape);
  const YAML::Node seq = cell.node()[array];
  if (!seq.IsSequence()) cell.Fail(array, std::string("expected ") + shape);
  std::vector<DirectionSample> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const std::string field = std::string(array) + "[" + std::to_string(i) + "]";
    const YAML::Node s = seq[i];
    DirectionSample sample;
    try {
      if (!s.IsSequence() || s.size() != 3) throw YAML::Exception(YAML::Mark::null_mark(), "shape");
      sample.truth = s[0].as<double>() * kRad;
      sample.estimate = s[1].as<double>() * kRad;
      sample.confidence = s[2].as<double>();
    } catch (const YAML::Exception&) {
      cell.Fail(field, std::string("expected ") + shape);
    }
    if (!std::isfinite(sample.truth) || std::isinf(sample.estimate) || !(sample.confidence >= 0.0 && sample.confidence <= 1.0)) {
      cell.Fail(field, std::string("expected ") + shape);
    }
    out.push_back(sample);
  }
  return out;
}

}  // namespace

DirectionErrors LoadDirectionErrors(const std::string& path, const std::string& expected_profile) {
  const grid::YamlFields root = grid::YamlFields::Load(path, "direction table");
  root.ExpectOnlyKeys({"profile", "command", "snr_db", "packets", "min_packets", "rt60_s", "drr_db", "arrays", "cells"});
  const std::string profile = root.String("profile");
  if (!expected_profile.empty() && profile != expected_profile) {
    root.Fail("profile", "the table is for '" + profile + "', but the link runs '" + expected_profile + "'");
  }
  std::vector<DirectionCell> cells;
  for (const grid::YamlFields& c : root.Elements("cells")) {
    c.ExpectOnlyKeys({"rt60_s", "drr_db", "sent", "omni", "bidirectional"});
    DirectionCell cell;
    cell.rt60 = c.Number("rt60_s");
    cell.drr_db = c.Number("drr_db");
    cell.omni = Samples(c, "omni");
    cell.bidirectional = Samples(c, "bidirectional");
    cells.push_back(std::move(cell));
  }
  const double min_packets = root.Number("min_packets", static_cast<double>(DirectionErrors::kMinPackets));
  if (!(min_packets >= 1.0 && min_packets <= 1e6) || min_packets != std::floor(min_packets)) {
    root.Fail("min_packets", "expected a whole number of packets from 1 (what a cell needs to be drawn from)");
  }
  try {
    return DirectionErrors(profile, std::move(cells), static_cast<std::size_t>(min_packets));
  } catch (const std::invalid_argument& e) {
    root.Fail("cells", e.what());
  }
}

std::string ShippedDirectionErrors(const std::string& profile) {
  return package_data::DataFile("tables/" + profile + "_direction.yaml");
}

}  // namespace audio_propagation
