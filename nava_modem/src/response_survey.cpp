#include "nava_modem/response_survey.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <memory>
#include <random>

#include "nava_modem/fft_plan.h"
#include "nava_modem/math_constants.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/parabola.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

using Spectrum = std::vector<std::complex<double>>;
// Lags before the packets, held as unknowns to measure the estimate's noise on.
constexpr double kQuietLagsS = 1.0;
// How long after a packet heard but not decoded its sound is left out of the fit, s.
constexpr double kUndecodedTailS = 0.3;
// The most rounds of placing the packets and timing their clocks (see ClockByResponse), and the
// change of a packet's length, samples, under which a clock already taken from the recording is
// left as it is.
constexpr int kTimingRounds = 3;
constexpr double kSettledSamples = 0.1;
// A packet's clock is taken from the recording instead of the receiver's rate_error only where
// the two disagree by this much over the packet's length, samples: a misjudged clock was seen
// 6.5 samples off, while in the long rooms (RT60 2-2.7 s) the halves' lags wander by less, and
// following them there read the RT60 10-15 % long (two warehouses, a car park).
constexpr double kClockMismatchSamples = 3.0;

std::unique_ptr<ModemProfile> RoomProfile(double sample_rate) {
  ModemOptions modem;
  modem.sample_rate = sample_rate;
  try {
    return MakeProfile(Profile::kRoom, modem);
  } catch (const std::invalid_argument& e) {
    throw SurveyError(std::string(e.what()) + " (a survey listens for room packets)");
  }
}

void ValidateSurveyOptions(const SurveyOptions& o) {
  const auto check = [](const char* field, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) {
      throw std::invalid_argument(std::string(field) + " " + std::to_string(v) + ": expected " + std::to_string(lo) +
                                  " to " + std::to_string(hi));
    }
  };
  check("lead_s", o.lead_s, 0.0, 1.0);
  check("search_s", o.search_s, 0.001, 0.5);
  check("regularisation", o.regularisation, 1e-9, 1e3);
  check("max_response_s", o.max_response_s, 0.1, 60.0);
  check("iterations", o.iterations, 0, 10000);
}

// The largest length up to `n` whose only prime factors are 2, 3, 5 and 7 (FFTW is fast on those).
std::size_t SmoothSizeWithin(std::size_t n) {
  const auto smooth = [](std::size_t m) {
    for (std::size_t p : {2, 3, 5, 7}) {
      while (m % p == 0) m /= p;
    }
    return m == 1;
  };
  while (n > 1 && !smooth(n)) --n;
  return n;
}

// Mean square per sample of the bins [lo, hi) Hz of an n-point spectrum, over `samples` samples.
double BandPower(const Spectrum& s, std::size_t n, double sample_rate, double lo, double hi, std::size_t samples) {
  double sum = 0.0;
  for (std::size_t k = 1; k < s.size(); ++k) {
    const double hz = BinHz(k, n, sample_rate);
    if (hz >= lo && hz < hi) sum += std::norm(s[k]);
  }
  return 2.0 * sum / (static_cast<double>(n) * static_cast<double>(std::max<std::size_t>(1, samples)));
}

double FlooredDb(double power) { return 10.0 * std::log10(std::max(power, 1e-30)); }

// The lag (fractional) within `reach` of 0 at which the circular sequence `c` is largest.
double PeakLag(const std::vector<double>& c, std::size_t reach) {
  const std::size_t n = c.size();
  const auto at = [&](long lag) { return c[static_cast<std::size_t>((lag % static_cast<long>(n) + static_cast<long>(n)) % static_cast<long>(n))]; };
  long best = 0;
  for (long lag = -static_cast<long>(reach); lag <= static_cast<long>(reach); ++lag) {
    if (at(lag) > at(best)) best = lag;
  }
  return static_cast<double>(best) + ParabolaOffset(at(best - 1), at(best), at(best + 1));
}

// The packet as sent (`modulated`, at the sender's clock), at our clock: the sender's clock ran
// 1 + rate_error times ours.
std::vector<float> AtOurClock(const std::vector<float>& modulated, double rate_error) {
  return std::abs(rate_error) > 1e-9 ? Resample(modulated, 1.0 / (1.0 + rate_error)) : modulated;
}

