#include "nava_modem/first_arrival.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/fft_plan.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

// The band is weighted by a Hann window across it, not a flat top with rolled-off edges: a flat
// top's pulse has sidelobes that fall off over 1/(roll-off), -13 dB at 0.3 ms and -30 dB still
// 2 ms out, and a strong reflection's would hide a weak direct sound a few milliseconds before
// it. The Hann band's pulse is below -45 dB from 1 ms on.
// Where the reference is weaker than this share of its strongest in-band power, the division
// is held back (a Wiener-like regularisation): its noise would swamp the response there.
constexpr double kRegularisation = 1e-3;
// An earlier peak counts as the direct sound only if it stands this far above the largest
// sidelobe the reference itself makes (nava's tones repeat their patterns bit by bit, and a
// reverberant room lifts those sidelobes); kDirectWithinDb where the reference has none.
constexpr double kSidelobeMargin = 1.5;
// Near a stronger peak an earlier one must stand this far above the sidelobe the reference's
// pulse has at that distance before it (amplitude ratio, 9.5 dB), whatever the largest peak:
// a measured direct sound's pulse, widened by the loudspeaker and the microphone, has its
// first sidelobe up to 4 dB over the band's own (-31.5 dB, 0.5 ms before it), and noise moves
// it by a few dB more; with only kSidelobeMargin over the band's, that sidelobe passed for an
// arrival in some packets and not in others, 0.4 ms early (a theatre, a church, a stone
// chamber, a sports hall). No direct sound is 20 dB under a reflection half a millisecond
// after it.
constexpr double kNearSidelobeMargin = 3.0;
// A peak of the envelope counts fully as one where its power falls by this much before rising
// again, not at all where it falls by kPeakDipRampDb less (a shoulder on the way up, an arrival
// merged into the next or the noise's ripple, climbed past), and in part in between. Not lower:
// a shipped hall's shoulder 0.4 ms before its direct sound dips by 0.8 to 1.9 dB, packet to
// packet, and is climbed past as the response's own edge climbs past it; a studio's earlier
// arrival dips by 2.7 to 4.6 dB and counts as the response's does.
constexpr double kPeakDipDb = 3.0, kPeakDipRampDb = 1.0;
// The direct sound must also stand this far above the envelope's floor: the kFloorQuantile of
// its power over the search, which begins well before the sound arrived (the receivers look from
// far before the strongest arrival), so the quantile is noise and whatever of the room's sound
// the reference does not explain. A Rayleigh envelope's power has its 20th percentile at 0.22 of
// its mean and passes 19.5 dB over it (20 x its mean) once in about 10^9 samples.
constexpr double kFloorQuantile = 0.2;
constexpr double kAboveFloorDb = 19.5;
// A pulse whose largest sidelobe is above this share of its peak rings (ReadPulse's `ring`): nava's
// reference gives 0.4, the room chirp 0.2.
constexpr double kRingingSidelobe = 0.3;
// (The envelope is read on the sample grid: a 4.8 kHz band sampled at 11 kHz or more is smooth
// between samples, and the half-peak crossing interpolated linearly moves with a fractional
// delay to within a microsecond, as first_arrival_test checks.)
// A measured response is judged from kDirectBeforeStrongestS and the floor's lead before its
// largest sample to this far after it: enough margin that the band-pass has no edge effects.
constexpr double kResponseWindowS = 0.05;

double BandWeight(double f) {
  if (f <= kResponseBandLowHz || f >= kResponseBandHighHz) return 0.0;
  return 0.5 - 0.5 * std::cos(2.0 * M_PI * (f - kResponseBandLowHz) / (kResponseBandHighHz - kResponseBandLowHz));
}

// How far x has come from `from` (0) to `to` (1), held within [0, 1].
double Ramp(double x, double from, double to) { return std::clamp((x - from) / (to - from), 0.0, 1.0); }

// Decibels of a power ratio.
double PowerDb(double ratio) { return 10.0 * std::log10(ratio); }

// Whether the peak at p is under near[d] times the power d samples after it, for some d: what a
// later, stronger arrival's pulse has there on its own.
bool SidelobeOfALaterPeak(const std::vector<double>& power, std::size_t p, const std::vector<double>& near) {
  const std::size_t reach = std::min(near.size(), power.size() - p);
  for (std::size_t d = 1; d < reach; ++d) {
    if (power[p] < near[d] * power[p + d]) return true;
  }
  return false;
}

