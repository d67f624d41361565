#include "nava_modem/fsk_equalizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;
// The taps: each filter sees its own tone from kEarly bits early (the bit clock a little late)
// to kLate bits late (the early reflections reach 40 ms, 12 bits; the diffuse tail's first
// 8 bits after them still help in rooms with RT60 0.5 s); the other tone only through its
// sidelobes, from the bits around the present one.
constexpr int kEarly = 1, kLate = 20, kCrossLate = 2;
static_assert(kEarly == 1, "the search's cost takes the bit being decided as the only one kEarly ahead");
constexpr int kOwnTaps = kEarly + kLate + 1;
constexpr int kCrossTaps = kEarly + kCrossLate + 1;
constexpr int kTaps = kOwnTaps + kCrossTaps;
// The Viterbi search's state: the last few bits; older ones come from each survivor's path.
constexpr int kStateBits = 4;
constexpr int kStates = 1 << kStateBits;
constexpr int kBreakBits = kBreakSpaceBits + kBreakMarkBits;
// A bit no competitor path ever challenged is this sure (log-likelihood ratio).
constexpr float kMaxSoft = 60.0f;
// Ridge on the least squares, relative to the mean diagonal: keeps taps that the bits do not
// excite (a late tap of a tone the packet rarely holds long) from fitting noise. The first fit
// has only the break and the header (50 observations, nearly collinear through the break's
// steady tones) for its 26 taps per filter and needs more: with 1e-3 it overfitted them and
// gave up on most packets of measured rooms at DRR 0 to +2 dB (a teaching room, 0.56 s);
// 0.05 and 0.01 read about a tenth more of them and lose none elsewhere.
constexpr double kFirstRidge = 0.05;
constexpr double kRidge = 0.01;
// The sender's clock offset is searched this far either side of the bit clock's estimate,
// coarse then finer (a 1e-4 error turns the SPACE filter's phase by 0.4 rad over a packet).
constexpr double kOffsetSpan = 0.003;
constexpr double kOffsetSteps[] = {0.0005, 0.0001, 0.00002};
constexpr int kPasses = 4;
// Start and stop bits (of 14) a first pass may get wrong and still be refitted.
constexpr int kMaxMisframedFirst = 3;

using Matrix = Eigen::Matrix<Complex, Eigen::Dynamic, kTaps>;
using Square = Eigen::Matrix<Complex, kTaps, kTaps>;
using Vector = Eigen::Matrix<Complex, kTaps, 1>;

// The tone a bit sends: 0 MARK (bit 1), 1 SPACE (bit 0).
int ToneOf(int bit) { return bit ? 0 : 1; }

// One filter's fit: the regressors of the packet's bits, and their Gram matrix factored.
struct Fit {
  Matrix a;
  Eigen::LDLT<Square> gram;
};

using Column = Eigen::Matrix<Complex, Eigen::Dynamic, 1>;

// How the sender's clock offset turns filter t's observations, and undoing it.
struct Turning {
  const std::complex<double>* const* heard;
  const double* at;
  double freq[2];
  double sample_rate;
  // Observation k of filter t turned back by `offset` (a fraction of the clock), the first `rows`.
  void Derotated(int t, double offset, int rows, Column& z) const {
    const double w = 2.0 * kPi * freq[t] / sample_rate * offset;
    z.resize(rows);
    for (int k = 0; k < rows; ++k) z(k) = heard[t][k] * std::polar(1.0, -w * (at[k] - at[0]));
  }
};

// Filter t's fit of its first `rows` observations to bits `b` (rot: how far a bit of each tone
// turns the phase in filter t's frame), with a ridge of `ridge` times the mean diagonal.
void MakeFit(const std::array<std::uint8_t, kPacketBits>& b, int t, const Complex rot[2][2], int rows, double ridge, Fit& fit) {
  std::array<Complex, kPacketBits> phasor;
  Complex p(1.0, 0.0);
  for (int k = 0; k < kPacketBits; ++k) {
    phasor[k] = p;
    p *= rot[t][ToneOf(b[k])];
  }
  fit.a.setZero(rows, kTaps);
  for (int k = 0; k < rows; ++k) {
    for (int l = -kEarly; l <= kLate; ++l) {
      const int j = k - l;
      if (j < 0 || j >= kPacketBits) continue;
      if (ToneOf(b[j]) == t) {
        fit.a(k, l + kEarly) = phasor[j];
      } else if (l <= kCrossLate) {
        fit.a(k, kOwnTaps + l + kEarly) = phasor[j];
      }
    }
  }
  // The Gram matrix's lower half is all the factorisation reads: a rank update fills it in half
  // the work of the full product.
  Square g = Square::Zero();
  g.selfadjointView<Eigen::Lower>().rankUpdate(fit.a.adjoint());
  g.diagonal().array() += ridge * g.diagonal().real().mean() + 1e-30;
  fit.gram.compute(g);
}

