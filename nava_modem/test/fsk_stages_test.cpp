// The nava receiver's stages alone: the ring of the tone filters' outputs, the break detector
// and the tone model, on made-up filter outputs whose answer is known and on a packet heard
// through a measured room.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/break_detector.h"
#include "nava_modem/clock_search.h"
#include "nava_modem/first_arrival.h"
#include "nava_modem/frame.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/nava_packet_timer.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/tone_filters.h"
#include "nava_modem/tone_model.h"
#include "nava_modem/tone_ring.h"

namespace nava_modem {
namespace {

TEST(ToneRing, KeepsTheLastStepsAndSilenceBeforeTheFirst) {
  ToneRing ring(8);
  EXPECT_EQ(ring.mark_power(-1), 0.0);
  for (int n = 0; n < 12; ++n) ring.Put(n, n, 2.0 * n, {1.0 * n, -1.0}, {0.0, 0.5 * n});
  EXPECT_EQ(ring.mark_power(11), 11.0);
  EXPECT_EQ(ring.space_power(11), 22.0);
  EXPECT_EQ(ring.difference(10), -10.0);
  EXPECT_EQ(ring.sum(10), 30.0);
  EXPECT_EQ(ring.mark(9), std::complex<double>(9.0, -1.0));
  EXPECT_EQ(ring.space(9), std::complex<double>(0.0, 4.5));
  EXPECT_EQ(ring.mark_power(3), 11.0);  // overwritten: step 3 lies 8 steps before step 11
  EXPECT_THROW(ToneRing(12), std::invalid_argument);
  EXPECT_THROW(ToneRing(0), std::invalid_argument);
}

constexpr double kPerBit = 10.0;  // filter steps a bit in the made-up outputs

// A break's filter outputs, step by step, its SPACE-to-MARK step at step `at` (kPerBit steps a
// bit): SPACE for kBreakSpaceBits bits at `space`, then MARK at `mark`; each filter also holds
// `floor`, and SPACE's tail, `tail` at the step, decays by `decay` a bit after it.
ToneRing Break(double at, double mark, double space, double floor, double tail, double decay) {
  ToneRing ring(1024);
  for (int n = 0; n < 1024; ++n) {
    const double bit = (n - at) / kPerBit;  // bits after the step
    const bool in_space = bit < 0.0 && bit >= -kBreakSpaceBits;
    const double space_tail = bit >= 0.0 ? tail * std::pow(decay, bit) : 0.0;
    const double m = floor + (bit >= 0.0 ? mark : 0.0);
    const double s = floor + (in_space ? space : 0.0) + space_tail;
    ring.Put(n, m, s, {std::sqrt(m), 0.0}, {std::sqrt(s), 0.0});
  }
  return ring;
}

TEST(ToneModelStage, ReadsSpacesTailDecayAndEachTonesLevel) {
  const double at = 400.0, decay = 0.9;
  const ToneRing ring = Break(at, 2.0, 8.0, 0.01, 0.8, decay);
  const ToneModel model = FitToneModel(ring, at, kPerBit);
  EXPECT_NEAR(model.decay, decay, 1e-3);  // three group means of a geometric tail give it exactly
  EXPECT_NEAR(model.floor[1], 0.01, 0.01);
  EXPECT_NEAR(model.floor[0], 0.01, 1e-9);  // MARK's filter in the SPACE half
  EXPECT_NEAR(model.level[1], 8.0, 0.8);
  EXPECT_GT(model.gain, 0.0);
  EXPECT_GT(model.tail[1], 0.0);
  // MARK's level, less the tail the model lets MARK's own bits build (the same room): near 2.
  EXPECT_NEAR(model.level[0], 2.0, 0.4);
}

TEST(ToneModelStage, ADryBreakHasNoTail) {
  const double at = 400.0;
  const ToneRing ring = Break(at, 2.0, 8.0, 0.01, 0.0, 0.0);
  const ToneModel model = FitToneModel(ring, at, kPerBit);
  EXPECT_EQ(model.decay, 0.0);
  EXPECT_EQ(model.gain, 0.0);
  EXPECT_NEAR(model.floor[1], 0.01, 1e-9);
  EXPECT_NEAR(model.level[0], 2.0, 1e-6);
  EXPECT_NEAR(model.level[1], 8.0, 1e-6);
}

// The detector's step at each filter step, from step 0.
std::vector<double> Steps(const ToneRing& ring, std::int64_t window, std::int64_t count) {
  BreakDetector detector(window);
  std::vector<double> steps;
  for (std::int64_t n = 0; n < count; ++n) {
    detector.Update(ring, n);
    steps.push_back(n >= 2 * window ? detector.Step() : -1.0);
  }
  return steps;
}

TEST(BreakDetectorStage, PeaksWhereItsWindowsStraddleTheBreak) {
  const double at = 400.0;
  const std::int64_t window = 100;  // 10 bits
  const std::vector<double> steps = Steps(Break(at, 1.0, 1.0, 1e-4, 0.0, 0.0), window, 700);
  const auto peak = std::max_element(steps.begin(), steps.end());
  EXPECT_GT(*peak, 0.95);
  // The later window is all MARK, the earlier all SPACE: the window's end lies a window past the step.
  EXPECT_NEAR(static_cast<double>(peak - steps.begin()) - static_cast<double>(window), at, 1.0);
}

TEST(BreakDetectorStage, FindsAFaintMarkUnderSpacesTail) {
  // MARK 15 dB under SPACE, SPACE's tail 6 dB over MARK at the step and dying slowly (a long
  // reverberation): summed, the tones never step from SPACE to MARK; each on its own scale they do.
  const double at = 400.0;
  const std::vector<double> steps = Steps(Break(at, 1.0, 31.6, 1e-4, 4.0, 0.95), 100, 700);
  EXPECT_GT(*std::max_element(steps.begin(), steps.end()), ReceiverOptions{}.detect_threshold);
}

TEST(BreakDetectorStage, NoiseAloneStaysUnderTheThreshold) {
  std::mt19937 rng(3);
  std::exponential_distribution<double> power(1.0);  // a Rayleigh envelope's power
  ToneRing ring(4096);
  for (int n = 0; n < 4000; ++n) ring.Put(n, power(rng), power(rng), {}, {});
  const std::vector<double> steps = Steps(ring, 100, 4000);
  EXPECT_LT(*std::max_element(steps.begin(), steps.end()), ReceiverOptions{}.detect_threshold);
  EXPECT_THROW(BreakDetector(0), std::invalid_argument);
}

TEST(BreakDetectorStage, FindsABreakHeardThroughAMeasuredRoom) {
  const std::filesystem::path file = std::filesystem::path(MULTIROBOT_AUDIO_REALROOMS) / "pori_s1_r1_b.wav";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  ModemOptions modem;
  const double fs = modem.sample_rate;
  const std::vector<float> packet = FskModulator(modem).ModulatePacket({0x12, 0x34, 0x56, 0x78});
  std::vector<float> clean(static_cast<std::size_t>(0.3 * fs), 0.0f);
  const double sent = static_cast<double>(clean.size());
  clean.insert(clean.end(), packet.begin(), packet.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.5 * fs), 0.0f);
  RoomOptions room;
  room.response = LoadImpulseResponse(file.string(), 0, fs);
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = 20.0;
  const std::vector<float> heard = RenderRoom(clean, fs, room);
  // Where the break's step is heard, in filter steps: the packet's start, its SPACE half and
  // the room's delay to its direct sound.
  ToneFilters filters(modem);
  const double per_bit = SamplesPerBit(modem) / filters.step();
  const double truth = (sent + LeadingEdge(room.response, fs) * fs) / filters.step() + kBreakSpaceBits * per_bit;
  const std::int64_t window = std::lround(10.0 * per_bit);
  ToneRing ring(4096);
  BreakDetector detector(window);
  std::int64_t n = 0, peak_at = 0;
  double peak = -1.0;
  for (float x : heard) {
    if (!filters.Push(x)) continue;
    ring.Put(n, filters.mark_power(), filters.space_power(), {filters.mark_re(), filters.mark_im()},
             {filters.space_re(), filters.space_im()});
    detector.Update(ring, n);
    if (n >= 2 * window && detector.Step() > peak) peak = detector.Step(), peak_at = n;
    ++n;
  }
  EXPECT_GT(peak, ReceiverOptions{}.detect_threshold);
  // As the receiver places it: the windows' boundary, less the filters' half window.
  const double found = static_cast<double>(peak_at - window) - filters.window() / 2.0;
  EXPECT_NEAR(found, truth, 2.0 * per_bit) << "found at bit " << (found - truth) / per_bit << " from the break";
}

// A reading of the frame carrying `data`, every bit decided as sure as `sure` (a log-likelihood
// ratio), the tones heard at power 1 when on and 0.01 when off.
FrameReading Reading(const std::vector<std::uint8_t>& data, double sure = 8.0) {
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame(data, CrcVariant::kCcittFalse));
  FrameReading r;
  for (int j = 0; j < kFrameBits; ++j) {
    const std::uint8_t bit = bits[static_cast<std::size_t>(kBreakSpaceBits + kBreakMarkBits + j)];
    r.hard[static_cast<std::size_t>(j)] = bit;
    r.heard[0][static_cast<std::size_t>(j)] = bit ? 1.0 : 0.01;
    r.heard[1][static_cast<std::size_t>(j)] = bit ? 0.01 : 1.0;
    const int pos = j % kBitsPerByte;
    if (pos >= 1 && pos <= 8) r.soft[static_cast<std::size_t>((j / kBitsPerByte) * 8 + pos - 1)] = static_cast<float>(bit ? sure : -sure);
  }
  r.start = 1.0;
  r.end = 1.3;
  r.level_db = -20.0;
  r.quality = 0.5;
  return r;
}