// How far (dB) the envelope falls after the peak at p before it first rises above it: +inf if it
// never does.
double DipDb(const std::vector<double>& power, std::size_t p) {
  double least = power[p];
  for (std::size_t k = p + 1; k < power.size(); ++k) {
    if (power[k] > power[p]) return least > 0.0 ? PowerDb(power[p] / least) : std::numeric_limits<double>::infinity();
    least = std::min(least, power[k]);
  }
  return std::numeric_limits<double>::infinity();
}

// Where the envelope, rising to the peak at p, first reaches half of it (in samples,
// interpolated on the envelope itself, not its square); 0 if it is above half from the start.
double EdgeBefore(const std::vector<double>& power, std::size_t p) {
  const double quarter = 0.25 * power[p];  // half the amplitude
  std::size_t j = p;
  while (j > 0 && power[j - 1] >= quarter) --j;
  if (j == 0) return 0.0;
  const double a = std::sqrt(power[j - 1]), b = std::sqrt(power[j]), half = std::sqrt(quarter);
  return static_cast<double>(j - 1) + (half - a) / (b - a);
}

// `power` is an envelope squared (no square roots for every lag). The direct sound is the first
// peak of the envelope within kDirectWithinDb (or `within`, an amplitude ratio) of its largest
// and above `floor` (a power), one the envelope falls from by kPeakDipDb before rising again, and
// not under `near`[d] times the power d samples after it (a power ratio: a later peak's
// sidelobe); the arrival is where the envelope rising to it first reaches half of it (in units
// of the envelope's samples, interpolated). NaN for an envelope that is zero everywhere.
//
// The dip is not a hard test: each peak before the largest counts by a score from 0 to 1 that
// ramps with its dip over kPeakDipRampDb, the edge is the scores' blend, peak by peak in time
// order (a peak counts with its score times what the earlier peaks left), and the largest takes
// what is left. A hard test jumps by the distance between two arrivals when noise moves a dip
// across it: two arrivals 0.4 ms apart, the first 10 dB under the second with a 3 dB dip between
// them, were one packet the direct sound and the next a shoulder climbed past (a studio, 344 us
// of jitter); with the blend the edge moves by a part of that distance for a part of a dB. (The
// floor and the sidelobe stay hard tests: ramped over 3 dB, the weak early arrivals of a car
// park and a kiln, a dB or two about the floor, spread the edge over a millisecond instead.)
double HalfPeakEdge(const std::vector<double>& power, double within = std::pow(10.0, -kDirectWithinDb / 20.0),
                    double floor = 0.0, const std::vector<double>& near = {}) {
  if (power.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto top = std::max_element(power.begin(), power.end());
  const double largest = *top;
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t last = static_cast<std::size_t>(top - power.begin());
  const double threshold = std::min(largest, std::max(floor, largest * within * within));
  double edge = 0.0, left = 1.0;
  for (std::size_t p = 0; p < last && left > 0.0; ++p) {
    const bool peak = (p == 0 || power[p] > power[p - 1]) && power[p] >= power[p + 1];
    if (!peak || power[p] < threshold) continue;
    if (SidelobeOfALaterPeak(power, p, near)) continue;
    const double score = Ramp(DipDb(power, p), kPeakDipDb - kPeakDipRampDb, kPeakDipDb);
    if (score <= 0.0) continue;
    edge += left * score * EdgeBefore(power, p);
    left *= 1.0 - score;
  }
  return edge + left * EdgeBefore(power, last);
}

// A moving average of `power` over `width` samples, centred (width 1: unchanged).
void Smooth(std::vector<double>& power, std::size_t width) {
  if (width <= 1 || power.empty()) return;
  std::vector<double> sum(power.size() + 1, 0.0);
  for (std::size_t i = 0; i < power.size(); ++i) sum[i + 1] = sum[i] + power[i];
  const std::size_t before = width / 2, after = width - before;
  for (std::size_t i = 0; i < power.size(); ++i) {
    const std::size_t lo = i > before ? i - before : 0, hi = std::min(power.size(), i + after);
    power[i] = (sum[hi] - sum[lo]) / static_cast<double>(hi - lo);
  }
}

// A pulse centred on lag 0 (a circular response of size n), its power smoothed over `width`:
// where its half-peak edge lies, in samples from lag 0 (negative: before it); its largest
// sidelobe over its peak (beyond the main lobe's first minima either side); by distance d from
// the peak, the largest sidelobe power at d or further, over the peak's (d up to where it falls
// under kDirectWithinDb); and how far from the peak the nearest other peak lies (a ringing's
// period; 0 if none).
struct Pulse {
  double rise = 0.0;
  double sidelobe = 0.0;
  std::vector<double> side_beyond;
  std::size_t ring = 0;
};
Pulse ReadPulse(const std::complex<double>* pulse, std::size_t n, std::size_t width) {
  const std::size_t half = n / 2;
  std::vector<double> env(n);
  for (std::size_t i = 0; i < n; ++i) env[i] = std::norm(pulse[(i + n - half) % n]);  // lags -half..half-1, squared
  Smooth(env, width);
  const std::size_t peak = static_cast<std::size_t>(std::max_element(env.begin(), env.end()) - env.begin());
  std::size_t lo = peak, hi = peak;
  while (lo > 0 && env[lo - 1] <= env[lo]) --lo;
  while (hi + 1 < n && env[hi + 1] <= env[hi]) ++hi;
  double side = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i < lo || i > hi) side = std::max(side, env[i]);
  }
  Pulse p;
  if (env[peak] > 0.0) {
    // Outwards from the far end: the largest sidelobe at each distance or beyond, either side.
    std::vector<double> beyond(half + 1, 0.0);
    for (std::size_t d = half; d-- > 0;) {
      double here = 0.0;
      if (peak >= d && (peak - d < lo)) here = std::max(here, env[peak - d]);
      if (peak + d < n && peak + d > hi) here = std::max(here, env[peak + d]);
      beyond[d] = std::max(beyond[d + 1], here / env[peak]);
    }
    const double least = std::pow(10.0, -kDirectWithinDb / 10.0);
    std::size_t reach = 1;
    while (reach < half && beyond[reach] >= least) ++reach;
    p.side_beyond.assign(beyond.begin(), beyond.begin() + static_cast<std::ptrdiff_t>(reach));
  }
  std::size_t next = hi;  // the next peak after the main lobe
  while (next + 1 < n && env[next + 1] >= env[next]) ++next;
  p.ring = next > hi ? next - peak : 0;
  p.sidelobe = env[peak] > 0.0 ? std::sqrt(side / env[peak]) : 0.0;
  p.rise = HalfPeakEdge(env, std::max(std::pow(10.0, -kDirectWithinDb / 20.0), std::min(0.9, kSidelobeMargin * p.sidelobe))) -
           static_cast<double>(half);
  return p;
}

}  // namespace

