// The nava receiver's diagnostics (fsk_diagnostics.h): a decoded packet's trace agrees with its
// event stage by stage, a lost packet's trace shows the stage that lost it, and tracing changes
// nothing that is decoded.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/frame.h"
#include "nava_modem/fsk_diagnostics.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/fsk_receiver.h"
#include "test_signals.h"

namespace nava_modem {
namespace {

std::vector<RxEvent> Decode(const ModemOptions& o, const std::vector<float>& audio, std::vector<BreakTrace>* traces,
                            ReceiverOptions ro = {}) {
  FskReceiver rx(o, ro);
  rx.SetDiagnostics(traces);
  std::vector<RxEvent> events;
  rx.Process(audio.data(), audio.size(), events);
  rx.Flush(events);
  return events;
}

// `packet` with `before` s of silence before it and 0.5 s after.
std::vector<float> Padded(const ModemOptions& o, const std::vector<float>& packet, double before) {
  std::vector<float> audio(static_cast<std::size_t>(before * o.sample_rate), 0.0f);
  audio.insert(audio.end(), packet.begin(), packet.end());
  audio.insert(audio.end(), static_cast<std::size_t>(0.5 * o.sample_rate), 0.0f);
  return audio;
}

// Every field of an event, NaN equal to NaN (a noise event's arrival).
void ExpectSameEvent(const RxEvent& a, const RxEvent& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.noise, b.noise);
  EXPECT_EQ(a.data, b.data);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.level_db, b.level_db);
  EXPECT_EQ(a.quality, b.quality);
  EXPECT_EQ(a.fixed_bits, b.fixed_bits);
  EXPECT_EQ(a.rate_error, b.rate_error);
  EXPECT_EQ(a.clarity, b.clarity);
  EXPECT_TRUE(a.arrival == b.arrival || (std::isnan(a.arrival) && std::isnan(b.arrival))) << a.arrival << " " << b.arrival;
}

// What every trace must say of itself, whatever became of its break: the stage its outcome
// names is the one whose verdict it carries.
void ExpectConsistent(const BreakTrace& t) {
  bool clock_read = false;
  for (const ClockSearchTrace& s : t.searches) {
    for (const ClockTrial& c : s.clocks) clock_read = clock_read || c.verdict.kind == RxEvent::Kind::kPacket;
  }
  bool equalized = false;
  for (const EqualizerTrial& e : t.equalizer) equalized = equalized || e.passed;
  switch (t.outcome) {
    case BreakOutcome::kPacketOnClock:
      ASSERT_TRUE(t.reported);
      ASSERT_FALSE(t.searches.empty());
      ASSERT_FALSE(t.searches.back().clocks.empty());
      EXPECT_EQ(t.searches.back().clocks.back().verdict.data, t.event.data);  // the last clock tried read it
      EXPECT_TRUE(t.equalizer.empty());
      break;
    case BreakOutcome::kPacketByEqualizer:
      ASSERT_TRUE(t.reported);
      EXPECT_FALSE(clock_read);
      ASSERT_FALSE(t.equalizer.empty());
      EXPECT_TRUE(t.equalizer.back().passed);  // the last one tried read it
      EXPECT_EQ(t.event.kind, RxEvent::Kind::kPacket);
      break;
    case BreakOutcome::kNotRead:
      ASSERT_TRUE(t.reported);
      EXPECT_FALSE(clock_read);
      EXPECT_FALSE(t.equalizer.empty());
      EXPECT_FALSE(equalized);
      EXPECT_EQ(t.event.kind, RxEvent::Kind::kNoise);
      break;
    case BreakOutcome::kNoClock:
      EXPECT_TRUE(t.reported);
      EXPECT_EQ(t.event.kind, RxEvent::Kind::kNoise);
      break;
    case BreakOutcome::kSuperseded:
    case BreakOutcome::kMuted:
      EXPECT_FALSE(t.reported);
      EXPECT_TRUE(t.searches.empty());  // dropped before its packet was read
      break;
    case BreakOutcome::kPending:
      ADD_FAILURE() << "a break still pending after the flush";
      break;
  }
}

