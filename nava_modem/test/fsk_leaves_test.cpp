// The nava receiver's leaf objects alone: the two tone filters (ToneFilters), the bit clock's
// loop (BitClock), the busy-air reports (BusyAir) and the equaliser (FskEqualizer), each on
// packets the modulator makes, heard through rooms whose responses are known by construction
// (known_response.h) or like measured ones (measured_like_response.h). Seeded throughout.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "array_signals.h"
#include "known_response.h"
#include "nava_modem/bit_clock.h"
#include "nava_modem/busy_air.h"
#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"
#include "nava_modem/fsk_equalizer.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/measured_like_response.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/tone_filters.h"
#include "test_signals.h"

namespace nava_modem {
namespace {

using array_signals::BandNoise;
using array_signals::Convolve;

// The tone filters' outputs at each of their steps over `audio`: step n describes the bit-long
// window that ends with sample (n + 1) * step - 1.
struct FilterTrace {
  int step = 0, window = 0;
  std::vector<double> mark, space;                   // powers
  std::vector<std::complex<double>> mark_c, space_c;  // complex amplitudes
};

FilterTrace Filter(const ModemOptions& o, const std::vector<float>& audio) {
  ToneFilters filters(o);
  FilterTrace t;
  t.step = filters.step();
  t.window = filters.window();
  for (const float x : audio) {
    if (!filters.Push(x)) continue;
    t.mark.push_back(filters.mark_power());
    t.space.push_back(filters.space_power());
    t.mark_c.emplace_back(filters.mark_re(), filters.mark_im());
    t.space_c.emplace_back(filters.space_re(), filters.space_im());
  }
  return t;
}

// `bits` as the modulator sounds them, after `lead` samples of silence.
std::vector<float> Sounded(const ModemOptions& o, const std::vector<std::uint8_t>& bits, std::size_t lead) {
  std::vector<float> audio(lead, 0.0f);
  const std::vector<float> burst = FskModulator(o).Modulate(bits);
  audio.insert(audio.end(), burst.begin(), burst.end());
  return audio;
}

// The break: kBreakSpaceBits of SPACE, then kBreakMarkBits of MARK.
std::vector<std::uint8_t> BreakBits() {
  std::vector<std::uint8_t> bits(kBreakSpaceBits, 0);
  bits.insert(bits.end(), kBreakMarkBits, 1);
  return bits;
}

// Where the two tones' powers, each over its own level, are equal, in steps (interpolated),
// nearest `near` within `reach` steps; NaN if they do not cross there.
double Crossing(const FilterTrace& t, double mark_level, double space_level, double near, double reach) {
  double best = std::nan(""), nearest = reach;
  const auto diff = [&](std::int64_t n) { return t.mark[n] / mark_level - t.space[n] / space_level; };
  const std::int64_t lo = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(near - reach)));
  const std::int64_t hi = std::min<std::int64_t>(static_cast<std::int64_t>(t.mark.size()) - 1, static_cast<std::int64_t>(std::ceil(near + reach)));
  for (std::int64_t n = lo; n <= hi; ++n) {
    const double a = diff(n - 1), b = diff(n);
    if ((a > 0.0) == (b > 0.0) || a == b) continue;
    const double at = (n - 1) + a / (a - b);
    if (std::abs(at - near) <= nearest) {
      nearest = std::abs(at - near);
      best = at;
    }
  }
  return best;
}

// A packet as a microphone hears it: `audio`, in which bit k of the packet (k = 0: the break's
// first SPACE bit) begins at sample first + k * per_bit.
struct Heard {
  std::vector<float> audio;
  std::vector<std::uint8_t> bits;  // the packet's, in air order
  double first = 0.0, per_bit = 0.0;
};

// The packet carrying `data`, sent by a sender whose clock runs (1 + clock_error) fast, a tenth
// of a second into the audio, through the room `response` (nava_room's renderer: its direct
// sound, at index `direct`, kept where it is) with white noise snr_db under the packet (seeded by
// `seed`).
Heard HeardThrough(const ModemOptions& o, const std::vector<std::uint8_t>& data, std::vector<float> response,
                   std::size_t direct, double clock_error, double snr_db, unsigned seed) {
  const double gap = 0.1;
  RoomOptions room;
  room.response = std::move(response);
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = snr_db;
  room.seed = seed;
  Heard h;
  h.audio = RenderRoom(test_signals::PacketTrain(o, {data}, gap, clock_error), o.sample_rate, room);
  h.bits = PacketBits(MakeFrame(data, o.crc));
  h.first = std::floor(gap * o.sample_rate) + static_cast<double>(direct);
  h.per_bit = SamplesPerBit(o) / (1.0 + clock_error);
  return h;
}

// The filter step whose window ends with bit k's last sample.
std::size_t EndOfBit(const Heard& h, int k, int step) {
  return static_cast<std::size_t>(std::lround((h.first + (k + 1) * h.per_bit) / step) - 1);
}