// The n-point spectrum of `sent` starting `place` samples into a period of n (a fraction of a
// sample by a phase ramp; circularly).
Spectrum Placed(const std::vector<float>& sent, double place, std::size_t n) {
  Spectrum s = ForwardFft(std::vector<double>(sent.begin(), sent.end()), n);
  for (std::size_t k = 0; k < s.size(); ++k) {
    s[k] *= std::polar(1.0, -2.0 * kPi * static_cast<double>(k) * place / static_cast<double>(n));
  }
  return s;
}

// Forward and backward transforms of one size, planned once: the least squares runs hundreds.
class Transforms {
 public:
  explicit Transforms(std::size_t n) : forward_(FftKind::kRealToComplex, n), backward_(FftKind::kComplexToReal, n) {}
  std::size_t size() const { return forward_.size(); }
  Spectrum Forward(const std::vector<double>& x) {
    std::copy(x.begin(), x.end(), forward_.real_input());
    forward_.Execute();
    return Spectrum(forward_.complex_output(), forward_.complex_output() + forward_.output_length());
  }
  // Scaled by 1/n, so that Backward(Forward(x)) == x.
  std::vector<double> Backward(const Spectrum& s) {
    std::copy(s.begin(), s.end(), backward_.complex_input());
    backward_.Execute();
    std::vector<double> x(backward_.real_output(), backward_.real_output() + size());
    for (double& v : x) v /= static_cast<double>(size());
    return x;
  }

 private:
  FftPlan forward_, backward_;
};

// The sent packets and where each one's first sample lies in the recording (less the lead, so
// that the response's strongest path comes out `lead` samples in).
struct Train {
  std::vector<std::vector<float>> modulated;  // each packet at the sender's clock
  std::vector<double> rate_error;             // each packet's sender's clock over ours, minus 1
  std::vector<bool> timed;                    // whether its clock was taken from the recording
  std::vector<std::vector<float>> sent;       // each packet at our clock
  std::vector<double> place;
  Spectrum Total(std::size_t n) const {
    Spectrum x(n / 2 + 1);
    for (std::size_t i = 0; i < sent.size(); ++i) {
      const Spectrum s = Placed(sent[i], place[i], n);
      for (std::size_t k = 0; k < x.size(); ++k) x[k] += s[k];
    }
    return x;
  }
};

// The first placing: each packet where its decode put it, all moved together so that the
// strongest path of the packet heard loudest (its matched filter's peak within `reach` of
// where its decode put it) lands at `lead`.
void PlaceByDecode(Train& train, const std::vector<SurveyPacket>& packets, const std::vector<float>& recording,
                   double sample_rate, std::size_t lead, std::size_t reach) {
  double loudest = -1.0, offset = 0.0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    const double decoded = packets[i].start_s * sample_rate;
    const std::size_t first = static_cast<std::size_t>(std::clamp(decoded - static_cast<double>(reach), 0.0,
                                                                  static_cast<double>(recording.size())));
    const std::size_t end = std::min(recording.size(), first + 2 * reach + 1 + train.sent[i].size());
    const std::vector<double> piece(recording.begin() + static_cast<std::ptrdiff_t>(first),
                                    recording.begin() + static_cast<std::ptrdiff_t>(end));
    const std::size_t m = FftSize(piece.size() + train.sent[i].size());
    Spectrum a = ForwardFft(piece, m);
    const Spectrum b = ForwardFft(std::vector<double>(train.sent[i].begin(), train.sent[i].end()), m);
    for (std::size_t k = 0; k < a.size(); ++k) a[k] *= std::conj(b[k]);
    std::vector<double> c = InverseFft(a, m);
    for (double& v : c) v = std::abs(v);
    c.resize(2 * reach + 1);
    const std::size_t lag = static_cast<std::size_t>(std::max_element(c.begin(), c.end()) - c.begin());
    if (c[lag] > loudest) {
      loudest = c[lag];
      const double peak = static_cast<double>(lag) +
                          (lag > 0 && lag + 1 < c.size() ? ParabolaOffset(c[lag - 1], c[lag], c[lag + 1]) : 0.0);
      offset = static_cast<double>(first) + peak - decoded;
    }
  }
  for (std::size_t i = 0; i < packets.size(); ++i) {
    train.place.push_back(packets[i].start_s * sample_rate + offset - static_cast<double>(lead));
  }
}

