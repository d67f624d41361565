#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "nava_modem/chirp_alignment.h"
#include "nava_modem/chirp_detector.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_arrival.h"
#include "nava_modem/room_carrier_sense.h"
#include "nava_modem/room_pair_decoder.h"
#include "nava_modem/room_symbol_reader.h"
#include "nava_modem/sample_ring.h"

namespace nava_modem {

// The `room` profile's receiver (see room_phy.h), a pipeline of stages that pass values: the
// chirp detector finds both chirps of a packet (ChirpDetector); their envelopes lined up give
// where the second starts to a fraction of a sample (chirp_alignment.h), and their distance the
// sender's clock; the pair decoder (RoomPairDecoder) reads the 42 symbol windows scaled to that
// clock (RoomSymbolReader: one FFT each), judges each tone against its own noise floor
// (RoomSoftBits: its median over the packet's other symbols, scaled by how loud that symbol's
// other tones were, which takes out a whine, the speaker's tilt and the reverberant tails of
// earlier symbols), and the Viterbi decoder and the CRC decide; a packet's arrival is timed by
// RoomArrival. This class keeps the samples heard (SampleRing), the chirps waiting for a
// partner, and the carrier sense (RoomCarrierSense).
//
// A chirp is paired with every earlier one at the packet's length (within the clock tolerance)
// and each such pair is decoded until one passes the CRC: speech and knocks can pass for a
// chirp, and the first pair found need not be the packet. A chirp without a partner has it
// looked for where it must be, below the detector's threshold (StrongestChirpIn), and a first
// chirp still alone then by the data after it (SearchByData, in DecodeByData). Noise reports: a
// chirp whose pairs all failed the CRC is BAD_CRC; a chirp with no partner at all is ONE_BYTE (a
// packet begun and never ended, or a sound that looked like a chirp); busy air in which no chirp
// was heard is ZERO_BYTE.
//
// Long frames (room_frame.h): a chirp heard the header's length after another (or with one
// standing out there) begins one when the header between them decodes; the frame then waits
// for its chirp C where the header's length and the sender's clock put it and decodes the
// payload between B and C. Today's packets are looked for first, as before, and while a frame
// waits, every report waits with it: a frame that decodes takes the place of the noise reports
// within its span (its chirps alone, its hops passing for chirps, its busy air); one that does not
// leaves them as they were, so a header read from noise changes no report but its timing.
class RoomReceiver : public PacketReceiver {
 public:
  // Throws std::invalid_argument for a rate the room profile cannot use (ValidateRoomRate),
  // impossible options (ValidateReceiverOptions), or a max_rate_error that would stretch the
  // highest tone past Nyquist.
  RoomReceiver(const ModemOptions& modem, const ReceiverOptions& options);

  void Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) override;
  void Flush(std::vector<RxEvent>& events) override;
  void SetMuted(bool muted) override;
  void SetCarrierThreshold(std::optional<double> db) override { carrier_.SetThreshold(db); }
  double level_db() const override { return carrier_.level_db(); }
  double time() const override { return static_cast<double>(history_.count()) / modem_.sample_rate; }

 private:
  void ProcessPiece(const float* samples, std::size_t count, std::vector<RxEvent>& events);
  void OnChirp(const ChirpPeak& peak, std::vector<RxEvent>& events);
  // Reports a decoded packet whose second chirp began at `post`.
  void Emit(RxEvent packet, double post, std::vector<RxEvent>& events);
  // Reports the chirps that can no longer pair with a later one.
  void ExpireChirps(std::int64_t now, std::vector<RxEvent>& events);
  // Decodes the packet between two chirps, trying each of AlignedPosts in turn.
  RxEvent Decode(const ChirpPeak& pre, const ChirpPeak& post);
  // The pair decoder's event, a packet timed (with the second chirp too when `post_heard`: it
  // was heard where aligned_post puts it; else by the first alone).
  RxEvent DecodeWith(const ChirpPeak& pre, const ChirpPeak& post, double aligned_post, bool post_heard = true);
  // A lone first chirp's partner found by the data after it: the packet and where its second
  // chirp starts, or nothing.
  std::optional<std::pair<RxEvent, double>> DecodeByData(const ChirpPeak& pre);
  // A long frame's chirp B at `peak`: begins one when a header decodes between it and a chirp A
  // the header's length before.
  void BeginFrame(const ChirpPeak& peak);
  // A long frame's chirp C at `peak`: whether it completed a frame waiting for it.
  bool CompleteFrame(const ChirpPeak& peak, std::vector<RxEvent>& events);
  // Reports the long frames whose chirp C can no longer come (after looking for it where it must be).
  void ExpireFrames(std::int64_t now, std::vector<RxEvent>& events);
  // Reports a decoded long frame, dropping the noise reports held within its span.
  void OnFrameDecoded(RxEvent frame, double c, std::vector<RxEvent>& events);
  // Moves what was heard to `events`, unless a long frame still waits (held_).
  void Deliver(std::vector<RxEvent>& events);
  // The distances from a first chirp at which its second may begin, at the clocks looked for.
  double Shortest() const { return decoder_.packet_length() * (1.0 - options_.max_rate_error); }
  double Longest() const { return decoder_.packet_length() * (1.0 + options_.max_rate_error); }

  ModemOptions modem_;
  ReceiverOptions options_;
  std::vector<float> chirp_;  // as sent
  ChirpDetector detector_;
  RoomArrival arrival_;
  RoomCarrierSense carrier_;
  RoomSymbolReader symbols_;
  RoomPairDecoder decoder_;
  // Samples of envelope needed past a chirp before it is lined up (AlignmentLookahead).
  std::int64_t lookahead_;
  SampleRing history_;
  bool muted_ = false;
  // A chirp heard, waiting for a partner at the packet's length after it.
  struct Heard {
    ChirpPeak peak;
    bool failed_post = false;         // it ended a pair that failed the CRC (reported with its first)
    std::optional<RxEvent> failure;   // the best failed decode it began
  };
  std::deque<Heard> heard_;
  // Chirps found, held until the matched filter's envelope is known far enough past them to
  // line them up (lookahead_).
  std::deque<ChirpPeak> pending_;
  // A long frame whose header was read, waiting for its chirp C.
  struct LongFrame {
    ChirpPeak a, b;
    double aligned_b = 0.0;  // B lined up against A: the header's clock, and the frame's arrival
    RoomHeaderFound found;
    ChirpShape b_shape;      // to line C up against B after the detector has forgotten B
    double c_at = 0.0, c_reach = 0.0;  // where C should start, and how far from there it may (samples)
    std::optional<RxEvent> failure;    // the best payload decode that failed its CRC-32
  };
  // The frame's payload against a chirp C at `c`: the best of its alignments.
  RxEvent DecodeFrame(LongFrame& frame, const ChirpPeak& c);
  std::deque<LongFrame> frames_;
  std::vector<RxEvent> held_;  // reports waiting for the long frames (Deliver)
  double decoded_until_ = -1.0;  // the end of the last packet decoded, in samples
  std::vector<ChirpPeak> peaks_;  // scratch
};

}  // namespace nava_modem