// ---------------------------------------------------------------------------------------------
// ToneFilters

TEST(ToneFilters, StepIsAFortiethOfABitAndTheWindowOneBit) {
  // (sample rate, step, window): a 40th of a bit rounded down, at least one sample; the window
  // as many steps as make a bit, to the nearest.
  const struct {
    double rate;
    int step, window;
  } cases[] = {{48000.0, 4, 40}, {44100.0, 3, 49}, {16000.0, 1, 53}, {8000.0, 1, 27}};
  for (const auto& c : cases) {
    ModemOptions o;
    o.sample_rate = c.rate;
    ToneFilters f(o);
    EXPECT_EQ(ToneFilters::Step(o), c.step) << c.rate;
    EXPECT_EQ(f.step(), c.step) << c.rate;
    EXPECT_EQ(f.window(), c.window) << c.rate;
  }
  // An output every step-th sample, and only then.
  ModemOptions o;
  ToneFilters f(o);
  for (int n = 0; n < 400; ++n) EXPECT_EQ(f.Push(0.1f), (n + 1) % 4 == 0) << "sample " << n;
}

TEST(ToneFilters, AToneFillsItsOwnFilterWellAboveTheOther) {
  for (const double rate : {48000.0, 44100.0, 16000.0}) {
    ModemOptions o;
    o.sample_rate = rate;
    const double full = o.amplitude * o.amplitude;  // a tone of amplitude a reads a^2 (full scale: 1)
    for (const std::uint8_t bit : {1, 0}) {
      const FilterTrace t = Filter(o, Sounded(o, std::vector<std::uint8_t>(30, bit), 0));
      // Ten bits in: past the burst's fade-in by far, a steady tone in a whole window.
      const std::size_t n = static_cast<std::size_t>(std::lround(10.0 * SamplesPerBit(o) / t.step));
      const double own = bit ? t.mark[n] : t.space[n], other = bit ? t.space[n] : t.mark[n];
      // Within the ripple of the tone's image at minus its frequency, which a window of a
      // fractional number of its cycles does not cancel: up to 2 % in amplitude.
      EXPECT_NEAR(own, full, 0.05 * full) << rate << " Hz, bit " << int(bit);
      // The other tone lies 4.7 bins off, on a sidelobe of the bit-long window: -25 dB.
      EXPECT_LT(other, 0.01 * own) << rate << " Hz, bit " << int(bit);
    }
  }
}

TEST(ToneFilters, ASteadyToneKeepsItsPhaseFromOutputToOutput) {
  // What the equaliser builds on: the complex outputs are correlations with e^{-j w n}, n from
  // the filter's first sample, so a steady tone of the filter's own frequency stands still.
  ModemOptions o;
  for (const std::uint8_t bit : {1, 0}) {
    const FilterTrace t = Filter(o, Sounded(o, std::vector<std::uint8_t>(30, bit), 0));
    const std::vector<std::complex<double>>& own = bit ? t.mark_c : t.space_c;
    const std::vector<double>& power = bit ? t.mark : t.space;
    const std::size_t from = 400, to = 1000;  // steps 10 to 25 bits in
    for (std::size_t n = from; n <= to; n += 7) {
      // Still but for the ripple of the tone's image (2 % at most): a phase turning from output
      // to output would be far off within a few steps.
      EXPECT_LT(std::abs(own[n] - own[from]), 0.05 * std::abs(own[from])) << "step " << n;
      EXPECT_NEAR(std::norm(own[n]), power[n], 1e-9);  // the same scale as the powers
    }
  }
}

TEST(ToneFilters, TheTonesCrossHalfAWindowAfterTheBoundaryAndSettleAWindowAfter) {
  ModemOptions o;
  const FilterTrace t = Filter(o, Sounded(o, BreakBits(), 0));
  const double full = o.amplitude * o.amplitude;
  const double boundary = kBreakSpaceBits * SamplesPerBit(o) / t.step;  // in steps: 800
  // They cross where the window holds half a bit of each: the boundary is step 800's first
  // sample, and step 819's window ends with the sample half a window less one past it. What
  // BitClock::ExpectedCrossing counts on.
  const double expected = boundary + t.window / 2.0 - 1.0;
  const double crossing = Crossing(t, full, full, expected, t.window / 2.0);
  EXPECT_NEAR(crossing, expected, 0.25);
  // Half way, each tone fills half the window: a quarter of its power.
  const std::size_t half = static_cast<std::size_t>(expected);
  EXPECT_NEAR(t.mark[half], full / 4.0, 0.05 * full);
  // A window after the boundary and the modulator's ramp (0.075 bit) MARK is steady, SPACE gone.
  const std::size_t settled = static_cast<std::size_t>(std::ceil(boundary + t.window + 0.075 * SamplesPerBit(o) / t.step));
  EXPECT_NEAR(t.mark[settled], full, 0.05 * full);
  EXPECT_LT(t.space[settled], 0.01 * full);
}