// The transforms of the window's size, planned once.
struct ArrivalTimer::Plans {
  explicit Plans(std::size_t n) : rx(FftKind::kRealToComplex, n), analytic(FftKind::kComplexBackward, n) {}
  FftPlan rx, analytic;
};

ArrivalTimer::ArrivalTimer(const std::vector<float>& reference, std::size_t count, double sample_rate)
    : rate_(sample_rate), count_(count), reference_length_(reference.size()) {
  if (reference.empty()) throw std::invalid_argument("first arrival: expected a reference sound, got none");
  if (count < reference.size()) {
    throw std::invalid_argument("first arrival: " + std::to_string(count) + " samples received, expected at least the reference's " +
                                std::to_string(reference.size()));
  }
  if (!(sample_rate >= 2.0 * kResponseBandHighHz) || !std::isfinite(sample_rate)) {
    throw std::invalid_argument("first arrival: sample rate " + std::to_string(sample_rate) + " Hz: expected at least " +
                                std::to_string(2.0 * kResponseBandHighHz));
  }
  // Linear, not circular, correlation at delays 0..count - reference.size().
  const std::size_t n = PowerOfTwoAtLeast(static_cast<double>(count + reference.size()));
  plans_ = std::make_unique<Plans>(n);
  FftPlan ref(FftKind::kRealToComplex, n);
  std::fill(ref.real_input(), ref.real_input() + n, 0.0);
  std::copy(reference.begin(), reference.end(), ref.real_input());
  ref.Execute();
  const std::size_t bins = n / 2 + 1;
  const double bin_hz = sample_rate / static_cast<double>(n);
  double strongest = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    if (BandWeight(static_cast<double>(k) * bin_hz) > 0.0) strongest = std::max(strongest, std::norm(ref.complex_output()[k]));
  }
  if (!(strongest > 0.0)) return;  // no reference in the band: every time is NaN
  const double floor = kRegularisation * strongest;
  // The division by the reference's spectrum, in the band, once; and two pulses on the same
  // grid: the band's own (what LeadingEdge reads a bare delay through) and the one a bare delay
  // gives through this reference (the band as the reference fills it).
  inverse_.assign(bins, std::complex<double>(0.0, 0.0));
  FftPlan band(FftKind::kComplexBackward, n), through(FftKind::kComplexBackward, n);
  std::complex<double>* zb = band.complex_input();
  std::complex<double>* zt = through.complex_input();
  std::fill(zb, zb + n, std::complex<double>(0.0, 0.0));
  std::fill(zt, zt + n, std::complex<double>(0.0, 0.0));
  for (std::size_t k = 0; k < bins; ++k) {
    const double w = BandWeight(static_cast<double>(k) * bin_hz);
    if (w == 0.0) continue;
    const std::complex<double> c = ref.complex_output()[k];
    inverse_[k] = w * std::conj(c) / (std::norm(c) + floor);
    zb[k] = w;
    zt[k] = w * std::norm(c) / (std::norm(c) + floor);
  }
  band.Execute();
  through.Execute();
  // A reference that fills only part of the band (nava's two tones) gives a wider pulse, whose
  // half-peak comes earlier before the arrival than the band's: its rise is taken out and the
  // band's put in, so that a bare delay arrives where LeadingEdge puts it, whatever the reference.
  Pulse own = ReadPulse(through.complex_output(), n, 1);
  // A reference whose pulse rings (nava's two tones beat at their difference), with its next
  // peak nearly as high as its main one, would have the edge jump by a period with the noise:
  // its envelope is read smoothed over that period.
  if (own.sidelobe > kRingingSidelobe && own.ring > 0) {
    smooth_ = own.ring;
    own = ReadPulse(through.complex_output(), n, smooth_);
  }
  rise_correction_ = ReadPulse(band.complex_output(), n, 1).rise - own.rise;
  within_ = std::max(std::pow(10.0, -kDirectWithinDb / 20.0), std::min(0.9, kSidelobeMargin * own.sidelobe));
  near_ = own.side_beyond;
  for (double& v : near_) v = std::min(0.81, kNearSidelobeMargin * kNearSidelobeMargin * v);
}

