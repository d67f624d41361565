#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "nava_modem/band_level.h"
#include "nava_modem/busy_air.h"
#include "nava_modem/chirp_detector.h"
#include "nava_modem/first_arrival.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

// The `room` profile's receiver (see room_phy.h). The chirp detector finds both chirps of a
// packet; their distance gives the sender's clock, to which the symbol windows and tone
// frequencies are scaled; each symbol's 192 tone energies come from one FFT of its window;
// each tone is judged against its own noise floor (its median over the packet's other
// symbols, scaled by how loud that symbol's other tones were), which takes out a whine, the
// speaker's tilt and the reverberant tails of earlier symbols; the soft bits go to the Viterbi
// decoder and the CRC decides.
//
// A chirp is paired with every earlier one at the packet's length (within the clock tolerance)
// and each such pair is decoded until one passes the CRC: speech and knocks can pass for a
// chirp, and the first pair found need not be the packet. A chirp without a partner has it
// looked for where it must be, below the detector's threshold, and a first chirp still alone
// then by the data after it (DecodeByData). Noise reports: a chirp whose pairs
// all failed the CRC is BAD_CRC; a chirp with no partner at all is ONE_BYTE (a packet begun
// and never ended, or a sound that looked like a chirp); busy air in which no chirp was heard
// is ZERO_BYTE.
class RoomReceiver : public PacketReceiver {
 public:
  // Throws std::invalid_argument for a rate the room profile cannot use (ValidateRoomRate),
  // impossible options (ValidateReceiverOptions), or a max_rate_error that would stretch the
  // highest tone past Nyquist.
  RoomReceiver(const ModemOptions& modem, const ReceiverOptions& options);
  ~RoomReceiver() override;

  void Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) override;
  void Flush(std::vector<RxEvent>& events) override;
  void SetMuted(bool muted) override;
  void SetCarrierThreshold(std::optional<double> db) override { busy_.SetThreshold(db); }
  double level_db() const override { return level_.db(); }
  double time() const override { return static_cast<double>(n_) / modem_.sample_rate; }

 private:
  void ProcessPiece(const float* samples, std::size_t count, std::vector<RxEvent>& events);
  void OnChirp(const ChirpPeak& peak, std::vector<RxEvent>& events);
  // Reports a decoded packet whose second chirp began at `post`.
  void Emit(RxEvent packet, double post, std::vector<RxEvent>& events);
  // Reports the chirps that can no longer pair with a later one.
  void ExpireChirps(std::int64_t now, std::vector<RxEvent>& events);
  // Decodes the packet between two chirps, trying each of AlignedPosts in turn.
  RxEvent Decode(const ChirpPeak& pre, const ChirpPeak& post);
  // `post_heard`: the second chirp was heard where aligned_post puts it, and times the arrival
  // with the first (else the first alone does).
  RxEvent DecodeWith(const ChirpPeak& pre, const ChirpPeak& post, double aligned_post, bool post_heard = true);
  // Where the second chirp starts, to a fraction of a sample, at the lags that best line up the
  // matched filter's envelope around the two peaks (the best and the runner-up), then at the
  // peaks' own distance: in a reverberant room the strongest peak can be the direct sound in
  // one chirp and a reflection in the other, but the room (and so the envelope's pattern of
  // direct sound and reflections) is the same for both.
  std::vector<double> AlignedPosts(const ChirpPeak& pre, const ChirpPeak& post) const;
  // Where a chirp lies near `around` (samples), by lining up `anchor`'s matched-filter envelope
  // (its direct sound and reflections) with the envelope there, at lags up to `reach_s` either
  // way: the best lag, then (picks 2) the best one at least a millisecond from it.
  std::vector<double> LinedUp(const ChirpPeak& anchor, double around, double reach_s, int picks) const;
  // A lone first chirp's partner found by the data after it (kScanStep, HopContrast in the
  // .cpp): the packet and where its second chirp starts, or nothing.
  std::optional<std::pair<RxEvent, double>> DecodeByData(const ChirpPeak& pre);
  // The tone energies of the 42 symbol windows of a packet whose first chirp starts at `pre`
  // (samples), sent by a clock whose durations are `stretch` times ours (kSymbols x kBins); with
  // `stride` k only every k-th symbol's row from the first (the others are left as they were).
  void ReadSymbols(double pre, double stretch, std::vector<double>& energy, int stride);
  // The matched filter's strongest output between two sample positions, as a chirp, if it
  // stands out from the output before them (see kSearchRatio).
  std::optional<ChirpPeak> StrongestIn(double from, double to) const;
  // When the packet whose chirps begin at `pre` and `post` (samples, as the decode put them)
  // first arrived (RxEvent::arrival): both chirps' responses together, or the first's alone
  // without `post`.
  double Arrival(double pre, std::optional<double> post);
  // Energy of tone bins kLowestBin.. of the window of `length` samples from `first`.
  void SymbolEnergies(std::int64_t first, int length, double* energies);
  // The largest clock error a decode accepts: the pairing's, and the alignment's reach.
  double MaxStretchError() const { return options_.max_rate_error + 0.01; }
  float Sample(std::int64_t n) const { return history_[static_cast<std::size_t>(n) & history_mask_]; }

  ModemOptions modem_;
  ReceiverOptions options_;
  std::vector<float> chirp_;  // as sent
  ChirpDetector detector_;
  ArrivalTimer arrival_timer_;
  BandLevel level_;
  BusyAir busy_;
  double packet_length_;  // samples from a packet's first chirp to its second, at our clock
  std::vector<float> history_;
  std::size_t history_mask_;
  std::int64_t n_ = 0;  // samples processed
  bool muted_ = false;
  // A chirp heard, waiting for a partner at the packet's length after it.
  struct Heard {
    ChirpPeak peak;
    bool failed_post = false;         // it ended a pair that failed the CRC (reported with its first)
    std::optional<RxEvent> failure;   // the best failed decode it began
  };
  std::deque<Heard> heard_;
  // Chirps found, held until the matched filter's envelope is known far enough past them to
  // line them up (AlignedPosts looks up to kAlignAfter + kAlignReach ahead).
  std::deque<ChirpPeak> pending_;
  std::int64_t lookahead_;
  double decoded_until_ = -1.0;  // the end of the last packet decoded, in samples
  std::int64_t level_step_, level_count_ = 0;
  struct Fft;
  std::unique_ptr<Fft> fft_;
  std::vector<ChirpPeak> peaks_;  // scratch
};

}  // namespace nava_modem
