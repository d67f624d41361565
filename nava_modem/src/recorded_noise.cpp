#include "nava_modem/recorded_noise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/fft_plan.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

Bands ListeningBands(Profile profile) {
  if (profile == Profile::kRoom) return {{room_phy::kLowestToneHz, room_phy::kHighestHz}};
  const ModemOptions modem;  // the thesis's tones, which the tables are measured with
  const double half = modem.baud / 2.0;
  return {{modem.mark_hz - half, modem.mark_hz + half}, {modem.space_hz - half, modem.space_hz + half}};
}

RecordedNoise::RecordedNoise(const std::vector<float>& samples, double sample_rate) : sample_rate_(sample_rate) {
  if (!(sample_rate > 0.0)) {
    throw std::invalid_argument("recorded noise: sample rate must be above 0 Hz, got " + std::to_string(sample_rate));
  }
  if (samples.size() < kWindow) {
    throw std::invalid_argument("recorded noise: expected at least " + std::to_string(kWindow) + " samples, got " +
                                std::to_string(samples.size()));
  }
  double sum = 0.0;
  for (float s : samples) {
    if (!std::isfinite(s)) throw std::invalid_argument("recorded noise: a sample is not a finite number");
    sum += static_cast<double>(s) * s;
  }
  power_ = sum / static_cast<double>(samples.size());
  if (!(power_ > 0.0)) throw std::invalid_argument("recorded noise: the recording is silent");

  FftPlan fft(FftKind::kRealToComplex, kWindow);
  std::vector<double> window(kWindow);
  const double pi = std::acos(-1.0);
  for (std::size_t k = 0; k < kWindow; ++k) window[k] = 0.5 - 0.5 * std::cos(2.0 * pi * k / kWindow);
  density_.assign(fft.output_length(), 0.0);
  for (std::size_t start = 0; start + kWindow <= samples.size(); start += kWindow / 2) {
    double* in = fft.real_input();
    for (std::size_t k = 0; k < kWindow; ++k) in[k] = window[k] * samples[start + k];
    fft.Execute();
    const std::complex<double>* out = fft.complex_output();
    for (std::size_t b = 0; b < density_.size(); ++b) density_[b] += std::norm(out[b]);
  }
  double total = 0.0;
  for (double d : density_) total += d;
  if (!(total > 0.0)) throw std::invalid_argument("recorded noise: the recording is silent");
  for (double& d : density_) d /= total;
}

double RecordedNoise::Fraction(const Bands& bands) const {
  const double bin_hz = sample_rate_ / kWindow;
  double fraction = 0.0;
  for (std::size_t b = 0; b < density_.size(); ++b) {
    // Bin b covers [(b - 1/2) bin_hz, (b + 1/2) bin_hz), clipped to [0, Nyquist].
    const double low = std::max(0.0, (b - 0.5) * bin_hz);
    const double high = std::min(sample_rate_ / 2.0, (b + 0.5) * bin_hz);
    if (high <= low) continue;
    double inside = 0.0;
    for (const auto& [lo, hi] : bands) inside += std::max(0.0, std::min(high, hi) - std::max(low, lo));
    fraction += density_[b] * std::min(1.0, inside / (high - low));
  }
  return fraction;
}

double WhiteFraction(const Bands& bands, double sample_rate) {
  const double nyquist = sample_rate / 2.0;
  double inside = 0.0;
  for (const auto& [lo, hi] : bands) inside += std::max(0.0, std::min(hi, nyquist) - std::max(lo, 0.0));
  return inside / nyquist;
}

double WhiteEquivalentOffsetDb(const RecordedNoise& noise, const Bands& bands, double white_rate) {
  // A recording with nothing in the bands is as harmless as white noise 60 dB down.
  const double recorded = std::max(noise.Fraction(bands), 1e-6 * WhiteFraction(bands, white_rate));
  return 10.0 * std::log10(WhiteFraction(bands, white_rate) / recorded);
}

std::vector<std::vector<double>> CellPowers(const std::vector<float>& samples, double sample_rate,
                                            const Bands& bands, double cell_seconds, double cell_hz) {
  if (!(cell_seconds > 0.0) || !(cell_hz > 0.0) || !(sample_rate > 0.0)) {
    throw std::invalid_argument("cell powers: a cell of " + std::to_string(cell_seconds) + " s by " +
                                std::to_string(cell_hz) + " Hz at " + std::to_string(sample_rate) +
                                " Hz sampling; expected all above 0");
  }
  const auto frame = static_cast<std::size_t>(std::lround(cell_seconds * sample_rate));
  const std::size_t frames = frame > 1 ? samples.size() / frame : 0;
  if (frames < 4) {
    throw std::invalid_argument("cell powers: expected at least 4 cells of " + std::to_string(cell_seconds) +
                                " s, the recording has " + std::to_string(samples.size()) + " samples");
  }
  // Each cell's FFT bins: those whose centres lie in [cell low, cell high) of a band.
  const double bin_hz = sample_rate / static_cast<double>(frame);
  std::vector<std::pair<std::size_t, std::size_t>> cells;  // bins [first, last)
  for (const auto& [low, high] : bands) {
    for (double lo = low; lo + 0.5 * cell_hz <= high; lo += cell_hz) {
      const auto first = static_cast<std::size_t>(std::ceil(lo / bin_hz));
      const auto last =
          std::min(frame / 2 + 1, static_cast<std::size_t>(std::ceil(std::min(high, lo + cell_hz) / bin_hz)));
      if (last > first) cells.emplace_back(first, last);
    }
  }
  if (cells.empty()) throw std::invalid_argument("cell powers: no cell of the bands lies below the Nyquist frequency");

  FftPlan fft(FftKind::kRealToComplex, frame);
  std::vector<double> window(frame);
  const double pi = std::acos(-1.0);
  for (std::size_t k = 0; k < frame; ++k) window[k] = 0.5 - 0.5 * std::cos(2.0 * pi * (k + 0.5) / frame);
  std::vector<std::vector<double>> powers(frames, std::vector<double>(cells.size()));
  double mean = 0.0;
  for (std::size_t f = 0; f < frames; ++f) {
    double* in = fft.real_input();
    for (std::size_t k = 0; k < frame; ++k) in[k] = window[k] * samples[f * frame + k];
    fft.Execute();
    const std::complex<double>* out = fft.complex_output();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      for (std::size_t b = cells[c].first; b < cells[c].second; ++b) powers[f][c] += std::norm(out[b]);
      mean += powers[f][c];
    }
  }
  mean /= static_cast<double>(frames * cells.size());
  if (!(mean > 0.0)) throw std::invalid_argument("cell powers: the recording is silent in the bands");
  for (std::vector<double>& row : powers) {
    for (double& p : row) p /= mean;
  }
  return powers;
}