TEST(ToneFilters, EachBitOfAPacketThroughARoomIsReadAtItsEnd) {
  // A reverberant room (RT60 0.3 s, DRR +10 dB): its echoes fade each tone by a few dB and put
  // the bits before into every window. Each tone is taken on its own scale, its level where the
  // break holds it steady; at each bit's end, where the one-bit window holds that bit alone, the
  // louder tone is the bit. (Wetter rooms, and the measured-like ones whose colouring puts the
  // tones up to 28 dB apart, beyond the filters' 25 dB of separation, are the equaliser's.)
  ModemOptions o;
  const auto payloads = test_signals::RandomPayloads(6, 11);
  int wrong_at_end = 0, wrong_in_middle = 0;
  for (unsigned seed = 0; seed < payloads.size(); ++seed) {
    const Heard h = HeardThrough(o, payloads[seed], KnownResponse(0.3, 10.0, o.sample_rate, 0, 100 + seed), 0, 0.0, 30.0, 200 + seed);
    const FilterTrace t = Filter(o, h.audio);
    const std::size_t space_end = EndOfBit(h, kBreakSpaceBits - 1, t.step), mark_end = EndOfBit(h, kBreakSpaceBits + kBreakMarkBits - 1, t.step);
    const double mark_level = t.mark[mark_end], space_level = t.space[space_end];
    for (int k = 0; k < kPacketBits; ++k) {
      const std::size_t end = EndOfBit(h, k, t.step), middle = end - t.window / 2;
      wrong_at_end += (t.mark[end] / mark_level > t.space[end] / space_level) != (h.bits[k] == 1);
      wrong_in_middle += (t.mark[middle] / mark_level > t.space[middle] / space_level) != (h.bits[k] == 1);
    }
  }
  std::printf("RT60 0.3 s, DRR +10 dB: %d of %zu bits wrong at their ends, %d half a bit earlier\n", wrong_at_end,
              payloads.size() * kPacketBits, wrong_in_middle);
  EXPECT_EQ(wrong_at_end, 0);
  // Half a bit earlier the window holds half of the bit before: after a transition, a coin toss.
  EXPECT_GT(wrong_in_middle, kPacketBits);  // 149 of 660 when written
}

// ---------------------------------------------------------------------------------------------
// BitClock

TEST(BitClock, PlacesBitsOnItsPeriodAndMovesOnlyFromTheBoundarySeen) {
  BitClock clock(100.0, 40.0, 40.0, 0.25, 0.01);
  EXPECT_DOUBLE_EQ(clock.Start(3), 220.0);
  EXPECT_DOUBLE_EQ(clock.AlignedSample(3), 259.0);  // the bit's last sample
  EXPECT_DOUBLE_EQ(clock.ExpectedCrossing(3), 239.0);  // half a window into the bit, less the sample
  // A crossing where it was expected changes nothing.
  clock.Observe(3, 239.0);
  EXPECT_DOUBLE_EQ(clock.Start(10), 500.0);
  EXPECT_DOUBLE_EQ(clock.period(), 40.0);
  // One 4 samples late: the boundary moves a quarter of that, the period a hundredth; the bits
  // after it follow the new period from the moved boundary, not from bit 0 (which would move
  // bit 10 by a further 10 x 0.04).
  clock.Observe(5, 323.0);
  EXPECT_DOUBLE_EQ(clock.period(), 40.04);
  EXPECT_DOUBLE_EQ(clock.Start(5), 301.0);
  EXPECT_DOUBLE_EQ(clock.Start(10), 301.0 + 5 * 40.04);
  EXPECT_DOUBLE_EQ(clock.ExpectedCrossing(6), 301.0 + 40.04 + 19.0);
}

// The loop gains used here. The frame reader's (0.1 and 0.002) pull in only a few tenths of a
// percent, as the clock search has the rate that close before its loop runs (with them a sender
// 3 % off loses a third of its bits here); here the loop alone must pull in a sender up to 3 %
// off the nominal rate, and a room's echoes move single crossings by several steps, which a
// larger period gain would follow.
constexpr double kTestPhaseGain = 0.15, kTestPeriodGain = 0.005;

struct Followed {
  std::vector<std::uint8_t> bits;  // as decided at each bit's aligned sample
  // Each crossing seen, less where the clock expected it (steps), and the bit it led into.
  std::vector<double> errors;
  std::vector<int> error_bits;
  double period = 0.0;
};

