#include "nava_modem/room_receiver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/chirp_alignment.h"
#include "nava_modem/room_data_search.h"
#include "nava_modem/room_modulator.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

using namespace room_phy;

// The largest clock error a decode accepts: the pairing's, and the alignment's reach.
double MaxStretchError(const ReceiverOptions& options) { return options.max_rate_error + 0.01; }

}  // namespace

RoomReceiver::RoomReceiver(const ModemOptions& modem, const ReceiverOptions& options)
    : modem_(modem),
      options_((ValidateReceiverOptions(options), options)),
      chirp_((ValidateRoomRate(modem.sample_rate), Chirp(modem.sample_rate))),
      detector_(chirp_, modem.sample_rate, ChirpDetectorOptions{}),
      arrival_(chirp_, modem.sample_rate),
      carrier_(modem.sample_rate),
      symbols_(modem.sample_rate),
      decoder_(modem.sample_rate, detector_.length(), MaxStretchError(options_), modem.crc),
      lookahead_(AlignmentLookahead(modem.sample_rate)),
      history_((room_frame::FrameSeconds(room_frame::kMaxBytes, 0) * (1.0 + options_.max_rate_error) + 1.0) *
                   modem.sample_rate +
               4.0 * detector_.length() + lookahead_) {
  if (kHighestHz * (1.0 + MaxStretchError(options_)) >= modem.sample_rate / 2.0) {
    throw std::invalid_argument("max_rate_error " + std::to_string(options_.max_rate_error) + ": a sender that fast would put " +
                                "the room profile's highest tone above the Nyquist frequency at " +
                                std::to_string(std::lround(modem.sample_rate)) + " Hz");
  }
  SetCarrierThreshold(options_.carrier_threshold_db);
}

void RoomReceiver::SetMuted(bool muted) {
  if (muted && !muted_) {
    heard_.clear();
    pending_.clear();
    frames_.clear();
    // (What waited for a frame is reported with the next samples.)
    carrier_.Reset();
  }
  muted_ = muted;
}

void RoomReceiver::Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  // In pieces shorter than the history's spare room, so that a packet found at the end of a
  // long call still has its samples.
  const std::size_t piece = static_cast<std::size_t>(0.1 * modem_.sample_rate);
  while (count > piece) {
    ProcessPiece(samples, piece, held_);
    Deliver(events);
    samples += piece;
    count -= piece;
  }
  ProcessPiece(samples, count, held_);
  Deliver(events);
}

void RoomReceiver::Deliver(std::vector<RxEvent>& events) {
  // While a long frame waits for its last chirp, what was heard meanwhile waits with it: the
  // chirps its hops pass for, its own chirps alone and the busy air are its to report if it
  // decodes (OnFrameDecoded), and are reported as they were heard if it does not.
  if (!frames_.empty()) return;
  events.insert(events.end(), std::make_move_iterator(held_.begin()), std::make_move_iterator(held_.end()));
  held_.clear();
}

void RoomReceiver::ProcessPiece(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  for (std::size_t k = 0; k < count; ++k) {
    history_.Push(samples[k]);
    if (carrier_.Push(samples[k])) {
      // A frame may still come out of busy air until the detector has judged all of it.
      const bool judged = detector_.computed() >= std::llround(carrier_.quiet_from() * modem_.sample_rate) + lookahead_;
      if (!muted_) carrier_.Step(time(), !heard_.empty() || !pending_.empty() || !judged, events);
    }
  }
  peaks_.clear();
  detector_.Process(samples, count, peaks_);
  if (muted_) {
    // What began while we were sending or deaf is our own sound.
    detector_.Blank(history_.count());
    return;
  }
  pending_.insert(pending_.end(), peaks_.begin(), peaks_.end());
  while (!pending_.empty() && detector_.computed() >= static_cast<std::int64_t>(pending_.front().sample) + lookahead_) {
    OnChirp(pending_.front(), events);
    pending_.pop_front();
  }
  const std::int64_t now = pending_.empty() ? detector_.computed() : static_cast<std::int64_t>(pending_.front().sample);
  ExpireChirps(now, events);
  ExpireFrames(now, events);
}

void RoomReceiver::Flush(std::vector<RxEvent>& events) {
  const std::vector<float> silence(static_cast<std::size_t>(modem_.sample_rate * (kPacketSeconds + 1.0)), 0.0f);
  Process(silence.data(), silence.size(), events);
  // Long frames still waiting for their last chirp: silence until its place has passed.
  while (!frames_.empty()) Process(silence.data(), silence.size(), events);
}

