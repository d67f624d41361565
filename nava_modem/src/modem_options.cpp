#include "nava_modem/modem_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nava_modem {
namespace {

[[noreturn]] void Fail(const std::string& what) { throw std::invalid_argument(what); }

}  // namespace

void ValidateSampleRate(const char* what, double sample_rate) {
  if (!(sample_rate >= kMinSampleRate && sample_rate <= kMaxSampleRate)) {
    std::ostringstream why;
    why << what << " " << sample_rate << " Hz: expected " << kMinSampleRate << " to " << kMaxSampleRate;
    Fail(why.str());
  }
}

void ValidateAmplitude(double amplitude) {
  if (!(amplitude > 0.0 && amplitude <= 1.0)) {
    std::ostringstream why;
    why << "amplitude " << amplitude << ": expected above 0 and at most 1 (full scale)";
    Fail(why.str());
  }
}

void ValidateModemOptions(const ModemOptions& o) {
  std::ostringstream why;
  ValidateSampleRate("sample rate", o.sample_rate);
  const double nyquist = o.sample_rate / 2.0;
  for (const auto& [name, f] : {std::pair<const char*, double>{"mark", o.mark_hz}, {"space", o.space_hz}}) {
    if (!(f > 0.0 && f < nyquist)) {
      why << name << " " << f << " Hz: expected above 0 and below Nyquist (" << nyquist << " Hz at "
          << o.sample_rate << " Hz)";
      Fail(why.str());
    }
  }
  if (o.mark_hz == o.space_hz) {
    why << "mark and space are both " << o.mark_hz << " Hz: they must differ";
    Fail(why.str());
  }
  if (!(o.baud > 0.0 && std::isfinite(o.baud))) {
    why << "bit rate " << o.baud << ": expected a positive number of bits/s";
    Fail(why.str());
  }
  if (o.sample_rate / o.baud < 8.0) {
    why << "bit rate " << o.baud << " bits/s is too high for " << o.sample_rate
        << " Hz: at least 8 samples per bit are needed (at most " << o.sample_rate / 8.0 << " bits/s)";
    Fail(why.str());
  }
  if (std::abs(o.mark_hz - o.space_hz) < o.baud) {
    why << "bit rate " << o.baud << " bits/s is too high for tones " << std::abs(o.mark_hz - o.space_hz)
        << " Hz apart: the tones must be at least one bit rate apart";
    Fail(why.str());
  }
  ValidateAmplitude(o.amplitude);
  if (!(o.transition >= 0.0 && o.transition <= 0.5)) {
    why << "transition " << o.transition << ": expected a fraction of a bit from 0 to 0.5";
    Fail(why.str());
  }
}

}  // namespace nava_modem