// Reads `count` bits from the filter outputs `t` (each tone over its level) on `clock`: each bit
// by the louder tone at the clock's aligned sample, and each transition's crossing, the one
// nearest where the clock expects it within half a bit, observed.
Followed Follow(BitClock clock, const FilterTrace& t, double mark_level, double space_level, int count) {
  Followed f;
  for (int k = 0; k < count; ++k) {
    const std::size_t at = static_cast<std::size_t>(std::lround(clock.AlignedSample(k)));
    const std::uint8_t bit = at < t.mark.size() && t.mark[at] / mark_level > t.space[at] / space_level;
    if (k > 0 && bit != f.bits.back()) {
      const double expected = clock.ExpectedCrossing(k);
      const double crossing = Crossing(t, mark_level, space_level, expected, clock.period() / 2.0);
      if (!std::isnan(crossing)) {
        f.errors.push_back(crossing - expected);
        f.error_bits.push_back(k);
        clock.Observe(k, crossing);
      }
    }
    f.bits.push_back(bit);
  }
  f.period = clock.period();
  return f;
}

TEST(BitClock, LocksToASenderWhoseClockIsOffThroughARoom) {
  // 16 alternating bits (a preamble, a transition at every boundary to pull the loop in), then
  // 94 random ones, from a sender 1 to 3 % fast or slow, heard through a room (RT60 0.3 s,
  // DRR +10 dB) with noise. The clock starts on the first bit's true start at the nominal period.
  ModemOptions o;
  std::mt19937 rng(5);
  std::bernoulli_distribution coin(0.5);
  std::vector<std::uint8_t> bits;
  for (int k = 0; k < 16; ++k) bits.push_back(static_cast<std::uint8_t>(k % 2));
  while (bits.size() < 110) bits.push_back(coin(rng));
  const std::size_t lead = 4800;
  for (const double offset : {-0.03, -0.01, 0.01, 0.03}) {
    RoomOptions room;
    room.response = KnownResponse(0.3, 10.0, o.sample_rate, 0, 7);
    room.clock_offset = offset;  // the whole sound resampled, as the sender's card plays it
    room.noise = RoomOptions::Noise::kWhite;
    room.snr_db = 25.0;
    room.seed = 8;
    const FilterTrace t = Filter(o, RenderRoom(Sounded(o, bits, lead), o.sample_rate, room));
    const double mark_level = *std::max_element(t.mark.begin(), t.mark.end());
    const double space_level = *std::max_element(t.space.begin(), t.space.end());
    const double per_bit = SamplesPerBit(o) / t.step, truth = per_bit / (1.0 + offset);
    const double start = lead / (1.0 + offset) / t.step;
    const Followed locked = Follow(BitClock(start, per_bit, t.window, kTestPhaseGain, kTestPeriodGain), t, mark_level, space_level, 110);
    const Followed free = Follow(BitClock(start, per_bit, t.window, 0.0, 0.0), t, mark_level, space_level, 110);
    int wrong = 0, wrong_free = 0;
    for (std::size_t k = 0; k < bits.size(); ++k) {
      wrong += locked.bits[k] != bits[k];
      wrong_free += free.bits[k] != bits[k];
    }
    // The crossings over the last quarter of the bits, by when the loop has pulled in (at 3 %
    // it takes some 60 bits with these gains): centred on where the clock expects them (over
    // the second half they still lag by 2 steps at 3 %).
    double late_mean = 0.0;
    int late = 0;
    for (std::size_t i = 0; i < locked.errors.size(); ++i) {
      if (locked.error_bits[i] < 3 * static_cast<int>(bits.size()) / 4) continue;
      late_mean += locked.errors[i];
      ++late;
    }
    late_mean /= std::max(late, 1);
    std::printf("sender %+.0f %%: %d bits wrong (a free-running clock: %d), period %.3f steps (the sender's %.3f), last crossings %.2f steps late\n",
                offset * 100.0, wrong, wrong_free, locked.period, truth, late_mean);
    EXPECT_EQ(wrong, 0) << "offset " << offset;
    // Without the loop the same clock drifts off the sender's bits: the signal needs following.
    EXPECT_GE(wrong_free, 20) << "offset " << offset;
    // The period has taken up the sender's rate to within 0.3 % (single crossings move by
    // several steps in the room; the period averages them), and the crossings are centred.
    EXPECT_NEAR(locked.period, truth, 0.003 * per_bit) << "offset " << offset;
    EXPECT_LT(std::abs(late_mean), 1.5) << "offset " << offset;
  }
}

// ---------------------------------------------------------------------------------------------
// BusyAir

// Steps of 1 ms from from_ms to to_ms (inclusive), each of in-band power `power` and quality
// `quality`.
void Steps(BusyAir& air, int from_ms, int to_ms, double power, double quality, bool waiting, std::vector<RxEvent>& events) {
  for (int ms = from_ms; ms <= to_ms; ++ms) air.Step(ms * 1e-3, power, quality, waiting, events);
}

TEST(BusyAir, WithoutAThresholdNothingIsBusy) {
  std::vector<RxEvent> events;
  BusyAir never(0.005, 0.005);
  Steps(never, 0, 200, 1.0, 1.0, false, events);
  EXPECT_FALSE(never.busy());
  BusyAir cleared(0.005, 0.005);
  cleared.SetThreshold(-20.0);
  cleared.SetThreshold(std::nullopt);
  Steps(cleared, 0, 200, 1.0, 1.0, false, events);
  EXPECT_FALSE(cleared.busy());
  EXPECT_TRUE(events.empty());
}