struct OffsetFit {
  double offset;
  // The sum over both filters of the log of the share of their observations' power the fits
  // leave unexplained: the likelihood with each filter's noise unknown.
  double score;
};

// The sender's clock offset whose fits leave the least residual in both filters, searched from
// `center` over +-span on the grids of kOffsetSteps finer than span in turn: the observations
// turned by a rotor per observation, so that a grid costs no sines.
OffsetFit SearchOffset(const Fit fit[2], const Turning& turning, int rows, double center, double span) {
  Column turned[2], rotor[2];
  double power[2] = {0.0, 0.0};
  double best = std::numeric_limits<double>::infinity();
  for (const double step : kOffsetSteps) {
    if (step > span) continue;
    const double lowest = center - span;
    for (int t = 0; t < 2; ++t) {
      turning.Derotated(t, lowest, rows, turned[t]);
      power[t] = std::max(turned[t].squaredNorm(), 1e-30);
      rotor[t].resize(rows);
      const double w = 2.0 * kPi * turning.freq[t] / turning.sample_rate * step;
      for (int k = 0; k < rows; ++k) rotor[t](k) = std::polar(1.0, -w * (turning.at[k] - turning.at[0]));
    }
    best = std::numeric_limits<double>::infinity();
    double best_eps = center;
    const int points = static_cast<int>(std::lround(2.0 * span / step));
    for (int i = 0; i <= points; ++i) {
      double sum = 0.0;
      for (int t = 0; t < 2; ++t) {
        const Vector b = fit[t].a.adjoint() * turned[t];
        const Vector h = fit[t].gram.solve(b);
        sum += std::log(std::max(power[t] - (b.adjoint() * h)(0, 0).real(), 1e-30 * power[t]) / power[t]);
        turned[t].array() *= rotor[t].array();
      }
      if (sum < best) {
        best = sum;
        best_eps = lowest + i * step;
      }
    }
    center = best_eps;
    span = step;
  }
  return {center, best};
}

// The observations whose bits are all known: the break, the header and its start and stop
// bits; the first fit uses only these, the later ones every bit as decided.
int KnownRows() {
  int rows = 0;
  while (rows + kEarly < kPacketBits && KnownPacketBit(rows + kEarly) >= 0) ++rows;
  return rows;
}

// rot[t][tone]: how far a bit of `tone` turns the phase in filter t's frame.
void Rotations(const ModemOptions& modem, Complex rot[2][2]) {
  const double freq[2] = {modem.mark_hz, modem.space_hz};
  for (int t = 0; t < 2; ++t)
    for (int tone = 0; tone < 2; ++tone) rot[t][tone] = std::polar(1.0, 2.0 * kPi * (freq[tone] - freq[t]) / modem.baud);
}

// The packet's bits as far as known, the others 0. Nothing reads those before it decides them:
// the first fit takes only rows whose bits are all known, and the search sets each bit before a
// prediction uses it.
std::array<std::uint8_t, kPacketBits> KnownBits() {
  std::array<std::uint8_t, kPacketBits> bits;
  for (int k = 0; k < kPacketBits; ++k) bits[k] = static_cast<std::uint8_t>(std::max(0, KnownPacketBit(k)));
  return bits;
}

// The error events of a search's best path: `event[k]` names the merge that set bit k's
// reliability `rel[k]` (-1: none), so bits sharing one were changed together by one competitor.
ErrorEvents EventsOf(const std::array<int, kPacketBits>& event, const std::array<float, kPacketBits>& rel) {
  std::vector<std::pair<float, std::vector<int>>> weighed;
  std::vector<int> seen;
  for (int k = kBreakBits; k < kPacketBits; ++k) {
    const int id = event[k];
    if (id < 0 || std::find(seen.begin(), seen.end(), id) != seen.end()) continue;
    seen.push_back(id);
    std::vector<int> data;
    bool framing = false;
    float weakest = kMaxSoft;
    for (int i = k; i < kPacketBits; ++i) {
      if (event[i] != id) continue;
      weakest = std::min(weakest, rel[i]);
      const int j = i - kBreakBits, pos = j % kBitsPerByte;
      if (pos < 1 || pos > 8) {
        framing = true;
      } else {
        data.push_back((j / kBitsPerByte) * 8 + pos - 1);
      }
    }
    if (!framing) weighed.push_back({weakest, std::move(data)});
  }
  std::stable_sort(weighed.begin(), weighed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ErrorEvents events;
  for (auto& w : weighed) events.push_back(std::move(w.second));
  return events;
}

}  // namespace