void RoomReceiver::Emit(RxEvent packet, double post, std::vector<RxEvent>& events) {
  // The packet's chirps, their reflections and anything heard inside it begin nothing more.
  decoded_until_ = post + static_cast<double>(detector_.length());
  while (!heard_.empty() && heard_.front().peak.sample < decoded_until_) heard_.pop_front();
  frames_.erase(std::remove_if(frames_.begin(), frames_.end(), [&](const LongFrame& f) { return f.b.sample < decoded_until_; }),
                frames_.end());
  events.push_back(std::move(packet));
  carrier_.FrameFound();
}

void RoomReceiver::OnChirp(const ChirpPeak& peak, std::vector<RxEvent>& events) {
  ExpireChirps(static_cast<std::int64_t>(peak.sample), events);
  ExpireFrames(static_cast<std::int64_t>(peak.sample), events);
  if (peak.sample < decoded_until_) return;
  if (CompleteFrame(peak, events)) return;
  const double shortest = Shortest(), longest = Longest();
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
    const double from = std::max(decoded_until_, peak.sample - longest);
    if (const std::optional<ChirpPeak> pre = StrongestChirpIn(detector_, modem_.sample_rate, from, peak.sample - shortest)) {
      RxEvent ev = Decode(*pre, peak);
      if (ev.kind == RxEvent::Kind::kPacket) {
        Emit(std::move(ev), peak.sample, events);
        return;
      }
    }
  }
  heard_.push_back({peak, failed_post, std::nullopt});
  BeginFrame(peak);
}

void RoomReceiver::ExpireChirps(std::int64_t now, std::vector<RxEvent>& events) {
  const double shortest = Shortest(), longest = Longest();
  while (!heard_.empty() && heard_.front().peak.sample + longest < now) {
    const Heard& h = heard_.front();
    std::optional<ChirpPeak> post;
    if (!h.failure && !h.failed_post) {
      post = StrongestChirpIn(detector_, modem_.sample_rate, h.peak.sample + shortest, h.peak.sample + longest);
    }
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
      // packet, not out of its own reverberant tail, and StrongestChirpIn finds it where the
      // second chirp stood out.)
      if (std::optional<std::pair<RxEvent, double>> found = DecodeByData(h.peak)) {
        Emit(std::move(found->first), found->second, events);
        continue;
      }
    }
    if (h.failure) {
      events.push_back(*h.failure);
      carrier_.FrameFound();
    } else if (!h.failed_post) {
      events.push_back(decoder_.LoneChirp(h.peak));
      carrier_.FrameFound();
    }
    heard_.pop_front();
  }
}

std::optional<std::pair<RxEvent, double>> RoomReceiver::DecodeByData(const ChirpPeak& pre) {
  // Every trial's samples must still be in the history, after the last packet decoded, and heard.
  const double oldest =
      std::max({0.0, decoded_until_, static_cast<double>(history_.count()) - static_cast<double>(history_.size()) + 1.0});
  if (pre.sample < oldest) return std::nullopt;
  for (double distance : SearchByData(symbols_, history_, pre.sample, decoder_.packet_length(), Shortest(), Longest(),
                                      detector_.length())) {
    // The data place the second chirp within half a trial step: line the chirps up within one.
    const double around = pre.sample + distance;
    std::vector<double> tries = LineUpChirp(detector_, modem_.sample_rate, pre, around, kDataSearchStepS, 1);
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

RxEvent RoomReceiver::Decode(const ChirpPeak& pre, const ChirpPeak& post) {
  std::optional<RxEvent> failed;
  for (double aligned : AlignedPosts(detector_, modem_.sample_rate, pre, post)) {
    RxEvent ev = DecodeWith(pre, post, aligned);
    if (ev.kind == RxEvent::Kind::kPacket) return ev;
    if (!failed || ev.quality > failed->quality) failed = std::move(ev);
  }
  return *failed;
}

RxEvent RoomReceiver::DecodeWith(const ChirpPeak& pre, const ChirpPeak& post, double aligned_post, bool post_heard) {
  RxEvent ev = decoder_.Decode(symbols_, history_, pre, post, aligned_post);
  if (ev.kind == RxEvent::Kind::kPacket && options_.time_arrivals) {
    ev.arrival = arrival_.Time(history_, pre.sample, post_heard ? std::optional<double>(aligned_post) : std::nullopt);
  }
  return ev;
}

}  // namespace nava_modem