// Moves each packet to where what it must have sounded like (the packet through the response
// `h`) best matches the recording, within `reach`. A decode's start can be samples off in a
// loud room (the chirp's peak moves between the direct sound and a reflection), which would
// smear the estimate; the whole packet through the whole response cannot be.
void PlaceByResponse(Train& train, const Spectrum& y, const Spectrum& h, std::size_t n, std::size_t reach) {
  for (std::size_t i = 0; i < train.sent.size(); ++i) {
    const Spectrum s = Placed(train.sent[i], train.place[i], n);
    Spectrum c(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) c[k] = y[k] * std::conj(s[k] * h[k]);
    train.place[i] += PeakLag(InverseFft(c, n), reach);
  }
}

// Times each packet's clock by the recording: the packet's first and second halves, each through
// the response `h`, are matched with the recording apart; a clock misjudged by e stretches the
// packet by e x its length, so the halves' best lags differ by that over half of it. The
// receiver's rate_error can be tens of ppm off for a packet (seen: 7e-5 where the sender's
// clock was exact, a drift of 6 samples over the packet); that packet then fits the recording
// nowhere well, and its misfit spreads the direct sound over the lags around it (a skirt 25 dB
// under the direct sound, 10 ms either side), which in a dry room outweighs the reverberation.
// Only a clock off by more than kClockMismatchSamples over the packet is corrected, and then
// refined in later rounds. Returns the largest correction of a packet's length, samples (0: none
// made).
double ClockByResponse(Train& train, const Spectrum& y, const Spectrum& h, std::size_t n, std::size_t reach) {
  double largest = 0.0;
  for (std::size_t i = 0; i < train.sent.size(); ++i) {
    const std::vector<float>& sent = train.sent[i];
    const std::size_t half = sent.size() / 2;
    const auto lag_of = [&](std::size_t from, std::size_t to) {
      std::vector<float> part(sent.size(), 0.0f);
      std::copy(sent.begin() + static_cast<std::ptrdiff_t>(from), sent.begin() + static_cast<std::ptrdiff_t>(to),
                part.begin() + static_cast<std::ptrdiff_t>(from));
      const Spectrum s = Placed(part, train.place[i], n);
      Spectrum c(s.size());
      for (std::size_t k = 0; k < s.size(); ++k) c[k] = y[k] * std::conj(s[k] * h[k]);
      return PeakLag(InverseFft(c, n), reach);
    };
    if (half < 2) continue;
    const double drift = lag_of(half, sent.size()) - lag_of(0, half);  // samples over `half`
    // The receiver's clock holds unless the recording disagrees clearly; once overridden, the
    // packet's clock follows the recording to a tenth of a sample.
    if (!(std::abs(drift) * 2.0 > (train.timed[i] ? kSettledSamples : kClockMismatchSamples))) continue;
    const double stretch = 1.0 + drift / static_cast<double>(half);
    if (!(stretch > 0.5 && stretch < 2.0)) continue;  // no clock runs so far off: a mismatch
    train.rate_error[i] = (1.0 + train.rate_error[i]) / stretch - 1.0;
    train.timed[i] = true;
    train.sent[i] = AtOurClock(train.modulated[i], train.rate_error[i]);
    largest = std::max(largest, std::abs(drift) * 2.0);
  }
  return largest;
}

// Per frequency, the regularised quotient of the recording by the sent train, in the band.
Spectrum Quotient(const Spectrum& y, const Spectrum& x, const std::vector<bool>& band, double lambda) {
  Spectrum h(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (band[k]) h[k] = y[k] * std::conj(x[k]) / (std::norm(x[k]) + lambda);
  }
  return h;
}