FskEqualizer::FskEqualizer(const ModemOptions& modem) : modem_(modem) {}

bool FskEqualizer::Equalize(const std::complex<double>* const heard[2], const double* at, double frequency_error,
                            const Accept& accept) const {
  Complex rot[2][2];
  Rotations(modem_, rot);
  std::array<std::uint8_t, kPacketBits> bits = KnownBits();
  const Turning turning{heard, at, {modem_.mark_hz, modem_.space_hz}, modem_.sample_rate};
  const int known_rows = KnownRows();

  double offset = frequency_error;
  Vector taps[2];
  double noise[2];
  for (int pass = 0; pass < kPasses; ++pass) {
    const int rows = pass == 0 ? known_rows : kPacketBits;
    Fit fit[2];
    for (int t = 0; t < 2; ++t) MakeFit(bits, t, rot, rows, pass == 0 ? kFirstRidge : kRidge, fit[t]);
    // The offset: searched on the first two passes, from the clock's estimate, then finer.
    if (pass < 2) offset = SearchOffset(fit, turning, rows, pass == 0 ? frequency_error : offset, pass == 0 ? kOffsetSpan : kOffsetSteps[1]).offset;
    Column z;
    for (int t = 0; t < 2; ++t) {
      turning.Derotated(t, offset, rows, z);
      taps[t] = fit[t].gram.solve(fit[t].a.adjoint() * z);
      const double rss = (z - fit[t].a * taps[t]).squaredNorm();
      noise[t] = std::max(rss / std::max(rows - kTaps, kTaps), 1e-30);
    }
    // The observations, turned back, for the search.
    Column obs[2];
    for (int t = 0; t < 2; ++t) turning.Derotated(t, offset, kPacketBits, obs[t]);

    // Per-survivor Viterbi over the frame's bits with soft outputs (SOVA).
    struct Survivor {
      double metric = std::numeric_limits<double>::infinity();
      std::array<std::uint8_t, kPacketBits> bits;
      std::array<float, kPacketBits> rel;
      std::array<int, kPacketBits> event;  // the merge that set each bit's reliability (-1: none)
      Complex phasor[2];  // each filter's phase of the next bit
    };
    std::vector<Survivor> now(kStates), next(kStates);
    {
      Survivor& s = now[kStates - 1];  // the break's MARK half
      s.metric = 0.0;
      s.bits = bits;
      s.rel.fill(kMaxSoft);
      s.event.fill(-1);
      for (int t = 0; t < 2; ++t) {
        Complex p(1.0, 0.0);
        for (int k = 0; k < kBreakBits; ++k) p *= rot[t][ToneOf(bits[k])];
        s.phasor[t] = p;
      }
    }
    // The prediction of observation k = j - kEarly (filters' outputs at bit k) from the
    // survivor's bits before j: the same for both branches at bit j, so made once per survivor.
    auto older = [&](const Survivor& s, int j, Complex pred[2]) {
      const int k = j - kEarly;
      for (int t = 0; t < 2; ++t) {
        pred[t] = Complex(0.0, 0.0);
        Complex p = s.phasor[t];  // phase of bit j
        for (int l = -kEarly + 1; l <= kLate; ++l) {
          const int i = k - l;  // the bit at lag l, before j
          if (i < 0) break;
          p *= std::conj(rot[t][ToneOf(s.bits[i])]);
          if (ToneOf(s.bits[i]) == t) {
            pred[t] += taps[t](l + kEarly) * p;
          } else if (l <= kCrossLate) {
            pred[t] += taps[t](kOwnTaps + l + kEarly) * p;
          }
        }
      }
    };
    // The metric of observation j - kEarly given the survivor's older bits' prediction and bit
    // j = `b` (kPacketBits: none, after the packet).
    auto cost = [&](const Survivor& s, const Complex pred[2], int j, int b) {
      const int k = j - kEarly;
      double c = 0.0;
      for (int t = 0; t < 2; ++t) {
        Complex here = pred[t];
        if (b >= 0) here += (ToneOf(b) == t ? taps[t](0) : taps[t](kOwnTaps)) * s.phasor[t];
        c += std::norm(obs[t](k) - here) / noise[t];
      }
      return c;
    };
    for (int j = kBreakBits; j < kPacketBits + kEarly; ++j) {
      for (Survivor& s : next) s.metric = std::numeric_limits<double>::infinity();
      const int known = j < kPacketBits && j < kBreakBits ? KnownPacketBit(j) : -1;
      double competitor[kStates];
      std::fill(competitor, competitor + kStates, std::numeric_limits<double>::infinity());
      int from[kStates], loser[kStates];
      std::fill(from, from + kStates, -1);
      std::fill(loser, loser + kStates, -1);
      for (int state = 0; state < kStates; ++state) {
        const Survivor& s = now[state];
        if (!std::isfinite(s.metric)) continue;
        Complex pred[2];
        older(s, j, pred);
        for (int b = 0; b < 2; ++b) {
          if (j >= kPacketBits && b > 0) break;  // after the packet: one branch, no bit
          if (j < kPacketBits && known >= 0 && b != known) continue;
          const double m = s.metric + cost(s, pred, j, j < kPacketBits ? b : -1);
          const int to = j < kPacketBits ? ((state << 1) | b) & (kStates - 1) : state;
          if (m < next[to].metric) {
            competitor[to] = next[to].metric;
            loser[to] = from[to];
            next[to].metric = m;
            from[to] = state;
          } else if (m < competitor[to]) {
            competitor[to] = m;
            loser[to] = state;
          }
        }
      }
      for (int to = 0; to < kStates; ++to) {
        if (from[to] < 0) continue;
        const Survivor& s = now[from[to]];
        Survivor& n = next[to];
        const double m = n.metric;
        n.bits = s.bits;
        n.rel = s.rel;
        n.event = s.event;
        if (j < kPacketBits) {
          n.bits[j] = static_cast<std::uint8_t>(to & 1);
          for (int t = 0; t < 2; ++t) n.phasor[t] = s.phasor[t] * rot[t][ToneOf(to & 1)];
        } else {
          n.phasor[0] = s.phasor[0];
          n.phasor[1] = s.phasor[1];
        }
        if (loser[to] >= 0) {
          const float delta = static_cast<float>(competitor[to] - m);
          const Survivor& other = now[loser[to]];
          for (int i = kBreakBits; i < std::min(j, kPacketBits); ++i) {
            if (other.bits[i] != n.bits[i] && delta < n.rel[i]) {
              n.rel[i] = delta;
              n.event[i] = j * kStates + to;
            }
          }
        }
      }
      std::swap(now, next);
    }
    Survivor* best = &now[0];
    for (Survivor& s : now)
      if (s.metric < best->metric) best = &s;
    // The packet's last kStateBits bits are the final state's and no merge ever challenged
    // them (nor, for the same reason, earlier bits where the final survivors still differ): their
    // reliability is what the other final survivors cost more.
    for (int f = 0; f < kStates; ++f) {
      const Survivor& s = now[f];
      if (&s == best || !std::isfinite(s.metric)) continue;
      const float delta = static_cast<float>(s.metric - best->metric);
      for (int i = kBreakBits; i < kPacketBits; ++i)
        if (s.bits[i] != best->bits[i] && delta < best->rel[i]) {
          best->rel[i] = delta;
          best->event[i] = (kPacketBits + kEarly + 1) * kStates + f;
        }
    }
    const ErrorEvents events = EventsOf(best->event, best->rel);
    SoftFrame soft{};
    for (int j = 0; j < kFrameBits; ++j) {
      const int pos = j % kBitsPerByte;
      if (pos < 1 || pos > 8) continue;
      const int k = kBreakBits + j;
      soft[(j / kBitsPerByte) * 8 + pos - 1] = best->bits[k] ? best->rel[k] : -best->rel[k];
    }
    // The start and stop bits were decided freely: all must be right for the frame to count.
    int misframed = 0;
    for (int c = 0; c < kFrameBytes; ++c) {
      misframed += best->bits[kBreakBits + c * kBitsPerByte] != 0;
      misframed += best->bits[kBreakBits + c * kBitsPerByte + 9] != 1;
    }
    if (misframed == 0 && accept(soft, events)) return true;
    // A first pass this far off is not a packet the later passes could save (a wrong clock,
    // or noise), and they cost.
    if (pass == 0 && misframed > kMaxMisframedFirst) return false;
    std::array<std::uint8_t, kPacketBits> decided = best->bits;
    for (int k = 0; k < kPacketBits; ++k)
      if (KnownPacketBit(k) >= 0) decided[k] = static_cast<std::uint8_t>(KnownPacketBit(k));
    if (pass > 0 && decided == bits) break;
    bits = decided;
  }
  return false;
}

}  // namespace nava_modem