// Bit `bit` of the frame (0 = the header's start bit) read as `value`, as surely as the tones'
// powers `on` and `off` say (and the log-likelihood ratio `sure`): its first decision, what the
// tones heard and its soft decision all agree.
void SetBit(FrameReading& r, int bit, int value, double on = 1.0, double off = 0.01, float sure = 8.0f) {
  const std::size_t j = static_cast<std::size_t>(bit);
  r.hard[j] = static_cast<std::uint8_t>(value);
  r.heard[0][j] = value ? on : off;
  r.heard[1][j] = value ? off : on;
  const int pos = bit % kBitsPerByte;
  if (pos >= 1 && pos <= 8) r.soft[static_cast<std::size_t>((bit / kBitsPerByte) * 8 + pos - 1)] = value ? sure : -sure;
}

// Bit `bit` read as the other value, unsure.
void Flip(FrameReading& r, int bit) { SetBit(r, bit, !r.hard[static_cast<std::size_t>(bit)], 0.6, 0.4, 0.2f); }

TEST(AcceptanceStage, AReadingWhoseCrcPassesIsThePacket) {
  const RxEvent ev = AcceptReading(Reading({1, 2, 3, 4}), CrcVariant::kCcittFalse, 2);
  ASSERT_EQ(ev.kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(ev.data, std::vector<std::uint8_t>({1, 2, 3, 4}));
  EXPECT_EQ(ev.fixed_bits, 0);
  EXPECT_EQ(ev.start, 1.0);
  EXPECT_EQ(ev.end, 1.3);
  EXPECT_EQ(ev.level_db, -20.0);
  EXPECT_EQ(ev.quality, 0.5);
}

TEST(AcceptanceStage, RepairsAnUnsureBitOnlyOnAClockNearTheNominalRate) {
  FrameReading r = Reading({0xA5, 0x5A, 0x0F, 0xF0});
  Flip(r, 2 * kBitsPerByte + 3);  // a data bit of the second data byte
  const RxEvent repaired = AcceptReading(r, CrcVariant::kCcittFalse, 2);
  ASSERT_EQ(repaired.kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(repaired.data, std::vector<std::uint8_t>({0xA5, 0x5A, 0x0F, 0xF0}));
  EXPECT_EQ(repaired.fixed_bits, 1);
  EXPECT_EQ(AcceptReading(r, CrcVariant::kCcittFalse, 0).noise, RxEvent::Noise::kBadCrc);
  r.rate_error = 0.02;  // a clock this far off is more often a wrong fit than a sound card
  const RxEvent far = AcceptReading(r, CrcVariant::kCcittFalse, 2);
  EXPECT_EQ(far.kind, RxEvent::Kind::kNoise);
  EXPECT_EQ(far.noise, RxEvent::Noise::kBadCrc);
  EXPECT_EQ(far.rate_error, 0.02);
}

TEST(AcceptanceStage, NoRepairWhereTheFramingBitsAreWrong) {
  FrameReading r = Reading({9, 8, 7, 6});
  Flip(r, 2 * kBitsPerByte + 3);
  // Three start bits read as MARK: more wrong framing than a repair should trust.
  for (int c = 2; c <= 4; ++c) r.hard[static_cast<std::size_t>(c * kBitsPerByte)] = 1;
  EXPECT_EQ(AcceptReading(r, CrcVariant::kCcittFalse, 2).kind, RxEvent::Kind::kNoise);
}

TEST(AcceptanceStage, NamesTheNoiseByWhatWasFramed) {
  FrameReading nothing = Reading({1, 2, 3, 4});
  for (int j = 0; j < kFrameBits; ++j) SetBit(nothing, j, 0);  // every stop bit SPACE: nothing framed
  EXPECT_EQ(AcceptReading(nothing, CrcVariant::kCcittFalse, 2).noise, RxEvent::Noise::kZeroByte);
  FrameReading wrong_header = Reading({1, 2, 3, 4});
  for (int pos = 1; pos <= 8; ++pos) SetBit(wrong_header, pos, 1);  // header 0xFF: framed, not 0x55
  EXPECT_EQ(AcceptReading(wrong_header, CrcVariant::kCcittFalse, 2).noise, RxEvent::Noise::kOneByte);
  FrameReading bad_data = Reading({1, 2, 3, 4});
  for (int pos = 1; pos <= 8; ++pos) SetBit(bad_data, kBitsPerByte + pos, 1);  // 0x01 read surely as 0xFF
  EXPECT_EQ(AcceptReading(bad_data, CrcVariant::kCcittFalse, 2).noise, RxEvent::Noise::kBadCrc);
}

// A whole packet's filter outputs, as one-bit tone filters give them without noise: each tone's
// amplitude the share of the last `period` steps its tone sounded, squared (a bit's tone is
// clearest at the bit's end). The break's first SPACE bit begins at step `first`.
ToneRing Packet(const std::vector<std::uint8_t>& data, double first, double period) {
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame(data, CrcVariant::kCcittFalse));
  auto tone_at = [&](double t) {  // 1 MARK, 0 SPACE, -1 silence
    const double bit = std::floor((t - first) / period);
    return bit >= 0.0 && bit < kPacketBits ? static_cast<int>(bits[static_cast<std::size_t>(bit)]) : -1;
  };
  ToneRing ring(4096);
  constexpr int kSub = 16;  // points a step, to integrate the window
  for (int n = 0; n < 4096; ++n) {
    double mark = 0.0, space = 0.0;
    const int points = static_cast<int>(std::lround(period * kSub));
    for (int q = 0; q < points; ++q) {
      const int tone = tone_at(n + 1 - period + (q + 0.5) / kSub);  // step n holds sample n and those before
      mark += tone == 1;
      space += tone == 0;
    }
    mark /= points;
    space /= points;
    ring.Put(n, mark * mark, space * space, {}, {});
  }
  return ring;
}

TEST(ClockSearchStage, FindsTheSendersRateAndThePhaseOfItsBreak) {
  const double per_bit = 10.0, first = 300.0;
  for (const double rate : {-0.02, 0.0, 0.013}) {
    const double period = per_bit / (1.0 + rate);  // a fast sender's bits are shorter
    const ToneRing ring = Packet({0x31, 0x41, 0x59, 0x26}, first, period);
    const double mark = first + kBreakSpaceBits * period;  // where its break's first MARK bit begins
    // The detector's estimate a bit and a half late, as a room's tail makes it.
    const double estimate = mark + 1.5 * per_bit;
    const NormalizedTones tones(ring, ToneModel{}, 0, 4096, 4096);
    const std::vector<ClockFit> candidates = ClockCandidates(tones, estimate, per_bit, 2.5 * per_bit, 0.035, 3);
    ASSERT_FALSE(candidates.empty());
    const ClockFit fine = BestClock(tones, candidates[0].start, candidates[0].period, per_bit / 16.0, per_bit / 64.0,
                                    kClockRateStep, 0.0005);
    EXPECT_NEAR(per_bit / fine.period - 1.0, rate, 0.003) << "rate " << rate;
    EXPECT_NEAR(fine.start, mark, 0.5 * per_bit) << "rate " << rate;
    // The fit is worse a bit off, and worse at the wrong rate.
    EXPECT_GT(fine.metric, ClockFitMetric(tones, fine.start + per_bit, fine.period));
    EXPECT_GT(fine.metric, ClockFitMetric(tones, fine.start, fine.period * 1.03));
  }
}

TEST(ClockSearchStage, WhatIsNotHeardYetIsNoEvidence) {
  const ToneRing ring = Packet({1, 2, 3, 4}, 300.0, 10.0);
  const NormalizedTones heard(ring, ToneModel{}, 0, 4096, 4096), half(ring, ToneModel{}, 0, 4096, 900);
  EXPECT_NE(heard(1000), 0.0);
  EXPECT_EQ(half(1000), 0.0);
  EXPECT_EQ(heard(5000), 0.0);  // outside the stretch
  EXPECT_GT(ClockFitMetric(heard, 500.0, 10.0), ClockFitMetric(half, 500.0, 10.0));
}

TEST(FrameReaderStage, ReadsEveryBitOnTheSendersClock) {
  const double per_bit = 10.0, first = 300.0, rate = 0.01, period = per_bit / (1.0 + rate);
  const std::vector<std::uint8_t> data = {0xDE, 0xAD, 0xBE, 0xEF};
  const ToneRing ring = Packet(data, first, period);
  ToneModel model;
  model.floor[0] = model.floor[1] = 0.01;
  const NormalizedTones tones(ring, model, 0, 4096, 4096);
  const double mark = first + kBreakSpaceBits * period;
  const FrameReading reading = ReadFrame({ring, model, tones, 10, per_bit, 0.001}, mark, period);
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame(data, CrcVariant::kCcittFalse));
  for (int j = 0; j < kFrameBits; ++j) {
    EXPECT_EQ(reading.hard[static_cast<std::size_t>(j)], bits[static_cast<std::size_t>(kBreakSpaceBits + kBreakMarkBits + j)])
        << "frame bit " << j;
  }
  // Each bit read at its end, where a one-bit filter hears it whole.
  for (int k = 0; k < kPacketBits; ++k) {
    EXPECT_NEAR(static_cast<double>(reading.at[static_cast<std::size_t>(k)]), first + (k + 1) * period - 1.0, 1.0) << "bit " << k;
  }
  EXPECT_NEAR(reading.rate_error, rate, 1e-9);
  EXPECT_NEAR(reading.start, first * 0.001, 1e-9);
  const RxEvent ev = AcceptReading(reading, CrcVariant::kCcittFalse, 2);
  ASSERT_EQ(ev.kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(ev.data, data);
  EXPECT_EQ(ev.fixed_bits, 0);
  // Half a bit off the sender's clock, the bits' ends smear into their neighbours': the
  // reading is worse, never a different packet.
  const RxEvent off = AcceptReading(ReadFrame({ring, model, tones, 10, per_bit, 0.001}, mark + 0.5 * period, period * 1.03),
                                    CrcVariant::kCcittFalse, 2);
  EXPECT_TRUE(off.kind == RxEvent::Kind::kNoise || off.data == data);
}

TEST(PacketTimerStage, TimesAPacketByItsKnownStartToAFractionOfASample) {
  ModemOptions modem;
  const double fs = modem.sample_rate;
  const std::vector<float> packet = FskModulator(modem).ModulatePacket({7, 7, 7, 7});
  std::vector<double> errors;
  for (const double delay : {0.0, 10.25, 333.6}) {  // samples of travel (a fraction too)
    std::vector<float> response(512, 0.0f);
    // A bare delay as a band-limited impulse (a windowed sinc), so that a fraction of a sample is
    // a delay too.
    for (int k = 0; k < 512; ++k) {
      const double x = k - 100.0 - std::fmod(delay, 1.0);
      const double w = std::abs(x) < 40.0 ? 0.5 + 0.5 * std::cos(M_PI * x / 40.0) : 0.0;
      response[static_cast<std::size_t>(k)] = static_cast<float>(x == 0.0 ? 1.0 : w * std::sin(M_PI * x) / (M_PI * x));
    }
    const double sent = 0.5 * fs + std::floor(delay);  // where the packet starts, with the whole samples of delay
    std::vector<float> heard(static_cast<std::size_t>(sent) + packet.size() + 1000, 0.0f);
    for (std::size_t n = 0; n < packet.size(); ++n) {
      for (int k = 0; k < 512; ++k) heard[static_cast<std::size_t>(sent) + n + static_cast<std::size_t>(k)] += packet[n] * response[static_cast<std::size_t>(k)];
    }
    NavaPacketTimer timer(modem, 0.035);
    for (float x : heard) timer.Push(x);
    // The decoder places a packet's start to within a few samples: 3 ms off here.
    const double arrival = timer.Time((sent + 100.0) / fs + 0.003);
    const double truth = sent / fs + LeadingEdge(response, fs);
    // Within a sample of the response's leading edge (nava's two tones fill the band unevenly:
    // 7 us late here), and by the same amount whatever the delay: ranging takes differences.
    EXPECT_NEAR(arrival, truth, 20e-6) << "delay " << delay;
    errors.push_back(arrival - truth);
  }
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()) - *std::min_element(errors.begin(), errors.end()), 1e-6);
}

TEST(PacketTimerStage, NoTimeForInputNoLongerHeldOrTooNarrowABand) {
  ModemOptions modem;
  const std::vector<float> packet = FskModulator(modem).ModulatePacket({1, 2, 3, 4});
  NavaPacketTimer timer(modem, 0.035);
  for (int k = 0; k < 1000; ++k) timer.Push(0.0f);
  for (float x : packet) timer.Push(x);
  EXPECT_TRUE(std::isfinite(timer.Time(1000.0 / modem.sample_rate)));
  EXPECT_TRUE(std::isnan(timer.Time(10.0)));  // not heard yet
  for (int k = 0; k < 10 * 48000; ++k) timer.Push(0.0f);
  EXPECT_TRUE(std::isnan(timer.Time(1000.0 / modem.sample_rate)));  // no longer held
  ModemOptions slow = modem;
  slow.sample_rate = 8000.0;
  NavaPacketTimer narrow(slow, 0.035);
  for (float x : FskModulator(slow).ModulatePacket({1, 2, 3, 4})) narrow.Push(x);
  EXPECT_TRUE(std::isnan(narrow.Time(0.0)));
}

}  // namespace
}  // namespace nava_modem