TEST(BusyAir, ALoudStretchIsReportedAsZeroByteOnceTheReleaseHasPassed) {
  BusyAir air(0.005, 0.005);
  air.SetThreshold(-20.0);  // 0.01
  std::vector<RxEvent> events;
  Steps(air, 0, 9, 0.001, 0.1, false, events);
  EXPECT_FALSE(air.busy());
  Steps(air, 10, 110, 0.1, 0.6, false, events);  // 10 dB over the threshold for 100 ms
  EXPECT_TRUE(air.busy());
  Steps(air, 111, 114, 0.001, 0.1, false, events);  // 4 ms of quiet: within the release
  EXPECT_TRUE(air.busy());
  EXPECT_TRUE(events.empty());
  Steps(air, 115, 116, 0.001, 0.1, false, events);  // 6 ms: past it
  EXPECT_FALSE(air.busy());
  ASSERT_EQ(events.size(), 1u);
  const RxEvent& ev = events[0];
  EXPECT_EQ(ev.kind, RxEvent::Kind::kNoise);
  EXPECT_EQ(ev.noise, RxEvent::Noise::kZeroByte);
  EXPECT_DOUBLE_EQ(ev.start, 0.010);
  EXPECT_DOUBLE_EQ(ev.end, 0.110);  // the last loud step, not the release after it
  EXPECT_DOUBLE_EQ(air.last_loud(), 0.110);
  // The loud steps' level and quality (the release's quiet steps count in the averages too, a
  // few percent of this stretch).
  EXPECT_NEAR(ev.level_db, -10.0, 0.5);
  EXPECT_NEAR(ev.quality, 0.6, 0.05);
}

