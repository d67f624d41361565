#include "nava_modem/room_receiver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "nava_modem/fft_plan.h"
#include "nava_modem/first_arrival.h"
#include "nava_modem/frame.h"
#include "nava_modem/hop_contrast.h"
#include "nava_modem/power_of_two.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_modulator.h"

namespace nava_modem {
namespace {

using namespace room_phy;

// The in-band level for carrier sense: the profile's band, smoothed over 10 ms.
constexpr double kLevelSeconds = 0.010;
constexpr double kBusyStepSeconds = 0.001;
// Busy air ends after a symbol's time of quiet; shorter stretches are clicks, not noise.
constexpr double kBusyRelease = kSymbolSeconds;
constexpr double kBusyMinimum = kSymbolSeconds;
// The envelope around each chirp's peak lined up to measure their distance: the direct sound
// and the early reflections, and lags up to a late reflection's delay either way.
constexpr double kAlignBefore = 0.010, kAlignAfter = 0.050, kAlignReach = 0.045;
// A chirp's missing partner is looked for where it must be: the strongest matched-filter
// output there counts when it is this many times the mean output before it. Far below the
// detector's own threshold: the window is narrow, and the CRC judges what is decoded.
constexpr double kSearchRatio = 4.0;
constexpr double kSearchBackground = 0.3, kSearchGuard = 0.02;
// A lone first chirp whose partner no matched filter output marks (in a room whose reverberation
// stands 15 dB or more over the direct sound for seconds, the second chirp's peak is one among
// many as tall) has it looked for by the data after it: the symbols are read at trial distances
// kScanStep apart across the clock tolerance, and the distance at which they stand out most in
// their sub-bands (HopContrast) is decoded, lined up with the lone chirp's envelope within a step.
// A step of 2 ms is at most 1 ms off: a symbol window 2.5 % of its length at the packet's end,
// the highest tone 3 Hz of its 25. Below kScanContrast the best trial is noise (16 equal tones in
// white noise give about 1.4 a trial, the best of a scan's up to about 1.7; packets heard at all
// give 2.5 or more) and nothing is decoded. Speech is tonal: most of its lone chirps pass, and
// each adds up to 2 * kScanDecoded CRC trials.
// The trials are judged first on every kScanStride-th symbol (21 of 42, spread over the packet,
// so a wrong clock still slides off them), and the best kScanFinalists at least kScanApart from
// each other again on all 42: about half the FFTs of judging every trial whole (speech's lone
// chirps, one every few seconds, each cost a scan). The contrast is broad, and where the
// reverberation rings on it has a second hump some 40 ms (a symbol) later, as high as the true
// one (windows late by up to a symbol still hear their own tone ring): the best kScanDecoded
// humps are decoded, best first.
constexpr double kScanStep = 0.002, kScanApart = 0.010;
constexpr double kScanContrast = 1.8;
constexpr int kScanStride = 2, kScanFinalists = 3, kScanDecoded = 2;
// A decoded packet's first arrival is looked for from kDirectBeforeStrongestS before its first
// chirp's strongest peak (the direct sound may precede a stronger reflection) to this long after
// it, with kFloorLeadS before that for the floor.
constexpr double kArrivalBefore = kDirectBeforeStrongestS + kFloorLeadS, kArrivalAfter = 0.010;

double Median(std::vector<double>& v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// How much a tone's energy, as a multiple of its noise floor, speaks for it. Logarithmic, so
// that one burst of speech or a click in a wrong tone cannot outvote the other symbols.
double Evidence(double ratio) { return std::log1p(ratio); }

}  // namespace

// One plan per symbol window length (the length follows the sender's clock), made when first
// needed.
struct RoomReceiver::Fft {
  FftPlan& Plan(int length) {
    auto it = plans.find(length);
    if (it == plans.end()) it = plans.emplace(length, FftPlan(FftKind::kRealToComplex, static_cast<std::size_t>(length))).first;
    return it->second;
  }
  std::map<int, FftPlan> plans;
};

RoomReceiver::RoomReceiver(const ModemOptions& modem, const ReceiverOptions& options)
    : modem_(modem),
      options_((ValidateReceiverOptions(options), options)),
      chirp_((ValidateRoomRate(modem.sample_rate), Chirp(modem.sample_rate))),
      detector_(chirp_, modem.sample_rate, ChirpDetectorOptions{}),
      arrival_timer_(chirp_, detector_.length() + static_cast<std::size_t>(std::lround((kArrivalBefore + kArrivalAfter) * modem.sample_rate)),
                     modem.sample_rate),
      level_(modem.sample_rate, kChirpLowHz - 100.0, kHighestHz + 600.0, kLevelSeconds),
      busy_(kBusyRelease, kBusyMinimum),
      packet_length_(kPostChirpStart * modem.sample_rate) {
  if (kHighestHz * (1.0 + MaxStretchError()) >= modem.sample_rate / 2.0) {
    throw std::invalid_argument("max_rate_error " + std::to_string(options_.max_rate_error) + ": a sender that fast would put " +
                                "the room profile's highest tone above the Nyquist frequency at " +
                                std::to_string(std::lround(modem.sample_rate)) + " Hz");
  }
  lookahead_ = std::llround((kAlignAfter + kAlignReach) * modem.sample_rate) + 1;
  const std::size_t size = PowerOfTwoAtLeast((kPacketSeconds * (1.0 + options_.max_rate_error) + 1.0) * modem.sample_rate +
                                             4.0 * detector_.length() + lookahead_);
  history_.assign(size, 0.0f);
  history_mask_ = size - 1;
  level_step_ = std::max<std::int64_t>(1, std::llround(kBusyStepSeconds * modem.sample_rate));
  fft_ = std::make_unique<Fft>();
  SetCarrierThreshold(options_.carrier_threshold_db);
}

RoomReceiver::~RoomReceiver() = default;

void RoomReceiver::SetMuted(bool muted) {
  if (muted && !muted_) {
    heard_.clear();
    pending_.clear();
    busy_.Reset();
  }
  muted_ = muted;
}

void RoomReceiver::Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  // In pieces shorter than the history's spare room, so that a packet found at the end of a
  // long call still has its samples.
  const std::size_t piece = static_cast<std::size_t>(0.1 * modem_.sample_rate);
  while (count > piece) {
    ProcessPiece(samples, piece, events);
    samples += piece;
    count -= piece;
  }
  ProcessPiece(samples, count, events);
}

void RoomReceiver::ProcessPiece(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  for (std::size_t k = 0; k < count; ++k) {
    history_[static_cast<std::size_t>(n_) & history_mask_] = samples[k];
    level_.Push(samples[k]);
    ++n_;
    if (++level_count_ == level_step_) {
      level_count_ = 0;
      // A frame may still come out of busy air until the detector has judged all of it.
      const bool judged = detector_.computed() >=
                          std::llround((busy_.last_loud() + kBusyRelease) * modem_.sample_rate) + lookahead_;
      if (!muted_) busy_.Step(time(), level_.power(), 0.0, !heard_.empty() || !pending_.empty() || !judged, events);
    }
  }
  peaks_.clear();
  detector_.Process(samples, count, peaks_);
  if (muted_) {
    // What began while we were sending or deaf is our own sound.
    detector_.Blank(n_);
    return;
  }
  pending_.insert(pending_.end(), peaks_.begin(), peaks_.end());
  while (!pending_.empty() && detector_.computed() >= static_cast<std::int64_t>(pending_.front().sample) + lookahead_) {
    OnChirp(pending_.front(), events);
    pending_.pop_front();
  }
  ExpireChirps(pending_.empty() ? detector_.computed() : static_cast<std::int64_t>(pending_.front().sample), events);
}

void RoomReceiver::Flush(std::vector<RxEvent>& events) {
  const std::vector<float> silence(static_cast<std::size_t>(modem_.sample_rate * (kPacketSeconds + 1.0)), 0.0f);
  Process(silence.data(), silence.size(), events);
}

void RoomReceiver::Emit(RxEvent packet, double post, std::vector<RxEvent>& events) {
  // The packet's chirps, their reflections and anything heard inside it begin nothing more.
  decoded_until_ = post + static_cast<double>(detector_.length());
  while (!heard_.empty() && heard_.front().peak.sample < decoded_until_) heard_.pop_front();
  events.push_back(std::move(packet));
  busy_.FrameFound();
}

void RoomReceiver::OnChirp(const ChirpPeak& peak, std::vector<RxEvent>& events) {
  ExpireChirps(static_cast<std::int64_t>(peak.sample), events);
  if (peak.sample < decoded_until_) return;
  const double shortest = packet_length_ * (1.0 - options_.max_rate_error);
  const double longest = packet_length_ * (1.0 + options_.max_rate_error);
  bool failed_post = false;
  for (auto it = heard_.begin(); it != heard_.end(); ++it) {
    const double d = peak.sample - it->peak.sample;
    if (d < shortest || d > longest) continue;
    RxEvent ev = Decode(it->peak, peak);
    if (ev.kind == RxEvent::Kind::kPacket) {
      Emit(std::move(ev), peak.sample, events);
      return;
    }
    if (!it->failure || ev.quality > it->failure->quality) it->failure = std::move(ev);
    failed_post = true;
  }
  if (!failed_post) {
    // No chirp heard where this one's partner would begin: the first chirp may have been too
    // faint for the detector on its own (a packet's second chirp, found over a reverberant
    // tail of data, is often the fainter). Look for it where it must be.
    if (const std::optional<ChirpPeak> pre = StrongestIn(std::max(decoded_until_, peak.sample - longest), peak.sample - shortest)) {
      RxEvent ev = Decode(*pre, peak);
      if (ev.kind == RxEvent::Kind::kPacket) {
        Emit(std::move(ev), peak.sample, events);
        return;
      }
    }
  }
  heard_.push_back({peak, failed_post, std::nullopt});
}

std::optional<ChirpPeak> RoomReceiver::StrongestIn(double from, double to) const {
  const std::int64_t first = std::max<std::int64_t>(0, std::llround(from)), last = std::llround(to);
  if (last <= first || last >= detector_.computed()) return std::nullopt;
  ChirpPeak best;
  for (std::int64_t n = first; n <= last; ++n) {
    const double p = detector_.Envelope(n);
    if (p > best.power) best = {static_cast<double>(n), 0.0, p};
  }
  // Against the filter's mean output before the window, as the detector judges.
  const std::int64_t guard = std::llround(kSearchGuard * modem_.sample_rate);
  const std::int64_t span = std::llround(kSearchBackground * modem_.sample_rate);
  double sum = 0.0;
  for (std::int64_t n = first - guard - span; n < first - guard; ++n) sum += detector_.Envelope(n);
  best.ratio = best.power / std::max(sum / static_cast<double>(span), 1e-20);
  if (best.ratio < kSearchRatio) return std::nullopt;
  return best;
}

void RoomReceiver::ExpireChirps(std::int64_t now, std::vector<RxEvent>& events) {
  const double shortest = packet_length_ * (1.0 - options_.max_rate_error);
  const double longest = packet_length_ * (1.0 + options_.max_rate_error);
  while (!heard_.empty() && heard_.front().peak.sample + longest < now) {
    const Heard& h = heard_.front();
    std::optional<ChirpPeak> post;
    if (!h.failure && !h.failed_post) post = StrongestIn(h.peak.sample + shortest, h.peak.sample + longest);
    if (post) {
      // The second chirp where it must be, too faint for the detector on its own.
      RxEvent ev = Decode(h.peak, *post);
      if (ev.kind == RxEvent::Kind::kPacket) {
        Emit(std::move(ev), post->sample, events);
        continue;
      }
    }
    if (!h.failed_post) {
      // No chirp stands out where its second chirp must be: the data between may still say
      // where it lies. (Not before it: a packet's first chirp comes out of the air before the
      // packet, not out of its own reverberant tail, and StrongestIn finds it where the second
      // chirp stood out.)
      if (std::optional<std::pair<RxEvent, double>> found = DecodeByData(h.peak)) {
        Emit(std::move(found->first), found->second, events);
        continue;
      }
    }
    if (h.failure) {
      events.push_back(*h.failure);
      busy_.FrameFound();
    } else if (!h.failed_post) {
      RxEvent ev;
      ev.kind = RxEvent::Kind::kNoise;
      ev.noise = RxEvent::Noise::kOneByte;
      ev.start = h.peak.sample / modem_.sample_rate;
      ev.end = (h.peak.sample + detector_.length()) / modem_.sample_rate;
      ev.level_db = 10.0 * std::log10(h.peak.power + 1e-20);
      ev.clarity = h.peak.ratio;
      events.push_back(ev);
      busy_.FrameFound();
    }
    heard_.pop_front();
  }
}

void RoomReceiver::SymbolEnergies(std::int64_t first, int length, double* energies) {
  FftPlan& plan = fft_->Plan(length);
  double* in = plan.real_input();
  for (int k = 0; k < length; ++k) in[k] = Sample(first + k);
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

std::vector<double> RoomReceiver::LinedUp(const ChirpPeak& anchor, double around, double reach_s, int picks) const {
  const double fs = modem_.sample_rate;
  const std::int64_t before = std::llround(kAlignBefore * fs), after = std::llround(kAlignAfter * fs);
  const std::int64_t reach = std::max<std::int64_t>(1, std::llround(reach_s * fs));
  const std::int64_t p = std::llround(anchor.sample), q = std::llround(around);
  std::vector<double> a(static_cast<std::size_t>(before + after));
  for (std::int64_t i = -before; i < after; ++i) a[static_cast<std::size_t>(i + before)] = std::sqrt(detector_.Envelope(p + i));
  std::vector<double> b(static_cast<std::size_t>(before + after + 2 * reach));
  for (std::int64_t i = -before - reach; i < after + reach; ++i) b[static_cast<std::size_t>(i + before + reach)] = std::sqrt(detector_.Envelope(q + i));
  std::vector<double> score(static_cast<std::size_t>(2 * reach + 1));
  for (std::size_t lag = 0; lag < score.size(); ++lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i + lag];
    score[lag] = sum;
  }
  // The best lag and the best one at least a millisecond from it (a reflection in one chirp
  // lined up with the direct sound in the other scores nearly as well), each to a fraction of
  // a sample.
  const std::int64_t apart = std::llround(0.001 * fs);
  std::vector<double> out;
  std::size_t first = score.size();
  for (int pick = 0; pick < picks; ++pick) {
    std::size_t best = score.size();
    for (std::size_t lag = 1; lag + 1 < score.size(); ++lag) {
      const bool local = score[lag] >= score[lag - 1] && score[lag] >= score[lag + 1];
      const bool far = first == score.size() || std::llabs(static_cast<std::int64_t>(lag) - static_cast<std::int64_t>(first)) >= apart;
      if (local && far && (best == score.size() || score[lag] > score[best])) best = lag;
    }
    if (best == score.size()) break;
    if (pick == 0) first = best;
    double refined = static_cast<double>(best);
    const double l = score[best - 1], c = score[best], r = score[best + 1];
    const double denom = l - 2.0 * c + r;
    if (denom < 0.0) refined += std::clamp(0.5 * (l - r) / denom, -0.5, 0.5);
    // The anchor's fractional part carries over: the lag is between whole samples.
    out.push_back(anchor.sample + static_cast<double>(q - p) + refined - static_cast<double>(reach));
  }
  return out;
}

std::vector<double> RoomReceiver::AlignedPosts(const ChirpPeak& pre, const ChirpPeak& post) const {
  std::vector<double> out = LinedUp(pre, post.sample, kAlignReach, 2);
  out.push_back(post.sample);
  return out;
}

std::optional<std::pair<RxEvent, double>> RoomReceiver::DecodeByData(const ChirpPeak& pre) {
  const double fs = modem_.sample_rate;
  const double shortest = packet_length_ * (1.0 - options_.max_rate_error);
  const double longest = packet_length_ * (1.0 + options_.max_rate_error);
  const double step = kScanStep * fs;
  // Every trial's samples must still be in the history, after the last packet decoded, and heard.
  const double oldest = std::max({0.0, decoded_until_, static_cast<double>(n_) - static_cast<double>(history_.size()) + 1.0});
  if (pre.sample < oldest) return std::nullopt;
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins);
  struct Trial {
    double contrast, distance;
    int index;  // of the trial, kScanStep apart
    bool operator>(const Trial& o) const { return contrast > o.contrast; }
  };
  const int apart_steps = static_cast<int>(std::lround(kScanApart / kScanStep));
  std::vector<Trial> trials;  // contrast on every kScanStride-th symbol
  int index = 0;
  for (double d = shortest; d <= longest; d += step, ++index) {
    if (pre.sample + d + static_cast<double>(detector_.length()) > static_cast<double>(n_)) continue;
    ReadSymbols(pre.sample, d / packet_length_, energy, kScanStride);
    const double contrast = HopContrast(energy, kScanStride);
    // (Audio that is not finite scores NaN, which no ordering can sort.)
    if (std::isfinite(contrast)) trials.push_back({contrast, d, index});
  }
  std::stable_sort(trials.begin(), trials.end(), std::greater<Trial>());
  std::vector<Trial> finalists;  // contrast on all symbols
  for (const Trial& t : trials) {
    if (finalists.size() == static_cast<std::size_t>(kScanFinalists)) break;
    const bool apart = std::none_of(finalists.begin(), finalists.end(), [&](const Trial& f) { return std::abs(f.index - t.index) < apart_steps; });
    if (!apart) continue;
    ReadSymbols(pre.sample, t.distance / packet_length_, energy, 1);
    const double contrast = HopContrast(energy);
    if (std::isfinite(contrast)) finalists.push_back({contrast, t.distance, t.index});
  }
  std::stable_sort(finalists.begin(), finalists.end(), std::greater<Trial>());
  for (std::size_t k = 0; k < finalists.size() && k < static_cast<std::size_t>(kScanDecoded); ++k) {
    if (finalists[k].contrast < kScanContrast) break;
    const double around = pre.sample + finalists[k].distance;
    std::vector<double> tries = LinedUp(pre, around, kScanStep, 1);
    tries.push_back(around);
    for (double at : tries) {
      const ChirpPeak post{at, 0.0, detector_.Envelope(std::llround(at))};
      // Timed by the first chirp alone: the second lies where the data put it, to a few
      // milliseconds, and is not heard above the room.
      RxEvent ev = DecodeWith(pre, post, at, false);
      if (ev.kind == RxEvent::Kind::kPacket) return std::make_pair(std::move(ev), at);
    }
  }
  return std::nullopt;
}

