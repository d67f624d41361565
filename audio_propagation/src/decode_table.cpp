#include "audio_propagation/decode_table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "grid/input_error.h"
#include "grid/yaml_fields.h"
#include "nava_modem/modem_profile.h"
#include "package_data/package_data.h"

namespace audio_propagation {
namespace {

constexpr std::array<Interference, kInterferenceCount> kAllKinds = {
    Interference::kWhite, Interference::kPink, Interference::kSpeech, Interference::kWhine, Interference::kPacket};
constexpr const char* kKindList = "white, pink, speech, whine, packet";

// Where `x` falls on an ascending axis: the two neighbouring entries and the weight of the upper
// one. Beyond either end (and for NaN, which compares false) the end entry alone.
struct AxisPoint {
  std::size_t low = 0, high = 0;
  double weight = 0.0;
};
AxisPoint Locate(const std::vector<double>& axis, double x) {
  if (!(x > axis.front())) return {0, 0, 0.0};
  if (x >= axis.back()) return {axis.size() - 1, axis.size() - 1, 0.0};
  const std::size_t high = static_cast<std::size_t>(std::upper_bound(axis.begin(), axis.end(), x) - axis.begin());
  const std::size_t low = high - 1;
  return {low, high, (x - axis[low]) / (axis[high] - axis[low])};
}

void AddScaled(DecodeOutcome& sum, const DecodeOutcome& o, double w) {
  sum.packet += w * o.packet;
  sum.zero_byte += w * o.zero_byte;
  sum.one_byte += w * o.one_byte;
  sum.bad_crc += w * o.bad_crc;
}

std::string FlowText(const YAML::Node& node) {
  YAML::Emitter e;
  e << YAML::Flow << node;
  return e.c_str();
}

// An axis: a non-empty list of finite numbers, strictly ascending.
std::vector<double> ReadAxis(const grid::YamlFields& f, const std::string& key) {
  const char* shape = "a non-empty list of numbers in ascending order";
  if (!f.Has(key)) f.Fail(key, std::string("missing; expected ") + shape);
  const YAML::Node seq = f.node()[key];
  if (!seq.IsSequence() || seq.size() == 0) f.Fail(key, std::string("expected ") + shape + ", got " + FlowText(seq));
  std::vector<double> axis;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    double v = 0.0;
    try {
      v = seq[i].as<double>();
    } catch (const YAML::Exception&) {
      f.Fail(key + "[" + std::to_string(i) + "]", "expected a number, got " + FlowText(seq[i]));
    }
    if (!std::isfinite(v)) f.Fail(key + "[" + std::to_string(i) + "]", "expected a finite number");
    if (!axis.empty() && !(v > axis.back())) {
      f.Fail(key, std::string("expected ") + shape + ", got " + FlowText(seq));
    }
    axis.push_back(v);
  }
  return axis;
}

// A list of `n` entries (one per value of the axis `per`), else a message naming both.
void ExpectList(const grid::YamlFields& kinds, const std::string& field, const YAML::Node& node, std::size_t n,
                const char* per) {
  if (node.IsSequence() && node.size() == n) return;
  const std::string got = node.IsSequence() ? std::to_string(node.size()) + " entries" : FlowText(node);
  kinds.Fail(field, "expected a list of " + std::to_string(n) + " entries, one per " + per + " value, got " + got);
}

DecodeOutcome ReadOutcome(const grid::YamlFields& kinds, const std::string& field, const YAML::Node& node) {
  const std::string problem = "expected 4 fractions in [0, 1] summing to at most 1, got " + FlowText(node);
  if (!node.IsSequence() || node.size() != 4) kinds.Fail(field, problem);
  double v[4];
  for (std::size_t k = 0; k < 4; ++k) {
    try {
      v[k] = node[k].as<double>();
    } catch (const YAML::Exception&) {
      kinds.Fail(field, problem);
    }
    if (!(v[k] >= 0.0 && v[k] <= 1.0)) kinds.Fail(field, problem);
  }
  // Tolerance for the decimal digits of a file written by hand.
  if (v[0] + v[1] + v[2] + v[3] > 1.0 + 1e-9) kinds.Fail(field, problem);
  return {v[0], v[1], v[2], v[3]};
}

// A fraction to 4 decimals, without trailing zeros ("0.5", "1", "0.0833").
std::string Fraction(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", x);
  std::string s = text;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

// The shortest text that reads back as the same double.
std::string Number(double x) {
  char text[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  return text;
}

// The outcome rounded to 4 decimals so that its fractions still sum to at most 1: the rounding
// of each may add up to 0.00005, so the excess comes off the largest.
std::array<double, 4> Rounded(const DecodeOutcome& o) {
  std::array<double, 4> v = {o.packet, o.zero_byte, o.one_byte, o.bad_crc};
  double sum = 0.0;
  for (double& x : v) {
    x = std::round(std::clamp(x, 0.0, 1.0) * 1e4) / 1e4;
    sum += x;
  }
  if (sum > 1.0) {
    double& largest = *std::max_element(v.begin(), v.end());
    largest = std::round((largest - (sum - 1.0)) * 1e4) / 1e4;
  }
  return v;
}

}  // namespace

std::optional<Interference> ParseInterference(const std::string& name) {
  for (Interference kind : kAllKinds) {
    if (name == InterferenceName(kind)) return kind;
  }
  return std::nullopt;
}

const char* InterferenceName(Interference kind) {
  switch (kind) {
    case Interference::kWhite: return "white";
    case Interference::kPink: return "pink";
    case Interference::kSpeech: return "speech";
    case Interference::kWhine: return "whine";
    case Interference::kPacket: return "packet";
  }
  return "?";
}

Interference FromNoiseKind(world_sim::NoiseKind kind) {
  switch (kind) {
    case world_sim::NoiseKind::kWhite: return Interference::kWhite;
    case world_sim::NoiseKind::kPink: return Interference::kPink;
    case world_sim::NoiseKind::kSpeech: return Interference::kSpeech;
    case world_sim::NoiseKind::kWhine: return Interference::kWhine;
    // Weighed as white noise by where its power lies (Disturbance::listened).
    case world_sim::NoiseKind::kRecording: return Interference::kWhite;
  }
  return Interference::kPink;
}

std::size_t DecodeTable::Index(Interference kind, std::size_t rt, std::size_t drr, std::size_t snr) const {
  const std::size_t k = static_cast<std::size_t>(kind);
  if (k >= kInterferenceCount || rt >= rt60.size() || drr >= drr_db.size() || snr >= snr_db.size()) {
    throw std::out_of_range("decode table: cell (" + std::to_string(k) + ", " + std::to_string(rt) + ", " +
                            std::to_string(drr) + ", " + std::to_string(snr) + ") is outside the axes");
  }
  return ((k * rt60.size() + rt) * drr_db.size() + drr) * snr_db.size() + snr;
}

void DecodeTable::Resize() {
  cells.assign(kInterferenceCount * rt60.size() * drr_db.size() * snr_db.size(), DecodeOutcome{});
}

DecodeOutcome DecodeTable::Lookup(Interference kind, double snr, double drr, double rt) const {
  if (snr_db.empty() || drr_db.empty() || rt60.empty()) throw std::logic_error("decode table: an axis is empty");
  const AxisPoint s = Locate(snr_db, snr), d = Locate(drr_db, drr), r = Locate(rt60, rt);
  DecodeOutcome sum;
  for (int corner = 0; corner < 8; ++corner) {
    const bool hs = corner & 1, hd = corner & 2, hr = corner & 4;
    const double w = (hs ? s.weight : 1.0 - s.weight) * (hd ? d.weight : 1.0 - d.weight) *
                     (hr ? r.weight : 1.0 - r.weight);
    if (w == 0.0) continue;
    AddScaled(sum, At(kind, hr ? r.high : r.low, hd ? d.high : d.low, hs ? s.high : s.low), w);
  }
  return sum;
}

double DecodeTable::WhineHarmDb(double hz) const {
  if (whine_harm_hz.empty() || whine_harm_hz.size() != whine_harm_db.size()) {
    throw std::logic_error("decode table: no whine harm curve");
  }
  if (!std::isfinite(hz)) throw std::invalid_argument("decode table: a whine of " + Number(hz) + " Hz has no harm");
  const AxisPoint at = Locate(whine_harm_hz, hz);
  return (1.0 - at.weight) * whine_harm_db[at.low] + at.weight * whine_harm_db[at.high];
}

DecodeTable LoadDecodeTable(const std::string& path, const std::string& expected_profile) {
  const grid::YamlFields root = grid::YamlFields::Load(path, "decode table");
  root.ExpectOnlyKeys({"profile", "packets", "whine_hz", "band_hz", "command", "rooms", "lead_s", "snr_db", "drr_db", "rt60",
                       "whine_harm", "kinds"});
  DecodeTable t;
  t.profile = root.String("profile");
  if (!nava_modem::ParseProfile(t.profile)) {
    root.Fail("profile", std::string("expected ") + nava_modem::kProfileNames + ", got '" + t.profile + "'");
  }
  if (!expected_profile.empty() && t.profile != expected_profile) {
    root.Fail("profile", "the table is for '" + t.profile + "', but the link runs '" + expected_profile + "'");
  }
  const double packets = root.Number("packets");
  if (!(packets >= 1.0 && packets <= 1e9 && packets == std::floor(packets))) {
    root.Fail("packets", "expected a whole number of packets from 1, got " + Number(packets));
  }
  t.packets = static_cast<int>(packets);
  t.whine_hz = root.Number("whine_hz");
  if (!(t.whine_hz > 0.0 && t.whine_hz < 1e5)) root.Fail("whine_hz", "expected a frequency in (0, 100000) Hz");
  const std::vector<double> band = root.Numbers("band_hz", 2, "[low, high] in Hz");
  if (!(band[0] >= 0.0 && band[0] < band[1] && std::isfinite(band[1]))) {
    root.Fail("band_hz", "expected [low, high] with 0 <= low < high");
  }
  t.band_low_hz = band[0];
  t.band_high_hz = band[1];
  t.command = root.String("command", "");
  const std::string rooms = root.String("rooms", nava_modem::RoomModelName(t.rooms));
  const auto model = nava_modem::ParseRoomModel(rooms);
  if (!model) root.Fail("rooms", std::string("expected ") + nava_modem::kRoomModelNames + ", got '" + rooms + "'");
  t.rooms = *model;
  t.lead_s = root.Number("lead_s", kFormerTableLeadSeconds);
  if (!(t.lead_s >= 0.0 && t.lead_s <= 60.0)) root.Fail("lead_s", "expected seconds from 0 to 60, got " + Number(t.lead_s));
  t.snr_db = ReadAxis(root, "snr_db");
  t.drr_db = ReadAxis(root, "drr_db");
  t.rt60 = ReadAxis(root, "rt60");
  if (!(t.rt60.front() > 0.0)) root.Fail("rt60", "expected reverberation times above 0 s");
  if (root.Has("whine_harm")) {
    const grid::YamlFields harm = root.Child("whine_harm");
    harm.ExpectOnlyKeys({"hz", "db"});
    t.whine_harm_hz = ReadAxis(harm, "hz");
    t.whine_harm_db = harm.Numbers("db", t.whine_harm_hz.size(), "one harm in dB per frequency of hz");
    if (!(t.whine_harm_hz.front() > 0.0)) {
      harm.Fail("hz", "expected frequencies above 0 Hz, got " + Number(t.whine_harm_hz.front()));
    }
    for (double db : t.whine_harm_db) {
      if (!(std::fabs(db) <= 60.0)) harm.Fail("db", "expected harms from -60 to 60 dB, got " + Number(db));
    }
  }

  if (!root.Has("kinds")) root.Fail("kinds", std::string("missing; expected every kind: ") + kKindList);
  const grid::YamlFields kinds = root.Child("kinds");
  kinds.ExpectOnlyKeys({"white", "pink", "speech", "whine", "packet"});
  t.Resize();
  for (Interference kind : kAllKinds) {
    const std::string name = InterferenceName(kind);
    if (!kinds.Has(name)) kinds.Fail(name, std::string("missing; every kind is required: ") + kKindList);
    const YAML::Node per_rt = kinds.node()[name];
    ExpectList(kinds, name, per_rt, t.rt60.size(), "rt60");
    for (std::size_t r = 0; r < t.rt60.size(); ++r) {
      const std::string rt_field = name + "[" + std::to_string(r) + "]";
      ExpectList(kinds, rt_field, per_rt[r], t.drr_db.size(), "drr_db");
      for (std::size_t d = 0; d < t.drr_db.size(); ++d) {
        const std::string drr_field = rt_field + "[" + std::to_string(d) + "]";
        ExpectList(kinds, drr_field, per_rt[r][d], t.snr_db.size(), "snr_db");
        for (std::size_t s = 0; s < t.snr_db.size(); ++s) {
          t.At(kind, r, d, s) = ReadOutcome(kinds, drr_field + "[" + std::to_string(s) + "]", per_rt[r][d][s]);
        }
      }
    }
  }
  return t;
}

void SaveDecodeTable(const std::string& path, const DecodeTable& table) {
  if (table.cells.size() != kInterferenceCount * table.rt60.size() * table.drr_db.size() * table.snr_db.size()) {
    throw std::invalid_argument(path + ": the decode table's cells do not match its axes");
  }
  YAML::Emitter out;
  auto numbers = [&](const char* key, const std::vector<double>& values) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double v : values) out << Number(v);
    out << YAML::EndSeq;
  };
  out << YAML::BeginMap;
  out << YAML::Key << "profile" << YAML::Value << table.profile;
  out << YAML::Key << "packets" << YAML::Value << table.packets;
  out << YAML::Key << "whine_hz" << YAML::Value << Number(table.whine_hz);
  numbers("band_hz", {table.band_low_hz, table.band_high_hz});
  out << YAML::Key << "command" << YAML::Value << YAML::DoubleQuoted << table.command;
  out << YAML::Key << "rooms" << YAML::Value << nava_modem::RoomModelName(table.rooms);
  out << YAML::Key << "lead_s" << YAML::Value << Number(table.lead_s);
  numbers("snr_db", table.snr_db);
  numbers("drr_db", table.drr_db);
  numbers("rt60", table.rt60);
  if (table.whine_harm_hz.size() != table.whine_harm_db.size()) {
    throw std::invalid_argument(path + ": the whine harm curve has " + std::to_string(table.whine_harm_hz.size()) +
                                " frequencies and " + std::to_string(table.whine_harm_db.size()) + " harms");
  }
  if (!table.whine_harm_hz.empty()) {
    out << YAML::Key << "whine_harm" << YAML::Value << YAML::BeginMap;
    numbers("hz", table.whine_harm_hz);
    numbers("db", table.whine_harm_db);
    out << YAML::EndMap;
  }
  out << YAML::Key << "kinds" << YAML::Value << YAML::BeginMap;
  for (Interference kind : kAllKinds) {
    // Block lists over rt60 and DRR; a line per DRR: the flow list over SNR, with a comment saying
    // which rt60 and DRR it is.
    out << YAML::Key << InterferenceName(kind) << YAML::Value << YAML::BeginSeq;
    for (std::size_t r = 0; r < table.rt60.size(); ++r) {
      out << YAML::BeginSeq;
      for (std::size_t d = 0; d < table.drr_db.size(); ++d) {
        out << YAML::Flow << YAML::BeginSeq;
        for (std::size_t s = 0; s < table.snr_db.size(); ++s) {
          out << YAML::Flow << YAML::BeginSeq;
          for (double v : Rounded(table.At(kind, r, d, s))) out << Fraction(v);
          out << YAML::EndSeq;
        }
        out << YAML::EndSeq << YAML::Comment("rt60 " + Number(table.rt60[r]) + " s, drr " + Number(table.drr_db[d]) + " dB");
      }
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap << YAML::EndMap;
  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error(path + ": cannot write the decode table");
}

std::string ShippedDecodeTable(const std::string& profile) {
  return package_data::DataFile("tables/" + profile + ".yaml");
}

}  // namespace audio_propagation
