#pragma once

// Test-only signals at a microphone array: band-limited noise, exact fractional delays (an FFT
// phase shift), a far-field source in free air, and a shoebox room (image sources for the early
// reflections, which are correlated between microphones, plus an independent diffuse tail per
// microphone, which is not). Seeded: the same audio every run.
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "nava_modem/direction_estimator.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_impulse_response.h"

namespace nava_modem::array_signals {

// White Gaussian noise kept to [lo_hz, hi_hz], RMS about 0.1.
inline std::vector<float> BandNoise(std::size_t n, double sample_rate, double lo_hz, double hi_hz, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = gauss(rng);
  auto spectrum = ForwardFft(x, n);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const double hz = BinHz(k, n, sample_rate);
    if (hz < lo_hz || hz > hi_hz) spectrum[k] = 0.0;
  }
  const std::vector<double> y = InverseFft(spectrum, n);
  const double band = (hi_hz - lo_hz) / (sample_rate / 2.0);
  std::vector<float> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<float>(0.1 * y[k] / std::sqrt(band));
  return out;
}

// `x` delayed by `samples` (may be fractional or negative), exactly, through a phase shift over
// a transform long enough that nothing wraps for delays under `pad` samples.
inline std::vector<float> Delayed(const std::vector<float>& x, double samples, std::size_t pad = 4096) {
  const std::size_t n = FftSize(x.size() + pad);
  auto spectrum = ForwardFft(std::vector<double>(x.begin(), x.end()), n);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    spectrum[k] *= std::polar(1.0, -2.0 * M_PI * static_cast<double>(k) * samples / static_cast<double>(n));
  }
  if (n % 2 == 0) spectrum.back() = spectrum.back().real() * std::cos(M_PI * samples);  // keep Nyquist real
  const std::vector<double> y = InverseFft(spectrum, n);
  return std::vector<float>(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(x.size()));
}

inline void AddWhiteNoise(std::vector<float>& x, double rms, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, rms);
  for (float& v : x) v += static_cast<float>(gauss(rng));
}

// What each microphone hears of a far-field source at `bearing` in free air: the source's
// signal delayed by (margin - r_m . u / c) samples, so that every delay is positive.
inline std::vector<std::vector<float>> FarField(const std::vector<float>& source, const std::vector<Microphone2D>& mics,
                                                double bearing, double sample_rate, double margin = 64.0) {
  std::vector<std::vector<float>> out;
  for (const Microphone2D& m : mics) {
    const double lead = (m.x * std::cos(bearing) + m.y * std::sin(bearing)) / 343.0 * sample_rate;
    out.push_back(Delayed(source, margin - lead));
  }
  return out;
}

struct Shoebox {
  double length = 7.0, width = 5.0, height = 3.0;  // m
  double rt60 = 0.5;                               // s, Sabine, sets the walls' reflection
  double drr_db = 0.0;                             // direct over everything else; the diffuse tail fills up to it
  int max_order = 3;                               // image sources up to this many reflections
  double array_x = 3.2, array_y = 2.4, height_of_all = 1.2;
};