void RoomReceiver::ReadSymbols(double pre, double stretch, std::vector<double>& energy, int stride) {
  const double fs = modem_.sample_rate;
  const int length = static_cast<int>(std::lround(kSymbolSeconds * fs * stretch));
  for (int s = 0; s < kSymbols; s += stride) {
    const std::int64_t first = std::llround(pre + (kDataStart + s * kSymbolSeconds) * fs * stretch);
    SymbolEnergies(first, length, &energy[static_cast<std::size_t>(s) * kBins]);
  }
}

RxEvent RoomReceiver::Decode(const ChirpPeak& pre, const ChirpPeak& post) {
  std::optional<RxEvent> failed;
  for (double aligned : AlignedPosts(pre, post)) {
    RxEvent ev = DecodeWith(pre, post, aligned);
    if (ev.kind == RxEvent::Kind::kPacket) return ev;
    if (!failed || ev.quality > failed->quality) failed = std::move(ev);
  }
  return *failed;
}

RxEvent RoomReceiver::DecodeWith(const ChirpPeak& pre, const ChirpPeak& post, double aligned_post, bool post_heard) {
  const double fs = modem_.sample_rate;
  // The sender's durations over ours: symbol windows are this much longer, tones this much lower.
  const double stretch = (aligned_post - pre.sample) / packet_length_;
  if (std::abs(stretch - 1.0) > MaxStretchError()) {
    // Lined up beyond any clock we look for: not a packet's two chirps.
    RxEvent ev;
    ev.noise = RxEvent::Noise::kBadCrc;
    ev.start = pre.sample / fs;
    ev.end = (post.sample + detector_.length()) / fs;
    ev.level_db = 10.0 * std::log10(pre.power + 1e-20);
    return ev;
  }
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins);
  ReadSymbols(pre.sample, stretch, energy, 1);
  auto at = [&](int s, int b) -> double& { return energy[static_cast<std::size_t>(s) * kBins + b]; };
  auto active = [](int s, int b) { return b / kTonesPerBand == Band(s); };

  // Each tone's floor: its median over the symbols that did not use its sub-band.
  std::vector<double> floor(kBins), values;
  for (int b = 0; b < kBins; ++b) {
    values.clear();
    for (int s = 0; s < kSymbols; ++s) {
      if (!active(s, b)) values.push_back(at(s, b));
    }
    floor[b] = Median(values) + 1e-15;
  }
  room_code::SoftBits soft{};
  for (int s = 0; s < kSymbols; ++s) {
    // How loud this symbol's time was across the other sub-bands (speech comes and goes).
    values.clear();
    for (int b = 0; b < kBins; ++b) {
      if (!active(s, b)) values.push_back(at(s, b) / floor[b]);
    }
    const double loudness = std::max(1.0, Median(values));
    std::array<double, kTonesPerBand> e{};
    for (int m = 0; m < kTonesPerBand; ++m) {
      const int b = Bin(s, m) - kLowestBin;
      e[m] = Evidence(at(s, b) / (floor[b] * loudness));
    }
    for (int j = 0; j < kBitsPerSymbol; ++j) {
      const int mask = 1 << (kBitsPerSymbol - 1 - j);
      double one = 0.0, zero = 0.0;
      for (int m = 0; m < kTonesPerBand; ++m) {
        double& side = (room_code::ToneBits(m) & mask) ? one : zero;
        side = std::max(side, e[m]);
      }
      soft[static_cast<std::size_t>(s * kBitsPerSymbol + j)] = static_cast<float>(one - zero);
    }
  }
  const room_code::Decoded decoded = room_code::Decode(soft);

  RxEvent ev;
  ev.start = pre.sample / fs;
  ev.end = (post.sample + detector_.length()) / fs;
  double power = 0.0;
  const std::int64_t first = std::llround(pre.sample), last = std::llround(post.sample) + static_cast<std::int64_t>(detector_.length());
  for (std::int64_t n = first; n < last; ++n) power += 2.0 * Sample(n) * Sample(n);
  ev.level_db = 10.0 * std::log10(power / std::max<std::int64_t>(1, last - first) + 1e-20);
  ev.quality = 1.0 - static_cast<double>(decoded.corrected) / kCodedBits;
  ev.fixed_bits = decoded.corrected;
  ev.rate_error = 1.0 / stretch - 1.0;
  ev.clarity = std::min(pre.ratio, post.ratio);
  Frame frame{};
  frame[0] = kHeader;
  std::copy(decoded.payload.begin(), decoded.payload.end(), frame.begin() + 1);
  if (CrcMatches(frame, modem_.crc)) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.data.assign(frame.begin() + 1, frame.begin() + 1 + kDataBytes);
    if (options_.time_arrivals) ev.arrival = Arrival(pre.sample, post_heard ? std::optional<double>(aligned_post) : std::nullopt);
  } else {
    ev.kind = RxEvent::Kind::kNoise;
    ev.noise = RxEvent::Noise::kBadCrc;
  }
  return ev;
}