TEST(BusyAir, ShortOrFramedStretchesAreNotReported) {
  std::vector<RxEvent> events;
  BusyAir air(0.005, 0.005);
  air.SetThreshold(-20.0);
  Steps(air, 10, 13, 0.1, 0.5, false, events);  // 3 ms: under the 5 ms least
  Steps(air, 14, 40, 0.0, 0.0, false, events);
  EXPECT_TRUE(events.empty());
  // A frame found in the stretch: the receiver reported it itself.
  Steps(air, 50, 100, 0.1, 0.5, false, events);
  air.FrameFound();
  Steps(air, 101, 140, 0.0, 0.0, false, events);
  EXPECT_TRUE(events.empty());
  // A frame found in quiet air belongs to no stretch: the next one is still reported.
  air.FrameFound();
  Steps(air, 150, 200, 0.1, 0.5, false, events);
  Steps(air, 201, 240, 0.0, 0.0, false, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_DOUBLE_EQ(events[0].start, 0.150);
  // Reset forgets a stretch unreported.
  events.clear();
  Steps(air, 300, 350, 0.1, 0.5, false, events);
  air.Reset();
  EXPECT_FALSE(air.busy());
  Steps(air, 351, 400, 0.0, 0.0, false, events);
  EXPECT_TRUE(events.empty());
}

TEST(BusyAir, QuietShorterThanTheReleaseOrWaitedForJoinsOneStretch) {
  std::vector<RxEvent> events;
  BusyAir air(0.005, 0.005);
  air.SetThreshold(-20.0);
  Steps(air, 10, 30, 0.1, 0.5, false, events);
  Steps(air, 31, 34, 0.0, 0.0, false, events);  // 4 ms of quiet: within the release
  Steps(air, 35, 50, 0.1, 0.5, false, events);
  // Quiet while a frame may still come out of it: the stretch is held open.
  Steps(air, 51, 80, 0.0, 0.0, true, events);
  EXPECT_TRUE(air.busy());
  EXPECT_TRUE(events.empty());
  Steps(air, 81, 81, 0.0, 0.0, false, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_DOUBLE_EQ(events[0].start, 0.010);
  EXPECT_DOUBLE_EQ(events[0].end, 0.050);
  // Quiet longer than the release: two stretches.
  events.clear();
  Steps(air, 100, 120, 0.1, 0.5, false, events);
  Steps(air, 121, 130, 0.0, 0.0, false, events);
  Steps(air, 131, 150, 0.1, 0.5, false, events);
  Steps(air, 151, 160, 0.0, 0.0, false, events);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_DOUBLE_EQ(events[0].end, 0.120);
  EXPECT_DOUBLE_EQ(events[1].start, 0.131);
}

// BusyAir as the nava receiver runs it (release and least length a bit each) on the tone
// filters' outputs of `audio`: each step's in-band power the two filters' powers summed, its
// quality their amplitudes summed. FrameFound() is called at found_at_s (s; none if negative).
struct BusyRun {
  std::vector<RxEvent> events;
  double first_busy = -1.0;  // s: the first step found busy
};

BusyRun RunBusyAir(const ModemOptions& o, const std::vector<float>& audio, double threshold_db, double found_at_s) {
  const double bit = 1.0 / o.baud;
  BusyAir air(bit, bit);
  air.SetThreshold(threshold_db);
  ToneFilters filters(o);
  const double seconds_per_step = filters.step() / o.sample_rate;
  BusyRun run;
  std::int64_t n = 0;
  bool found = found_at_s < 0.0;
  for (const float x : audio) {
    if (!filters.Push(x)) continue;
    const double time = n++ * seconds_per_step, mark = filters.mark_power(), space = filters.space_power();
    air.Step(time, mark + space, std::sqrt(mark) + std::sqrt(space), false, run.events);
    if (air.busy() && run.first_busy < 0.0) run.first_busy = time;
    if (!found && time >= found_at_s) {
      air.FrameFound();
      found = true;
    }
  }
  return run;
}

TEST(BusyAir, InARoomSilenceIsQuietAFoundPacketIsNotNoiseAndNoiseIsZeroByte) {
  // Through a reverberant room (RT60 0.4 s, DRR 0 dB), with a faint noise floor: 0.2 s of
  // nothing, a packet, 0.4 s of its echoes dying, then 0.3 s of in-band noise and its echoes.
  ModemOptions o;
  const double fs = o.sample_rate, threshold_db = -30.0, two_bits = 2.0 / o.baud;
  const std::vector<float> packet = FskModulator(o).ModulatePacket({1, 2, 3, 4});
  const double packet_start = 0.2, packet_end = packet_start + packet.size() / fs;
  const double noise_start = packet_end + 0.4, noise_end = noise_start + 0.3;
  std::vector<float> clean(static_cast<std::size_t>(packet_start * fs), 0.0f);
  clean.insert(clean.end(), packet.begin(), packet.end());
  clean.resize(static_cast<std::size_t>(noise_start * fs), 0.0f);
  const std::vector<float> burst = BandNoise(static_cast<std::size_t>(0.3 * fs), fs, 2000.0, 4000.0, 3);  // RMS 0.1
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.3 * fs), 0.0f);
  std::vector<float> heard = Convolve(clean, KnownResponse(0.4, 0.0, fs, 0, 21));
  test_signals::AddNoise(heard, 1.0, 70.0, fs, 22);  // -70 dB in 2-4 kHz
  // The burst's level in the filters: its power 0.01 spread over 2 kHz; each one-bit filter
  // passes 300 Hz of it and reads a power P as 2 P (a tone of power 1/2 reads 1): 0.003 each,
  // 0.006 both; the room (DRR 0 dB) doubles it.
  const double noise_db = 10.0 * std::log10(2.0 * 2.0 * 2.0 * 0.01 * 300.0 / 2000.0);
  const double tail = 0.4 * 30.0 / 60.0;  // the room's echoes fall 30 dB in 0.2 s

  // What a stretch of busy air overlapping [from, to] was reported as, if one was.
  const auto overlapping = [](const BusyRun& run, double from, double to) {
    std::vector<RxEvent> out;
    for (const RxEvent& e : run.events)
      if (e.end >= from && e.start <= to) out.push_back(e);
    return out;
  };

  const BusyRun found = RunBusyAir(o, heard, threshold_db, (packet_start + packet_end) / 2.0);
  // The packet's frame was found in its stretch: not reported.
  EXPECT_TRUE(overlapping(found, packet_start, packet_end).empty());
  // The noise is one stretch, from its start until its echoes fall under the threshold, at its level.
  const std::vector<RxEvent> noise = overlapping(found, noise_start, noise_end);
  ASSERT_EQ(noise.size(), 1u);
  EXPECT_EQ(noise[0].kind, RxEvent::Kind::kNoise);
  EXPECT_EQ(noise[0].noise, RxEvent::Noise::kZeroByte);
  EXPECT_NEAR(noise[0].start, noise_start, two_bits);
  EXPECT_GT(noise[0].end, noise_end);
  EXPECT_LT(noise[0].end, noise_end + tail);
  EXPECT_NEAR(noise[0].level_db, noise_db, 2.0);
  EXPECT_GT(noise[0].quality, 0.0);
  // Nothing is busy before the packet, nor once its echoes have died; what else is reported
  // (the echoes fading in and out around the threshold as they die: each a stretch of its own
  // once a bit's quiet has ended the one before) lies within their reach.
  EXPECT_NEAR(found.first_busy, packet_start, two_bits);
  for (const RxEvent& e : found.events) {
    EXPECT_EQ(e.noise, RxEvent::Noise::kZeroByte);
    EXPECT_TRUE((e.start > packet_end && e.end < packet_end + tail) || (e.start >= noise[0].start && e.end < noise_end + tail))
        << "busy air at " << e.start << " to " << e.end << " s";
  }

  // Had no frame been found in the packet, it too would be busy air without a frame.
  const BusyRun lost = RunBusyAir(o, heard, threshold_db, -1.0);
  const std::vector<RxEvent> unframed = overlapping(lost, packet_start, packet_end);
  ASSERT_EQ(unframed.size(), 1u);
  EXPECT_EQ(unframed[0].noise, RxEvent::Noise::kZeroByte);
  EXPECT_NEAR(unframed[0].start, packet_start, two_bits);
  EXPECT_GT(unframed[0].end, packet_end);
  EXPECT_LT(unframed[0].end, packet_end + tail);

  // The faint floor alone: never busy.
  const std::vector<float> quiet(heard.begin(), heard.begin() + static_cast<std::ptrdiff_t>(packet_start * fs));
  const BusyRun silence = RunBusyAir(o, quiet, threshold_db, -1.0);
  EXPECT_TRUE(silence.events.empty());
  EXPECT_LT(silence.first_busy, 0.0);
}