double EffectiveSnrDb(const std::vector<double>& cells, double snr_db, double beta_db) {
  if (cells.empty()) throw std::invalid_argument("effective SNR: no cells");
  const double g = std::pow(10.0, snr_db / 10.0), beta = std::pow(10.0, beta_db / 10.0);
  // ln mean exp(-g_i / beta), from the largest term so that no exponential underflows; a cell
  // of digital silence is held 60 dB under the mean.
  std::vector<double> terms;
  terms.reserve(cells.size());
  double top = -1e300;
  for (double c : cells) {
    terms.push_back(-g / std::max(c, 1e-6) / beta);
    top = std::max(top, terms.back());
  }
  double sum = 0.0;
  for (double t : terms) sum += std::exp(t - top);
  const double log_mean = top + std::log(sum / static_cast<double>(cells.size()));
  return 10.0 * std::log10(-beta * log_mean);
}

namespace {

constexpr double kCellSeconds = room_phy::kSymbolSeconds;
constexpr double kCellHz = room_phy::kTonesPerBand * room_phy::kToneSpacingHz;  // a sub-band

// The cells a room packet whose first symbol falls on frame `start` uses: symbol s in frame
// start + s (wrapping round the recording, as the renderer loops it), in sub-band Band(s).
std::vector<double> PacketCells(const std::vector<std::vector<double>>& powers, std::size_t start) {
  std::vector<double> cells(room_phy::kSymbols);
  for (int s = 0; s < room_phy::kSymbols; ++s) {
    cells[static_cast<std::size_t>(s)] =
        powers[(start + static_cast<std::size_t>(s)) % powers.size()][static_cast<std::size_t>(room_phy::Band(s))];
  }
  return cells;
}

}  // namespace

RecordingWeight::RecordingWeight(const std::vector<float>& samples, double sample_rate, Profile profile,
                                 double white_rate) {
  const Bands bands = ListeningBands(profile);
  const RecordedNoise noise(samples, sample_rate);
  in_band_offset_db_ = WhiteEquivalentOffsetDb(noise, bands, white_rate);
  in_band_fraction_ = noise.Fraction(bands);
  if (profile != Profile::kRoom) return;
  // Every sub-band must be there: a recording sampled slower cannot say what it puts in the top.
  if (!(sample_rate >= 2.0 * room_phy::kHighestHz)) {
    throw std::invalid_argument("recorded noise: sampled at " + std::to_string(sample_rate) +
                                " Hz; the room profile's band reaches " + std::to_string(room_phy::kHighestHz) +
                                " Hz, so expected a rate of at least " + std::to_string(2.0 * room_phy::kHighestHz) +
                                " Hz");
  }
  const std::vector<std::vector<double>> powers = CellPowers(samples, sample_rate, bands, kCellSeconds, kCellHz);
  for (std::size_t k = 0; k < kPacketWindows; ++k) packets_.push_back(PacketCells(powers, k * powers.size() / kPacketWindows));
  // White noise's cells scatter too (a cell holds few degrees of freedom), and the table holds
  // that scatter: each packet is weighed against it, not against a flat noise.
  const std::vector<double> white = WhiteNoise(static_cast<std::size_t>(8.0 * sample_rate), 1);
  for (const std::vector<double>& row :
       CellPowers(std::vector<float>(white.begin(), white.end()), sample_rate, bands, kCellSeconds, kCellHz)) {
    white_cells_.insert(white_cells_.end(), row.begin(), row.end());
  }
}

std::vector<double> RecordingWeight::TableSnrsDb(double white_snr_db, double share) const {
  if (packets_.empty()) return {white_snr_db};
  // No signal (or no noise) at all: nothing for the cells to change.
  if (!std::isfinite(white_snr_db)) return std::vector<double>(packets_.size(), white_snr_db);
  share = std::clamp(share, 0.0, 1.0);
  const double white = EffectiveSnrDb(white_cells_, white_snr_db, kRoomBetaDb);
  std::vector<double> out;
  out.reserve(packets_.size());
  for (const std::vector<double>& cells : packets_) {
    std::vector<double> mixed(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) mixed[i] = share * cells[i] + (1.0 - share);
    out.push_back(white_snr_db + EffectiveSnrDb(mixed, white_snr_db, kRoomBetaDb) - white);
  }
  return out;
}

}  // namespace nava_modem