double RoomReceiver::Arrival(double pre, std::optional<double> post) {
  const double fs = modem_.sample_rate;
  const std::size_t count = arrival_timer_.count();
  // Each chirp's window, from kArrivalBefore before it (its samples, and where its chirp lies in
  // it); the second chirp lies where the decode put it, to a fraction of a sample, so the two
  // responses add up in phase.
  std::array<std::vector<float>, 2> heard;
  std::array<double, 2> from{}, at{};
  std::array<std::size_t, 2> lead{};
  const std::array<double, 2> chirps = {pre, post.value_or(0.0)};
  const std::size_t windows = post ? 2 : 1;
  for (std::size_t w = 0; w < windows; ++w) {
    const double start = std::floor(chirps[w] - kArrivalBefore * fs);
    const std::int64_t first = std::max<std::int64_t>(0, static_cast<std::int64_t>(start));
    heard[w].resize(count);
    // (Nothing past what has been heard: a packet decoded at the stream's end.)
    for (std::size_t k = 0; k < count; ++k) {
      const std::int64_t n = first + static_cast<std::int64_t>(k);
      heard[w][k] = n < n_ ? Sample(n) : 0.0f;
    }
    from[w] = static_cast<double>(first);
    at[w] = chirps[w] - from[w];
    // Near the stream's start a window begins later: its lead is what is left, and with less
    // than a quarter of it left its floor is read over the whole search.
    const double left = std::round(kFloorLeadS * fs - (from[w] - start));
    lead[w] = left >= 0.25 * kFloorLeadS * fs ? static_cast<std::size_t>(left) : 0;
  }
  if (!post) return from[0] / fs + arrival_timer_.Together({{heard[0].data(), 0.0, lead[0]}});
  return from[0] / fs + arrival_timer_.Together({{heard[0].data(), 0.0, lead[0]}, {heard[1].data(), at[1] - at[0], lead[1]}});
}

}  // namespace nava_modem