// Least squares for the response on the lags where `on_support` holds, from `h` on, over the
// samples of the recording where `heeded` holds (a packet heard but not decoded is sound the
// sent train cannot explain, so its samples are left out): conjugate gradients on the normal
// equations with Tikhonov weight `lambda` (as in Quotient), in the band, preconditioned by the
// quotient's own division (each bin of a step divided by |x|^2 + lambda, on the support). The
// normal equations are that division but for the support and the samples left out, so the
// preconditioned steps converge in a few iterations where the plain ones crawl along the
// train's spectral dips: plain, 20 iterations left a warehouse's late tail (RT60 2.65 s) too
// strong, its RT60 read 12-17 % long, 100 iterations 2-4 %. Returns the residual: the heeded
// samples' part of the recording, in the band, that the fit leaves.
std::vector<double> LeastSquares(std::vector<double>& h, const Spectrum& y, const Spectrum& x,
                                 const std::vector<bool>& band, const std::vector<bool>& heeded, double lambda,
                                 const std::function<bool(std::size_t)>& on_support, int iterations,
                                 Transforms& fft) {
  const std::size_t n = h.size();
  const auto convolve = [&](const std::vector<double>& lags) {  // x * lags, on the heeded samples
    Spectrum f = fft.Forward(lags);
    for (std::size_t k = 0; k < f.size(); ++k) f[k] = band[k] ? f[k] * x[k] : 0.0;
    std::vector<double> t = fft.Backward(f);
    for (std::size_t k = 0; k < n; ++k) t[k] = heeded[k] ? t[k] : 0.0;
    return t;
  };
  // Parseval: sum_k |H_k|^2 = n ||h||^2, so the quotient's weight per bin is this weight per lag.
  const double mu = lambda;
  const auto gradient = [&](const std::vector<double>& r) {  // x correlated with r, on the support, less mu h
    Spectrum g = fft.Forward(r);
    for (std::size_t k = 0; k < g.size(); ++k) g[k] = band[k] ? std::conj(x[k]) * g[k] : 0.0;
    std::vector<double> v = fft.Backward(g);
    for (std::size_t k = 0; k < n; ++k) v[k] = on_support(k) ? v[k] - mu * h[k] : 0.0;
    return v;
  };
  std::vector<double> divisor(x.size());  // the quotient's, bin by bin
  for (std::size_t k = 0; k < x.size(); ++k) divisor[k] = (band[k] ? std::norm(x[k]) : 0.0) + mu;
  const auto precondition = [&](const std::vector<double>& g) {  // g divided bin by bin, on the support
    Spectrum f = fft.Forward(g);
    for (std::size_t k = 0; k < f.size(); ++k) f[k] /= divisor[k];
    std::vector<double> v = fft.Backward(f);
    for (std::size_t k = 0; k < n; ++k) v[k] = on_support(k) ? v[k] : 0.0;
    return v;
  };
  const auto dot = [](const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] * b[k];
    return sum;
  };
  Spectrum yb(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) yb[k] = band[k] ? y[k] : 0.0;
  std::vector<double> residual = fft.Backward(yb);
  const std::vector<double> fitted = convolve(h);
  for (std::size_t k = 0; k < n; ++k) residual[k] = heeded[k] ? residual[k] - fitted[k] : 0.0;
  std::vector<double> grad = gradient(residual);
  std::vector<double> dir = precondition(grad);
  double gamma = dot(grad, dir);
  for (int it = 0; it < iterations && gamma > 0.0; ++it) {
    const std::vector<double> q = convolve(dir);
    const double curvature = dot(q, q) + mu * dot(dir, dir);  // ||x * dir||^2 + mu ||dir||^2
    if (!(curvature > 0.0)) break;
    const double alpha = gamma / curvature;
    for (std::size_t k = 0; k < n; ++k) h[k] += alpha * dir[k];
    for (std::size_t k = 0; k < n; ++k) residual[k] -= alpha * q[k];
    grad = gradient(residual);
    const std::vector<double> z = precondition(grad);
    const double next = dot(grad, z);
    for (std::size_t k = 0; k < n; ++k) dir[k] = z[k] + (next / gamma) * dir[k];
    gamma = next;
  }
  return residual;
}

}  // namespace

std::vector<float> SurveyTrain(double sample_rate, int count, double gap, unsigned seed) {
  if (count < 1 || !(gap >= 0.0)) {
    throw std::invalid_argument("survey train of " + std::to_string(count) + " packets " + std::to_string(gap) +
                                " s apart: expected at least one packet and a gap of 0 s or more");
  }
  ModemOptions modem;
  modem.sample_rate = sample_rate;
  const std::unique_ptr<ModemProfile> profile = MakeProfile(Profile::kRoom, modem);
  std::mt19937 rng(seed);
  // Each gap drawn from 0.5 to 1.5 times `gap`: packets at a fixed period would repeat their
  // chirps at that period, and the estimate could not tell a tap from one a period later as well.
  std::uniform_real_distribution<double> spread(0.5, 1.5);
  const auto silence = [&] { return static_cast<std::size_t>(std::lround(gap * spread(rng) * sample_rate)); };
  std::vector<float> out(silence(), 0.0f);
  for (int p = 0; p < count; ++p) {
    std::vector<std::uint8_t> data(4);
    for (auto& b : data) b = static_cast<std::uint8_t>(rng() & 0xFF);
    const std::vector<float> packet = profile->ModulatePacket(data);
    out.insert(out.end(), packet.begin(), packet.end());
    out.resize(out.size() + silence(), 0.0f);
  }
  return out;
}

