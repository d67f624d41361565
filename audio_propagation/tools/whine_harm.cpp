#include "whine_harm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "nava_modem/modem_profile.h"
#include "parallel_cells.h"

namespace audio_propagation::tools {

void MeasureWhineHarm(CellSetup s, const WhineHarmOptions& o, DecodeTable& table) {
  if (s.profile != nava_modem::Profile::kNava || table.profile != "nava") {
    throw std::invalid_argument("whine harm: measured for nava's tones only, not '" + table.profile + "'");
  }
  if (!(o.low_hz > 0.0 && o.step_hz > 0.0 && o.high_hz >= o.low_hz && o.sir_step_db > 0.0 &&
        o.high_sir_db > o.low_sir_db)) {
    throw std::invalid_argument("whine harm: expected 0 < low <= high frequency, a step above 0 and low < high SIR");
  }
  std::vector<double> freqs;
  for (double f = o.low_hz; f <= o.high_hz + 1e-9; f += o.step_hz) freqs.push_back(f);
  // The reference is curve 0.
  freqs.insert(freqs.begin(), table.whine_hz);
  std::vector<double> sirs;
  for (double x = o.low_sir_db; x <= o.high_sir_db + 1e-9; x += o.sir_step_db) sirs.push_back(x);

  std::vector<std::vector<double>> delivered(freqs.size(), std::vector<double>(sirs.size()));
  const std::size_t cells = freqs.size() * sirs.size();
  struct Worker {
    std::unique_ptr<nava_modem::ModemProfile> receiver;
    CellSetup setup;
  };
  ParallelCells(
      cells, o.threads, [&] { return Worker{nava_modem::MakeProfile(s.profile, s.modem), s}; },
      [&](Worker& w, std::size_t c) {
        const std::size_t f = c / sirs.size(), k = c % sirs.size();
        w.setup.table.whine_hz = freqs[f];
        // The same seeds for every frequency at one SIR: the curves differ by the whine alone.
        const CellCounts n = MeasureCell(w.setup, *w.receiver, 7000 + k, Interference::kWhine, o.rt60, o.drr_db, sirs[k]);
        delivered[f][k] = static_cast<double>(n.heard[static_cast<int>(Heard::kPacket)]) / s.table.packets;
      },
      [&](std::size_t done) {
        if (done % std::max<std::size_t>(1, cells / 20) == 0) std::fprintf(stderr, "  %zu/%zu whine cells\n", done, cells);
      });

  auto area = [](const std::vector<double>& curve) {
    double a = 0.0;
    for (double v : curve) a += v;
    return a;
  };
  // The reference's plateau: the mean of its best quarter of SIRs' delivery (3 of 13).
  std::vector<double> best = delivered[0];
  std::sort(best.rbegin(), best.rend());
  const std::size_t top = std::max<std::size_t>(1, best.size() / 4);
  double plateau = 0.0;
  for (std::size_t k = 0; k < top; ++k) plateau += best[k] / static_cast<double>(top);
  if (!(plateau >= 0.5)) {
    throw std::runtime_error("whine harm: the reference whine at " + std::to_string(table.whine_hz) +
                             " Hz leaves a plateau of " + std::to_string(plateau) +
                             " of packets; expected at least half (the room is too hard for a curve)");
  }
  const double reference = area(delivered[0]);
  std::vector<double> hz, db;
  std::printf("whine harm of nava against a whine at %.0f Hz (RT60 %.2f s, DRR %+.0f dB, %d packets a SIR; plateau %.2f)\n",
              table.whine_hz, o.rt60, o.drr_db, s.table.packets, plateau);
  for (std::size_t f = 1; f < freqs.size(); ++f) {
    const double harm = std::round(10.0 * (reference - area(delivered[f])) / plateau * o.sir_step_db) / 10.0;
    hz.push_back(freqs[f]);
    db.push_back(std::clamp(harm, -60.0, 60.0));
    std::printf("  %6.0f Hz  %+5.1f dB  delivery by SIR:", freqs[f], db.back());
    for (double v : delivered[f]) std::printf(" %.2f", v);
    std::printf("\n");
  }
  // The table's own whine harms as the table says, whatever the grid: 0 dB at whine_hz.
  if (std::find(hz.begin(), hz.end(), table.whine_hz) == hz.end()) {
    const auto at = std::lower_bound(hz.begin(), hz.end(), table.whine_hz) - hz.begin();
    hz.insert(hz.begin() + at, table.whine_hz);
    db.insert(db.begin() + at, 0.0);
  }
  table.whine_harm_hz = hz;
  table.whine_harm_db = db;
}

}  // namespace audio_propagation::tools
