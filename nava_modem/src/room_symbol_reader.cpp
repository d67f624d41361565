#include "nava_modem/room_symbol_reader.h"

#include <cmath>
#include <complex>
#include <map>

#include "nava_modem/fft_plan.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

using namespace room_phy;

void RoomSymbolReader::Read(const SampleRing& heard, double pre, double stretch, int count, std::vector<double>& energy,
                            int stride) {
  const double fs = sample_rate_;
  const int length = static_cast<int>(std::lround(kSymbolSeconds * fs * stretch));
  for (int s = 0; s < count; s += stride) {
    const std::int64_t first = std::llround(pre + (kDataStart + s * kSymbolSeconds) * fs * stretch);
    Window(heard, first, length, &energy[static_cast<std::size_t>(s) * kBins]);
  }
}

void RoomSymbolReader::Window(const SampleRing& heard, std::int64_t first, int length, double* energies) {
  // One plan per window length (the length follows the sender's clock: some hundred of them),
  // made when first needed and kept for the thread's life, by every reader: a receiver made
  // anew for each recording or frame would otherwise plan them all again (FFTW's planning was a
  // sixth of a long frame's decoding in nava_bench --frames).
  thread_local std::map<int, FftPlan> plans;
  auto it = plans.find(length);
  if (it == plans.end()) it = plans.emplace(length, FftPlan(FftKind::kRealToComplex, static_cast<std::size_t>(length))).first;
  FftPlan& plan = it->second;
  double* in = plan.real_input();
  for (int k = 0; k < length; ++k) in[k] = heard[first + k];
  plan.Execute();
  const std::complex<double>* out = plan.complex_output();
  // A tone of amplitude A whose frequency sits on a bin gives |X| = A * length / 2: energies
  // are the tones' squared amplitudes.
  const double scale = 4.0 / (static_cast<double>(length) * length);
  for (int b = 0; b < kBins; ++b) {
    const std::complex<double>& x = out[kLowestBin + b];
    energies[b] = (x.real() * x.real() + x.imag() * x.imag()) * scale;
  }
}

}  // namespace nava_modem