ArrivalTimer::~ArrivalTimer() = default;

void ArrivalTimer::Response(const ArrivalWindow& window, std::vector<std::complex<double>>& z) {
  Plans& p = *plans_;
  const std::size_t n = p.rx.size();
  std::fill(p.rx.real_input() + count_, p.rx.real_input() + n, 0.0);
  std::copy(window.samples, window.samples + count_, p.rx.real_input());
  p.rx.Execute();
  // Analytic: positive frequencies only. A sound `shift` samples later is moved back by a phase
  // ramp (a fraction of a sample as well as whole ones).
  z.assign(n, std::complex<double>(0.0, 0.0));
  const double turn = 2.0 * M_PI * window.shift / static_cast<double>(n);
  for (std::size_t k = 0; k < inverse_.size(); ++k) {
    z[k] = p.rx.complex_output()[k] * inverse_[k];
    if (window.shift != 0.0) z[k] *= std::polar(1.0, turn * static_cast<double>(k));
  }
}

void ArrivalTimer::Envelope(const std::vector<std::complex<double>>& z) {
  Plans& p = *plans_;
  std::copy(z.begin(), z.end(), p.analytic.complex_input());
  p.analytic.Execute();
  const std::size_t lags = count_ - reference_length_ + 1;
  power_.resize(lags);
  for (std::size_t i = 0; i < lags; ++i) power_[i] = std::norm(p.analytic.complex_output()[i]);
  Smooth(power_, smooth_);
}