// ---------------------------------------------------------------------------------------------
// FskEqualizer

// What the equaliser reads, as the receiver gives it: each tone filter's complex output at each
// bit's end and the sample it was taken at; and, to compare with, the frame's bits as the louder
// filter there has them.
struct EqualizerInput {
  std::vector<std::complex<double>> heard[2];
  std::vector<double> at;
  std::vector<std::uint8_t> louder;
};

EqualizerInput InputOf(const Heard& h, const FilterTrace& t) {
  EqualizerInput in;
  for (int k = 0; k < kPacketBits; ++k) {
    const std::size_t n = EndOfBit(h, k, t.step);
    in.heard[0].push_back(t.mark_c[n]);
    in.heard[1].push_back(t.space_c[n]);
    in.at.push_back(static_cast<double>(n) * t.step);  // as the receiver counts: the step's first sample
    if (k >= kBreakSpaceBits + kBreakMarkBits) in.louder.push_back(t.mark[n] > t.space[n]);
  }
  return in;
}

// The frame whose header and CRC check without repair, if a pass of the equaliser offers one;
// `offered`: the passes offered.
std::optional<Frame> Equalized(const ModemOptions& o, const EqualizerInput& in, double frequency_error, int* offered = nullptr) {
  const std::complex<double>* const heard[2] = {in.heard[0].data(), in.heard[1].data()};
  std::optional<Frame> frame;
  int offers = 0;
  FskEqualizer(o).Equalize(heard, in.at.data(), frequency_error, [&](const SoftFrame& soft, const ErrorEvents&) {
    ++offers;
    const std::optional<RepairedFrame> checked = RepairFrame(soft, o.crc, 0);
    if (checked) frame = checked->frame;
    return checked.has_value();
  });
  if (offered) *offered = offers;
  return frame;
}

// Whether the louder filter's decisions alone spell a frame whose header and CRC check.
bool PowerReadingChecks(const ModemOptions& o, const EqualizerInput& in) {
  Frame frame{};
  for (int c = 0; c < kFrameBytes; ++c) frame[c] = ReadUartByte(&in.louder[c * kBitsPerByte]).value;
  return frame[0] == kHeader && CrcMatches(frame, o.crc);
}

TEST(FskEqualizer, ReadsPacketsThroughReverberantRoomsThatAPowerReadingLoses) {
  // Rooms like measured ones with RT60 0.5 s and DRR +3 dB: early reflections 1.5 to 12 bits
  // late add to each bit's tone in the phase of earlier bits, and the tones lie several dB
  // apart. Compared at each bit's end, the louder filter spells a frame that checks for hardly
  // any of them; the equaliser, modelling the room on the packet itself, reads them.
  ModemOptions o;
  const auto payloads = test_signals::RandomPayloads(8, 31);
  int read = 0, power = 0;
  for (unsigned i = 0; i < payloads.size(); ++i) {
    const Heard h = HeardThrough(o, payloads[i], MeasuredLikeResponse(0.5, 3.0, o.sample_rate, 40 + i), kMeasuredLikeDelay, 0.0, 30.0, 50 + i);
    EqualizerInput in = InputOf(h, Filter(o, h.audio));
    power += PowerReadingChecks(o, in);
    const std::optional<Frame> frame = Equalized(o, in, 0.0);
    const Frame sent = MakeFrame(payloads[i], o.crc);
    EXPECT_TRUE(!frame || *frame == sent) << "room " << i << ": a wrong frame passed";
    read += frame && *frame == sent;
  }
  std::printf("RT60 0.5 s, DRR +3 dB: the equaliser read %d of %zu packets, the louder filter %d\n", read, payloads.size(), power);
  EXPECT_GE(read, 7);  // 8 when written
  EXPECT_LE(power, 2);  // 1 when written
}