TEST(FskDiagnostics, ADecodedPacketsTraceAgreesWithItsEvent) {
  ModemOptions o;
  const std::vector<std::uint8_t> data = {1, 2, 3, 4};
  std::vector<BreakTrace> traces;
  const auto events = Decode(o, Padded(o, FskModulator(o).ModulatePacket(data), 1.0), &traces);
  ASSERT_EQ(events.size(), 1u);
  ASSERT_EQ(traces.size(), 1u);
  const BreakTrace& t = traces[0];
  ExpectConsistent(t);
  EXPECT_EQ(t.outcome, BreakOutcome::kPacketOnClock);
  ExpectSameEvent(t.event, events[0]);
  EXPECT_EQ(t.clarity, events[0].clarity);
  // The break: its SPACE-to-MARK step 20 bits after the packet's start at 1 s, where the
  // detector found it (within a bit), and the known bits left it there.
  const double step_s = 1.0 + kBreakSpaceBits / o.baud, bit_s = 1.0 / o.baud;
  EXPECT_NEAR(t.scale.Seconds(t.detected_step), step_s, bit_s);
  ASSERT_TRUE(t.settled);
  EXPECT_EQ(t.settled_step, t.detected_step);
  EXPECT_NEAR(t.scale.Samples(t.detected_step), step_s * o.sample_rate, bit_s * o.sample_rate);
  // The model: both tones heard, far above a floor of nothing.
  ASSERT_EQ(t.searches.size(), 1u);
  const ClockSearchTrace& search = t.searches[0];
  EXPECT_EQ(search.break_step, t.settled_step);
  for (int tone = 0; tone < 2; ++tone) {
    EXPECT_GT(search.model.level[tone], 0.01) << "tone " << tone;
    EXPECT_LT(search.model.floor[tone], 0.01 * search.model.level[tone]) << "tone " << tone;
  }
  // The clock read on: the event's start, end and rate are its reading's, and its reading's
  // frame bits are the packet's.
  ASSERT_FALSE(search.clocks.empty());
  const ClockTrial& read = search.clocks.back();
  EXPECT_EQ(read.verdict.kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(read.verdict.data, data);
  EXPECT_DOUBLE_EQ(t.scale.Seconds(read.fine.start - kBreakSpaceBits * read.fine.period), events[0].start);
  EXPECT_DOUBLE_EQ(t.scale.RateError(read.fine.period), events[0].rate_error);
  EXPECT_EQ(read.reading.start, events[0].start);
  EXPECT_EQ(read.reading.end, events[0].end);
  EXPECT_EQ(read.reading.rate_error, events[0].rate_error);
  EXPECT_NEAR(t.scale.Seconds(read.fine.start), step_s, 0.1 * bit_s);
  EXPECT_NEAR(t.scale.RateError(read.candidate.period), 0.0, 0.005);
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame(data, o.crc));
  for (int j = 0; j < kFrameBits; ++j) {
    EXPECT_EQ(read.reading.hard[static_cast<std::size_t>(j)], bits[static_cast<std::size_t>(kBreakSpaceBits + kBreakMarkBits + j)]) << j;
  }
}

TEST(FskDiagnostics, ACutPacketsTraceShowsWhereItWasLost) {
  ModemOptions o;
  // Cut two thirds in: the break and the header are heard, the rest of the frame is not.
  const std::vector<float> packet = FskModulator(o).ModulatePacket({9, 9, 9, 9});
  const std::vector<float> cut(packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(packet.size() * 2 / 3));
  std::vector<BreakTrace> traces;
  const auto events = Decode(o, Padded(o, cut, 0.3), &traces);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, RxEvent::Kind::kNoise);
  ASSERT_EQ(traces.size(), 1u);
  const BreakTrace& t = traces[0];
  ExpectConsistent(t);
  ExpectSameEvent(t.event, events[0]);
  // Found where it was sent, its tones modelled and its clocks read; every reading was noise,
  // and so was every reading the equaliser made: lost at the frame, not at the break.
  EXPECT_NEAR(t.scale.Seconds(t.detected_step), 0.3 + kBreakSpaceBits / o.baud, 1.0 / o.baud);
  EXPECT_EQ(t.outcome, BreakOutcome::kNotRead);
  ASSERT_FALSE(t.searches.empty());
  for (const ClockSearchTrace& s : t.searches) {
    EXPECT_GT(s.model.level[0], 0.01);
    ASSERT_FALSE(s.clocks.empty());
    for (const ClockTrial& c : s.clocks) {
      EXPECT_EQ(c.verdict.kind, RxEvent::Kind::kNoise);
      // The header was heard: the UART framed it, so the frame was lost at its CRC.
      const UartByte header = ReadUartByte(c.reading.hard.data());
      if (header.framed && header.value == kHeader) {
        EXPECT_EQ(c.verdict.noise, RxEvent::Noise::kBadCrc);
      }
    }
  }
  EXPECT_EQ(t.searches[0].clocks[0].verdict.noise, events[0].noise);
}