SurveyHeard FindSurveyPackets(const std::vector<float>& recording, double sample_rate) {
  const std::unique_ptr<ModemProfile> profile = RoomProfile(sample_rate);
  ReceiverOptions rx;
  rx.time_arrivals = false;
  const std::unique_ptr<PacketReceiver> receiver = profile->MakeReceiver(rx);
  std::vector<RxEvent> events;
  receiver->Process(recording.data(), recording.size(), events);
  receiver->Flush(events);
  SurveyHeard heard;
  for (const RxEvent& e : events) {
    if (e.kind == RxEvent::Kind::kPacket) {
      heard.packets.push_back(SurveyPacket{e.data, e.start, e.rate_error});
    } else if (e.noise == RxEvent::Noise::kOneByte || e.noise == RxEvent::Noise::kBadCrc) {
      heard.undecoded_s.push_back(e.start);
    }
  }
  return heard;
}

SurveyResult SurveyResponse(const std::vector<float>& recording, double sample_rate, const SurveyHeard& heard,
                            const SurveyOptions& options) {
  ValidateSurveyOptions(options);
  const std::vector<SurveyPacket>& packets = heard.packets;
  if (packets.empty()) throw SurveyError("no room packet decoded: expected at least one to survey the room from");
  const std::unique_ptr<ModemProfile> profile = RoomProfile(sample_rate);
  const auto samples = [&](double s) { return static_cast<std::size_t>(std::lround(s * sample_rate)); };
  const std::size_t lead = samples(options.lead_s), reach = samples(options.search_s);
  // The whole recording is one period of a circular convolution (cut by at most a few ms to a
  // length FFTW is fast on): then the recording's noise lies under every lag of the estimate
  // alike, and lags before the packets measure the estimate's noise floor. (Zero-padding instead
  // would leave less noise at the lags far from the packets than near them.) The cost is that
  // the reverberation cut off by the recording's end is not found at its start; a recording that
  // goes on a while after the last packet keeps that small.
  const std::size_t n = SmoothSizeWithin(recording.size());
  const std::size_t window = std::min(lead + samples(options.max_response_s), n / 2);
  const std::size_t quiet = std::min(samples(kQuietLagsS), n - window);
  if (n < samples(2.0 * room_phy::kPacketSeconds) || window < lead + samples(kMinTailS) || quiet < samples(0.1)) {
    throw SurveyError("recording of " + std::to_string(static_cast<double>(recording.size()) / sample_rate) +
                      " s: too short to survey from, expected at least " +
                      std::to_string(2.0 * room_phy::kPacketSeconds) + " s");
  }
  const Spectrum y =
      ForwardFft(std::vector<double>(recording.begin(), recording.begin() + static_cast<std::ptrdiff_t>(n)), n);
  std::vector<bool> band(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double hz = BinHz(k, n, sample_rate);
    band[k] = hz >= kResponseBandLowHz && hz <= kResponseBandHighHz;
  }

  // The samples a packet heard but not decoded sounds in (its chirp, data and chirp, and a
  // little of its reverberation) are left out of the fit.
  std::vector<bool> heeded(n, true);
  for (double start : heard.undecoded_s) {
    const double from = start * sample_rate - static_cast<double>(reach);
    const double to = (start + room_phy::kPacketSeconds + kUndecodedTailS) * sample_rate;
    for (double k = std::max(0.0, std::ceil(from)); k < std::min(static_cast<double>(n), to); k += 1.0) {
      heeded[static_cast<std::size_t>(k)] = false;
    }
  }
  const std::size_t heeded_samples = static_cast<std::size_t>(std::count(heeded.begin(), heeded.end(), true));
  Transforms fft(n);

  Train train;
  for (const SurveyPacket& p : packets) {
    train.modulated.push_back(profile->ModulatePacket(p.data));
    train.rate_error.push_back(p.rate_error);
    train.timed.push_back(false);
    train.sent.push_back(AtOurClock(train.modulated.back(), p.rate_error));
  }
  PlaceByDecode(train, packets, recording, sample_rate, lead, reach);
  const auto weight = [&](const Spectrum& x) {  // lambda: `regularisation` x the band's mean |X|^2
    double sum = 0.0, bins = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (band[k]) sum += std::norm(x[k]), bins += 1.0;
    }
    return options.regularisation * sum / std::max(1.0, bins);
  };
  // Each packet placed and its clock timed through a first estimate of the response, then again
  // through one from the packets so placed (a packet whose clock was misjudged smears the first
  // estimate, though the others hold it up), until no packet's clock is corrected.
  Spectrum x = train.Total(n);
  for (int round = 0; round < kTimingRounds; ++round) {
    const Spectrum first = Quotient(y, x, band, weight(x));
    PlaceByResponse(train, y, first, n, reach);
    const double moved = ClockByResponse(train, y, first, n, reach);
    if (moved > 0.0) PlaceByResponse(train, y, first, n, reach);
    x = train.Total(n);
    if (moved == 0.0) break;
  }
  const double lambda = weight(x);

  // The unknowns: the response's `window` lags, and `quiet` lags before the packets were sent
  // (more than `lead` before the direct sound), which hold the estimate's noise alone. The
  // quotient alone cannot use that a response is short (so its spectrum is smooth): it lets
  // noise through wherever the train's spectrum dips, and a train that repeats the same chirps
  // has a spectrum like a comb. Least squares on the lags fills the dips from the frequencies
  // around them.
  const auto on_support = [&](std::size_t k) { return k < window || k >= n - quiet; };
  std::vector<double> h = InverseFft(Quotient(y, x, band, lambda), n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!on_support(k)) h[k] = 0.0;
  }
  const std::vector<double> residual =
      LeastSquares(h, y, x, band, heeded, lambda, on_support, options.iterations, fft);

  SurveyResult result;
  result.packets = packets;
  for (std::size_t i = 0; i < packets.size(); ++i) result.packets[i].rate_error = train.rate_error[i];
  result.undecoded = heard.undecoded_s.size();
  result.response.assign(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(window));
  result.response_noise_power =
      InBandPower(std::vector<float>(h.end() - static_cast<std::ptrdiff_t>(quiet), h.end()), sample_rate);
  result.figures = MeasureResponseOverNoise(result.response, result.response_noise_power, sample_rate);

  // What the packets through that response do not explain is the room's noise. The fit's free
  // lags took their share of it, which is given back.
  const double kept = static_cast<double>(heeded_samples) /
                      std::max(1.0, static_cast<double>(heeded_samples) - static_cast<double>(window + quiet));
  const Spectrum left = fft.Forward(residual);
  const auto noise_db = [&](double lo, double hi) { return FlooredDb(kept * BandPower(left, n, sample_rate, lo, hi, heeded_samples)); };
  result.noise_db = noise_db(kResponseBandLowHz, kResponseBandHighHz);
  for (int b = 0; b < kSurveyBands; ++b) {
    const double lo = room_phy::kLowestToneHz + b * room_phy::kTonesPerBand * room_phy::kToneSpacingHz;
    result.band_noise_db[static_cast<std::size_t>(b)] = noise_db(lo, lo + room_phy::kTonesPerBand * room_phy::kToneSpacingHz);
  }
  Spectrum sounded = fft.Forward(h);
  for (std::size_t k = 0; k < sounded.size(); ++k) sounded[k] = band[k] ? sounded[k] * x[k] : 0.0;
  double sent_power = 0.0;
  std::size_t sent_samples = 0;
  for (const std::vector<float>& s : train.sent) {
    for (float v : s) sent_power += static_cast<double>(v) * v;
    sent_samples += s.size();
  }
  sent_power /= static_cast<double>(std::max<std::size_t>(1, sent_samples));
  result.signal_db = FlooredDb(BandPower(sounded, n, sample_rate, kResponseBandLowHz, kResponseBandHighHz, sent_samples));
  // The direct sound's share: the sent power through the response's direct window alone. The
  // estimate holds the band only, so its direct energy is the band's share of the whole (a
  // direct sound spreads over every frequency, the packets over the band).
  const std::size_t peak = result.figures.peak;
  const std::size_t half = samples(kDirectHalfWidthS);
  double direct = 0.0;
  for (std::size_t k = peak >= half ? peak - half : 0; k < std::min(window, peak + half + 1); ++k) {
    direct += result.response[k] * result.response[k];
  }
  const double band_share = (kResponseBandHighHz - kResponseBandLowHz) / (sample_rate / 2.0);
  result.direct_db =
      FlooredDb(sent_power * std::max(0.0, direct - static_cast<double>(2 * half + 1) * result.response_noise_power) / band_share);
  return result;
}

}  // namespace nava_modem