TEST(FskEqualizer, FindsTheSendersClockNearTheEstimateItIsGiven) {
  // A sender 0.25 % fast or slow, each bit taken at its end on the sender's clock: its tones
  // turn against the filters' by 2 pi f x 0.0025 rad a second, SPACE by 3.4 turns over a packet.
  // From an estimate of 0 the equaliser finds the offset; from one 0.5 % off the offset lies
  // beyond the 0.3 % either side that it searches, and no fit explains the packet.
  ModemOptions o;
  const auto payloads = test_signals::RandomPayloads(3, 32);
  for (const double offset : {-0.0025, 0.0025}) {
    for (unsigned i = 0; i < payloads.size(); ++i) {
      const Heard h = HeardThrough(o, payloads[i], MeasuredLikeResponse(0.3, 3.0, o.sample_rate, 60 + i), kMeasuredLikeDelay, offset, 30.0, 70 + i);
      const EqualizerInput in = InputOf(h, Filter(o, h.audio));
      const Frame sent = MakeFrame(payloads[i], o.crc);
      const std::optional<Frame> found = Equalized(o, in, 0.0);
      EXPECT_TRUE(found && *found == sent) << "offset " << offset << ", room " << i;
      EXPECT_FALSE(Equalized(o, in, offset - 0.005).has_value()) << "offset " << offset << ", room " << i;
      EXPECT_FALSE(Equalized(o, in, offset + 0.005).has_value()) << "offset " << offset << ", room " << i;
    }
  }
}

TEST(FskEqualizer, OffersEachPassUntilOneIsAcceptedWithItsErrorEventsWeakestFirst) {
  // Deep noise (white, as loud as the packet over the whole band) in a room with RT60 0.3 s and
  // DRR 0 dB: still read, but with many competitor paths weighed close to the best.
  ModemOptions o;
  const std::vector<std::uint8_t> data = {0xC3, 0x3C, 0x5A, 0xA5};
  const Heard h = HeardThrough(o, data, MeasuredLikeResponse(0.3, 0.0, o.sample_rate, 62), kMeasuredLikeDelay, 0.0, 0.0, 63);
  const EqualizerInput in = InputOf(h, Filter(o, h.audio));
  const std::complex<double>* const heard[2] = {in.heard[0].data(), in.heard[1].data()};
  const FskEqualizer equalizer(o);
  // Accepted at once: one offer.
  int offers = 0;
  SoftFrame soft{};
  ErrorEvents events;
  EXPECT_TRUE(equalizer.Equalize(heard, in.at.data(), 0.0, [&](const SoftFrame& s, const ErrorEvents& e) {
    ++offers;
    soft = s;
    events = e;
    return true;
  }));
  EXPECT_EQ(offers, 1);
  EXPECT_EQ(HardFrame(soft), MakeFrame(data, o.crc));
  // Never accepted: the later passes, refitted on the earlier decisions, offer theirs too, and
  // the equaliser gives up.
  offers = 0;
  EXPECT_FALSE(equalizer.Equalize(heard, in.at.data(), 0.0, [&](const SoftFrame&, const ErrorEvents&) {
    ++offers;
    return false;
  }));
  EXPECT_GE(offers, 2);
  // Each error event names data bits (byte * 8 + bit), each once, and the events come weakest
  // first: an event's weakness is its least sure bit's.
  ASSERT_GE(events.size(), 2u);  // 14 when written
  double weakest_before = 0.0;
  for (const std::vector<int>& event : events) {
    ASSERT_FALSE(event.empty());
    double weakest = 1e300;
    for (std::size_t a = 0; a < event.size(); ++a) {
      ASSERT_GE(event[a], 0);
      ASSERT_LT(event[a], kFrameDataBits);
      for (std::size_t b = a + 1; b < event.size(); ++b) EXPECT_NE(event[a], event[b]);
      weakest = std::min(weakest, static_cast<double>(std::abs(soft[static_cast<std::size_t>(event[a])])));
    }
    EXPECT_GE(weakest, weakest_before);
    weakest_before = weakest;
  }
}

TEST(FskEqualizer, MakesNoPacketOfNoise) {
  // In-band noise through a room, read on the nominal clock as if a packet's break had been
  // found in it: the frame's 14 start and stop bits, decided freely, hardly ever all come out
  // right, so hardly anything is offered, and nothing that checks.
  ModemOptions o;
  int offers = 0, packets = 0;
  for (unsigned seed = 0; seed < 20; ++seed) {
    RoomOptions room;
    room.response = MeasuredLikeResponse(0.3, 3.0, o.sample_rate, 90 + seed);
    Heard h;
    h.audio = RenderRoom(BandNoise(static_cast<std::size_t>(0.6 * o.sample_rate), o.sample_rate, 2000.0, 4000.0, 80 + seed),
                         o.sample_rate, room);
    h.first = 0.1 * o.sample_rate;
    h.per_bit = SamplesPerBit(o);
    int offered = 0;
    packets += Equalized(o, InputOf(h, Filter(o, h.audio)), 0.0, &offered).has_value();
    offers += offered;
  }
  EXPECT_EQ(packets, 0);
  EXPECT_LE(offers, 2);  // 0 when written
}

}  // namespace
}  // namespace nava_modem