TEST(FskDiagnostics, TracingChangesNothingDecoded) {
  // Packets in white noise deep enough that some are read on a clock, some only by the
  // equaliser and some lost (at -2 dB in band: 4, 8 and 5 of 17 breaks when written).
  ModemOptions o;
  const auto payloads = test_signals::RandomPayloads(16, 7);
  std::vector<float> audio = test_signals::PacketTrain(o, payloads, 0.3, 0.002);
  test_signals::AddNoise(audio, o.amplitude * o.amplitude / 2.0, -2.0, o.sample_rate, 8);
  ReceiverOptions ro;
  ro.carrier_threshold_db = -40.0;
  const auto plain = Decode(o, audio, nullptr, ro);
  std::vector<BreakTrace> traces;
  const auto traced = Decode(o, audio, &traces, ro);
  ASSERT_EQ(traced.size(), plain.size());
  for (std::size_t k = 0; k < plain.size(); ++k) {
    SCOPED_TRACE(k);
    ExpectSameEvent(traced[k], plain[k]);
  }
  // Each break reported has its event among the events, in order.
  std::size_t next = 0;
  int reported = 0, on_clock = 0, by_equalizer = 0, not_read = 0;
  for (const BreakTrace& t : traces) {
    ExpectConsistent(t);
    on_clock += t.outcome == BreakOutcome::kPacketOnClock;
    by_equalizer += t.outcome == BreakOutcome::kPacketByEqualizer;
    not_read += t.outcome == BreakOutcome::kNotRead;
    if (!t.reported) continue;
    ++reported;
    while (next < traced.size() && traced[next].end != t.event.end) ++next;
    ASSERT_LT(next, traced.size()) << "a trace's event is not among the events";
    ExpectSameEvent(t.event, traced[next]);
  }
  EXPECT_GE(reported, 16);
  EXPECT_GT(on_clock, 0);
  EXPECT_GT(by_equalizer, 0);
  EXPECT_GT(not_read, 0);
}

TEST(FskDiagnostics, AMutedBreakIsTracedAsMutedAndNothingOnceTheSinkIsTakenAway) {
  ModemOptions o;
  const std::vector<float> audio = Padded(o, FskModulator(o).ModulatePacket({5, 6, 7, 8}), 0.3);
  FskReceiver rx(o, {});
  std::vector<BreakTrace> traces;
  std::vector<RxEvent> events;
  rx.SetDiagnostics(&traces);
  // Up to the middle of the frame: the break is found and being collected; then the link sends.
  const std::size_t half = static_cast<std::size_t>((0.3 + 70.0 / o.baud) * o.sample_rate);
  rx.Process(audio.data(), half, events);
  rx.SetMuted(true);
  rx.Process(audio.data() + half, audio.size() - half, events);
  EXPECT_TRUE(events.empty());
  ASSERT_EQ(traces.size(), 1u);
  ExpectConsistent(traces[0]);
  EXPECT_EQ(traces[0].outcome, BreakOutcome::kMuted);
  // Heard again with no sink: the packet is decoded, and nothing more recorded.
  rx.SetMuted(false);
  rx.SetDiagnostics(nullptr);
  rx.Process(audio.data(), audio.size(), events);
  rx.Flush(events);
  EXPECT_EQ(events.size(), 1u);
  EXPECT_EQ(traces.size(), 1u);
}

}  // namespace
}  // namespace nava_modem
