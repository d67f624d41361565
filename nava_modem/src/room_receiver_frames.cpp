// The `room` receiver's long frames (room_frame.h): chirp B found after A with the header between
// them, then chirp C where the header puts it. The rest of the receiver is room_receiver.cpp.
#include <algorithm>
#include <cmath>

#include "nava_modem/chirp_alignment.h"
#include "nava_modem/room_receiver.h"

namespace nava_modem {
namespace {

// How far from where the header puts it chirp C may start: the header's clock, measured over
// A to B's 0.76 s to a few hundredths of a percent, is trusted to this fraction of the payload's
// length (a speaker moving at 1 m/s changes it by 0.3 %), plus this many seconds.
constexpr double kClockReach = 0.004, kPlaceReachS = 0.010;

}  // namespace

void RoomReceiver::BeginFrame(const ChirpPeak& peak) {
  const double fs = modem_.sample_rate;
  const double nominal = decoder_.header_length();
  const double shortest = nominal * (1.0 - options_.max_rate_error), longest = nominal * (1.0 + options_.max_rate_error);
  auto start = [&](const ChirpPeak& a) {
    for (double aligned : AlignedPosts(detector_, fs, a, peak)) {
      const std::optional<RoomHeaderFound> found = decoder_.DecodeHeader(symbols_, history_, a, aligned);
      if (!found) continue;
      LongFrame frame{a, peak, aligned, *found, ShapeOf(detector_, fs, peak), 0.0, 0.0, std::nullopt};
      const double payload = decoder_.PayloadLength(found->header) * found->stretch;
      frame.c_at = peak.sample + payload;
      frame.c_reach = kClockReach * payload + kPlaceReachS * fs;
      frames_.push_back(std::move(frame));
      return true;
    }
    return false;
  };
  bool paired = false;
  for (const Heard& h : heard_) {
    const double d = peak.sample - h.peak.sample;
    if (d < shortest || d > longest) continue;
    paired = true;
    if (start(h.peak)) return;
  }
  if (paired) return;
  // Chirp A may have been too faint for the detector on its own: look for it where it must be.
  const double from = std::max(decoded_until_, peak.sample - longest);
  const std::optional<ChirpPeak> a = StrongestChirpIn(detector_, fs, from, peak.sample - shortest);
  if (a) start(*a);
}

RxEvent RoomReceiver::DecodeFrame(LongFrame& frame, const ChirpPeak& c) {
  std::vector<double> tries = LineUpShape(detector_, modem_.sample_rate, frame.b_shape, c.sample, kAlignReachS, 2);
  tries.push_back(c.sample);
  for (double at : tries) {
    RxEvent ev = decoder_.DecodePayload(symbols_, history_, frame.a, frame.b, frame.found, c, at);
    if (ev.kind == RxEvent::Kind::kPacket) {
      if (options_.time_arrivals) ev.arrival = arrival_.Time(history_, frame.a.sample, frame.aligned_b);
      return ev;
    }
    if (!frame.failure || ev.quality > frame.failure->quality) frame.failure = std::move(ev);
  }
  return *frame.failure;
}

void RoomReceiver::OnFrameDecoded(RxEvent frame, double c, std::vector<RxEvent>& events) {
  const double from = frame.start - 1e-9, to = frame.end + 1e-9;
  events.erase(std::remove_if(events.begin(), events.end(),
                              [&](const RxEvent& e) { return e.kind == RxEvent::Kind::kNoise && e.start >= from && e.end <= to; }),
               events.end());
  Emit(std::move(frame), c, events);
}

bool RoomReceiver::CompleteFrame(const ChirpPeak& peak, std::vector<RxEvent>& events) {
  for (auto it = frames_.begin(); it != frames_.end(); ++it) {
    if (std::abs(peak.sample - it->c_at) > it->c_reach) continue;
    RxEvent ev = DecodeFrame(*it, peak);
    if (ev.kind == RxEvent::Kind::kPacket) {
      frames_.erase(it);
      OnFrameDecoded(std::move(ev), peak.sample, events);
      return true;
    }
  }
  return false;
}

void RoomReceiver::ExpireFrames(std::int64_t now, std::vector<RxEvent>& events) {
  std::vector<LongFrame> expired;
  for (auto it = frames_.begin(); it != frames_.end();) {
    if (it->c_at + it->c_reach + static_cast<double>(lookahead_) < static_cast<double>(now)) {
      expired.push_back(std::move(*it));
      it = frames_.erase(it);
    } else {
      ++it;
    }
  }
  const double fs = modem_.sample_rate;
  for (LongFrame& frame : expired) {
    if (frame.b.sample < decoded_until_) continue;  // inside a frame decoded since
    // Chirp C where it must be, too faint for the detector on its own.
    if (const std::optional<ChirpPeak> c = StrongestChirpIn(detector_, fs, frame.c_at - frame.c_reach, frame.c_at + frame.c_reach)) {
      RxEvent ev = DecodeFrame(frame, *c);
      if (ev.kind == RxEvent::Kind::kPacket) OnFrameDecoded(std::move(ev), c->sample, events);
    }
    // A frame that does not decode reports nothing of its own: its chirps, and what was heard
    // within it, were judged and held as if it had not begun (Deliver).
  }
}

}  // namespace nava_modem