// The impulse responses of a shoebox room from a source `distance` m away at `bearing` to each
// microphone (array centre at the box's array_x, array_y). Index 0 is time 0 at the source.
inline std::vector<std::vector<float>> ShoeboxResponses(const Shoebox& room, const std::vector<Microphone2D>& mics,
                                                        double bearing, double distance, double sample_rate,
                                                        unsigned seed) {
  const double c = 343.0;
  const double volume = room.length * room.width * room.height;
  const double surface = 2.0 * (room.length * room.width + room.length * room.height + room.width * room.height);
  const double absorption = std::min(0.99, 0.161 * volume / (surface * room.rt60));
  const double beta = std::sqrt(1.0 - absorption);
  const double sx = room.array_x + distance * std::cos(bearing), sy = room.array_y + distance * std::sin(bearing);
  const double sz = room.height_of_all;
  const std::size_t length = static_cast<std::size_t>((1.2 * room.rt60 + 0.1) * sample_rate);
  std::vector<std::vector<float>> out;
  for (std::size_t m = 0; m < mics.size(); ++m) {
    const double mx = room.array_x + mics[m].x, my = room.array_y + mics[m].y, mz = room.height_of_all;
    std::vector<double> h(length, 0.0);
    double direct_energy = 0.0, image_energy = 0.0, direct_delay = 0.0;
    const int n_max = (room.max_order + 1) / 2 + 1;
    for (int nx = -n_max; nx <= n_max; ++nx)
      for (int ny = -n_max; ny <= n_max; ++ny)
        for (int nz = -n_max; nz <= n_max; ++nz)
          for (int p = 0; p < 8; ++p) {
            const int px = p & 1, py = (p >> 1) & 1, pz = (p >> 2) & 1;
            const int order = std::abs(2 * nx - px) + std::abs(2 * ny - py) + std::abs(2 * nz - pz);
            if (order > room.max_order) continue;
            const double ix = 2.0 * nx * room.length + (px ? -sx : sx);
            const double iy = 2.0 * ny * room.width + (py ? -sy : sy);
            const double iz = 2.0 * nz * room.height + (pz ? -sz : sz);
            const double r = std::sqrt((ix - mx) * (ix - mx) + (iy - my) * (iy - my) + (iz - mz) * (iz - mz));
            const double gain = std::pow(beta, order) / r, delay = r / c * sample_rate;
            (order == 0 ? direct_energy : image_energy) += gain * gain;
            if (order == 0) direct_delay = delay;
            // Windowed-sinc fractional delay, 64 taps.
            const long centre = std::lround(delay);
            for (long k = centre - 32; k <= centre + 32; ++k) {
              if (k < 0 || k >= static_cast<long>(length)) continue;
              const double t = static_cast<double>(k) - delay;
              const double sinc = std::abs(t) < 1e-9 ? 1.0 : std::sin(M_PI * t) / (M_PI * t);
              h[static_cast<std::size_t>(k)] += gain * sinc * (0.5 + 0.5 * std::cos(M_PI * t / 33.0));
            }
          }
    // The diffuse tail, independent per microphone: the statistical model's response minus its
    // direct sound, from 5 ms after the direct sound, scaled to fill up to the DRR.
    const double tail_energy = std::max(0.0, direct_energy / std::pow(10.0, room.drr_db / 10.0) - image_energy);
    std::vector<float> tail = RoomImpulseResponse(room.rt60, 0.0, sample_rate, seed + 1000 * static_cast<unsigned>(m));
    double have = 0.0;
    for (std::size_t k = 1; k < tail.size(); ++k) have += static_cast<double>(tail[k]) * tail[k];
    const double scale = have > 0.0 ? std::sqrt(tail_energy / have) : 0.0;
    const std::size_t start = static_cast<std::size_t>(direct_delay);
    for (std::size_t k = 1; k < tail.size() && start + k < length; ++k) h[start + k] += scale * tail[k];
    out.emplace_back(h.begin(), h.end());
  }
  return out;
}

// `x` through the response `h` (FFT convolution), cut to x's length plus the response's.
inline std::vector<float> Convolve(const std::vector<float>& x, const std::vector<float>& h) {
  const std::size_t n = FftSize(x.size() + h.size());
  auto a = ForwardFft(std::vector<double>(x.begin(), x.end()), n);
  const auto b = ForwardFft(std::vector<double>(h.begin(), h.end()), n);
  for (std::size_t k = 0; k < a.size(); ++k) a[k] *= b[k];
  const std::vector<double> y = InverseFft(a, n);
  return std::vector<float>(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(x.size() + h.size() - 1));
}

// The smallest angle between two bearings, rad.
inline double AngleError(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

inline std::vector<const float*> Pointers(const std::vector<std::vector<float>>& channels, std::size_t offset = 0) {
  std::vector<const float*> out;
  for (const auto& c : channels) out.push_back(c.data() + offset);
  return out;
}

}  // namespace nava_modem::array_signals
