#include "likeness_table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "measured_rooms.h"
#include "nava_modem/measured_like_response.h"
#include "nava_modem/response_features.h"

namespace nava_modem::tools {
namespace {

// nava's tones: the tone ratio is read at them (the two tones a room can set apart).
constexpr double kToneAHz = 2300.0, kToneBHz = 3700.0;
// MeasuredLikeResponse's range of DRR and RT60: a room outside it is drawn at the nearest.
constexpr double kLikeDrrDb = 40.0, kLikeRt60S = 10.0;

struct Feature {
  const char* name;
  double (*read)(const ResponseFeatures&);
  int decimals;
};
const std::array<Feature, 6> kFeatures = {{
    {"onset_db", [](const ResponseFeatures& f) { return f.onset_db; }, 1},
    {"edt_ratio", [](const ResponseFeatures& f) { return f.reverb_edt_ratio; }, 2},
    {"early_db", [](const ResponseFeatures& f) { return f.early_db; }, 1},
    {"colour_db", [](const ResponseFeatures& f) { return f.colour_db; }, 1},
    {"|tone_ratio_db|", [](const ResponseFeatures& f) { return std::fabs(f.tone_ratio_db); }, 1},
    {"direct_spread_ms", [](const ResponseFeatures& f) { return f.direct_spread_ms; }, 1},
}};

// The q-quantile of `v` (linear between order statistics); NaN for none.
double Quantile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(at);
  return i + 1 < v.size() ? v[i] + (at - static_cast<double>(i)) * (v[i + 1] - v[i]) : v[i];
}

struct Row {
  double drr_db = 0.0;
  std::array<double, kFeatures.size()> measured{}, like{};
};

void PrintSpread(const char* label, const std::vector<const Row*>& rows) {
  std::printf("%-22s %5zu", label, rows.size());
  if (rows.empty()) {
    std::printf("   (no room)\n");
    return;
  }
  for (std::size_t k = 0; k < kFeatures.size(); ++k) {
    std::vector<double> d;
    for (const Row* r : rows) d.push_back(r->like[k] - r->measured[k]);
    const int p = kFeatures[k].decimals;
    std::printf("   %+6.*f (%+6.*f..%+6.*f)", p, Quantile(d, 0.5), p, Quantile(d, 0.1), p, Quantile(d, 0.9));
  }
  std::printf("\n");
}

}  // namespace

int LikenessTable(const LikenessRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const double fs = request.sample_rate;
  const std::vector<MeasuredRoom> rooms = MeasuredRooms(request.rir_dir, usage);
  std::printf("likeness (%s): each room's features beside the median of %d measured-like rooms at its RT60 and DRR "
              "(response_features.h; onset_db: the reverberation's share within %.0f ms of the direct sound; edt_ratio: "
              "its early decay over the RT60)\n",
              request.rir_dir.c_str(), request.rooms, kOnsetEndS * 1e3);
  std::printf("%-44s %6s %6s", "room", "rt60_s", "drr_dB");
  for (const Feature& f : kFeatures) std::printf(" %17s", f.name);
  std::printf("\n%-58s", "");
  for (std::size_t k = 0; k < kFeatures.size(); ++k) std::printf(" %8s %8s", "measured", "like");
  std::printf("\n");
  std::vector<Row> rows;
  for (const MeasuredRoom& room : rooms) {
    const ResponseFeatures measured = MeasureFeatures(LoadImpulseResponse(room.path, room.channel, fs), fs, kToneAHz, kToneBHz);
    const double rt60 = std::min(room.figures.rt60_s, kLikeRt60S);
    const double drr = std::clamp(room.figures.drr_db, -kLikeDrrDb, kLikeDrrDb);
    std::array<std::vector<double>, kFeatures.size()> drawn;
    for (int s = 0; s < request.rooms; ++s) {
      const std::uint32_t seed = request.seed + static_cast<std::uint32_t>(s);
      const ResponseFeatures like = MeasureFeatures(MeasuredLikeResponse(rt60, drr, fs, seed), fs, kToneAHz, kToneBHz);
      for (std::size_t k = 0; k < kFeatures.size(); ++k) drawn[k].push_back(kFeatures[k].read(like));
    }
    Row row;
    row.drr_db = room.figures.drr_db;
    std::printf("%-44s %6.2f %+6.1f", room.name.c_str(), room.figures.rt60_s, room.figures.drr_db);
    for (std::size_t k = 0; k < kFeatures.size(); ++k) {
      row.measured[k] = kFeatures[k].read(measured);
      row.like[k] = Quantile(drawn[k], 0.5);
      std::printf(" %8.*f %8.*f", kFeatures[k].decimals, row.measured[k], kFeatures[k].decimals, row.like[k]);
    }
    std::printf("\n");
    rows.push_back(row);
  }
  std::printf("\nmeasured-like less measured: median (10th..90th percentile) over the rooms\n%-22s %5s", "rooms", "count");
  for (const Feature& f : kFeatures) std::printf("   %-24s", f.name);
  std::printf("\n");
  std::vector<const Row*> all, dry, middle, far;
  for (const Row& r : rows) {
    all.push_back(&r);
    (r.drr_db >= 0.0 ? dry : r.drr_db >= -6.0 ? middle : far).push_back(&r);
  }
  PrintSpread("all", all);
  PrintSpread("DRR >= 0 dB", dry);
  PrintSpread("DRR -6 to 0 dB", middle);
  PrintSpread("DRR < -6 dB", far);
  return 0;
}

}  // namespace nava_modem::tools