double ArrivalTimer::Floor(std::size_t lead) {
  // Over the lead the caller knows to precede the sound, else over the whole search. Over the
  // whole search it was the room's own early response wherever fewer than a fifth of the delays
  // came before the direct sound: a hall whose reverberation peaks 40 ms after a direct sound
  // 25 dB under it (round a corner) had its direct sound under that floor, and its arrival read
  // at a reflection 1 to 37 ms late.
  const std::size_t span = lead > 0 && lead < power_.size() ? lead : power_.size();
  sorted_.assign(power_.begin(), power_.begin() + static_cast<std::ptrdiff_t>(span));
  const auto low = sorted_.begin() + static_cast<std::ptrdiff_t>(kFloorQuantile * static_cast<double>(span - 1));
  std::nth_element(sorted_.begin(), low, sorted_.end());
  return *low;
}

double ArrivalTimer::Arrival(std::size_t lead, double* clarity) {
  if (clarity) {
    sorted_ = power_;
    const auto mid = sorted_.begin() + static_cast<std::ptrdiff_t>(sorted_.size() / 2);
    std::nth_element(sorted_.begin(), mid, sorted_.end());
    const double largest = *std::max_element(power_.begin(), power_.end());
    *clarity = *mid > 0.0 ? std::sqrt(largest / *mid) : (largest > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  }
  const double floor = Floor(lead);
  return (HalfPeakEdge(power_, within_, floor * std::pow(10.0, kAboveFloorDb / 10.0), near_) + rise_correction_) / rate_;
}

double ArrivalTimer::Time(const float* received, double* clarity, std::size_t lead) {
  return Together({{received, 0.0, lead}}, clarity);
}

double ArrivalTimer::Together(const std::vector<ArrivalWindow>& windows, double* clarity) {
  if (windows.empty()) throw std::invalid_argument("first arrival: expected at least one window, got none");
  for (const ArrivalWindow& w : windows) {
    if (!w.samples) throw std::invalid_argument("first arrival: a window without samples");
  }
  if (clarity) *clarity = 0.0;
  if (inverse_.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (windows.size() == 1) {
    Response(windows[0], z_);
  } else {
    // Each response weighted by the inverse of its floor: the least noisy counts most. A window
    // of digital silence (floor 0) says nothing of the noise and is left out.
    sum_.assign(plans_->rx.size(), std::complex<double>(0.0, 0.0));
    double total = 0.0;
    for (const ArrivalWindow& w : windows) {
      Response(w, z_);
      Envelope(z_);
      const double floor = Floor(w.lead);
      if (!(floor > 0.0) || !std::isfinite(floor)) continue;
      for (std::size_t k = 0; k < sum_.size(); ++k) sum_[k] += z_[k] / floor;
      total += 1.0 / floor;
    }
    if (total > 0.0) {
      for (std::complex<double>& v : sum_) v /= total;
      z_.swap(sum_);
    } else {
      Response(windows[0], z_);
    }
  }
  Envelope(z_);
  return Arrival(windows[0].lead, clarity);
}

double FirstArrival(const float* received, std::size_t count, const std::vector<float>& reference, double sample_rate,
                    double* clarity) {
  ArrivalTimer timer(reference, count, sample_rate);
  return timer.Time(received, clarity);
}

double LeadingEdge(const std::vector<float>& response, double sample_rate) {
  if (response.empty()) throw std::invalid_argument("leading edge: expected a response, got none");
  std::size_t peak = 0;
  for (std::size_t k = 0; k < response.size(); ++k) {
    if (std::abs(response[k]) > std::abs(response[peak])) peak = k;
  }
  // The window, with the silence before the response's first sample where it reaches back
  // further (nothing arrives before a response begins, and the floor is read before the sound).
  const std::size_t lead = static_cast<std::size_t>(std::lround(kFloorLeadS * sample_rate));
  const std::size_t before = static_cast<std::size_t>(std::lround(kDirectBeforeStrongestS * sample_rate)) + lead;
  const std::size_t after = static_cast<std::size_t>(std::lround(kResponseWindowS * sample_rate));
  const std::size_t to = std::min(response.size(), peak + after + 1);
  std::vector<float> window(before > peak ? before - peak : 0, 0.0f);
  const double first = static_cast<double>(peak) - static_cast<double>(before);
  window.insert(window.end(), response.begin() + static_cast<std::ptrdiff_t>(peak > before ? peak - before : 0),
                response.begin() + static_cast<std::ptrdiff_t>(to));
  ArrivalTimer timer({1.0f}, window.size(), sample_rate);
  return first / sample_rate + timer.Time(window.data(), nullptr, lead);
}

}  // namespace nava_modem
