#pragma once

// When a known sound first reached a microphone: the leading edge of its direct (or, round a
// corner, diffracted) arrival, finer than a sample. The base of acoustic ranging: the first
// arrival is the shortest way, whatever the room adds after it. No ROS.
//
// The definition, the same for a measured response and for a packet heard: the channel's
// impulse response is read in the modems' band (600-5400 Hz, as MeasureResponse reads it,
// weighted by a Hann window across it so that a pulse has no sidelobes to speak of beyond 1 ms),
// its envelope is the magnitude of its analytic signal, the direct sound is the earliest peak of
// that envelope within kDirectWithinDb of its largest, well above the floor before it (noise,
// and what of the room the reference does not explain) and well above the sidelobe a later peak
// has where it lies (the reference's pulse's, with a margin), and the arrival is where the envelope,
// rising to that peak, first reaches half of it. A peak is one the envelope falls from by 3 dB
// before rising again: a shoulder on the way up is not; one that falls by 2 to 3 dB counts in
// part, the edge a blend of its and the later peak's, so that noise moving the dip across 3 dB
// does not make the edge jump from one arrival to the next. (For a bare delay the edge is about
// 0.2 ms before the delay itself: the band's pulse rises over that. Ranging takes differences,
// and both sides of a check use the same definition, so the offset cancels.)
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

namespace nava_modem {

// The direct sound's peak is the first within this of the largest: round a corner in a
// reverberant hall the diffracted sound can be 30 dB under the reflections that follow it.
constexpr double kDirectWithinDb = 40.0;

// How far before its strongest arrival a sound's direct sound is looked for, and the stretch
// before that read as the floor (noise, and what of the room the reference does not explain).
// 0.1 s: in a hall whose reverberation builds up over its mixing time (about sqrt(V) ms), the
// strongest arrival comes up to 90 ms after the direct sound.
constexpr double kDirectBeforeStrongestS = 0.1;
constexpr double kFloorLeadS = 0.02;

// Seconds from received[0] at which `reference`'s first sample reached the microphone: the
// leading edge of the impulse response found by dividing received's spectrum by reference's in
// the band (regularised where the reference is weak), looked for at delays 0 to
// `count - reference.size()` samples; NaN for silence. With `clarity`, also how far the
// response's largest envelope stands above its median over the search (an amplitude ratio):
// noise without the reference in it gives a few; a sound that arrived, tens to thousands. Throws
// std::invalid_argument for an empty reference, a count shorter than it, or a sample rate
// below 2 x 5400 Hz.
double FirstArrival(const float* received, std::size_t count, const std::vector<float>& reference, double sample_rate,
                    double* clarity = nullptr);

// One of several windows of a recording that hold the same reference through the same room (a
// packet's two chirps): its samples (the timer's count() of them), how many samples later the
// sound lies in it than in the first window, counted from each window's start (a fraction of a
// sample, as the receiver measured it), and its lead (see ArrivalTimer::Time).
struct ArrivalWindow {
  const float* samples = nullptr;
  double shift = 0.0;
  std::size_t lead = 0;
};

// FirstArrival of one reference in windows of one length, again and again (a receiver timing
// its packets): the reference's spectrum, its pulse and the transforms are made once. Throws as
// FirstArrival does. Not thread-safe (one per receiver).
class ArrivalTimer {
 public:
  ArrivalTimer(const std::vector<float>& reference, std::size_t count, double sample_rate);
  ~ArrivalTimer();
  ArrivalTimer(const ArrivalTimer&) = delete;
  ArrivalTimer& operator=(const ArrivalTimer&) = delete;
  // As FirstArrival, on `count()` samples from `received`. With `lead` above 0, the window's
  // first `lead` samples are known to come before the sound (the receiver put them there): the
  // floor is read over those delays alone (see the .cpp: read over the whole search, a big
  // room's early response can outnumber the noise before it and pass for the floor).
  double Time(const float* received, double* clarity = nullptr, std::size_t lead = 0);
  // The arrival in windows[0] from the responses of every window together, each moved by its
  // shift and weighted by the inverse of its own floor (over its lead): two chirps through the
  // same room give the direct sound 3 dB further over the noise than one. The floor is then read
  // over windows[0]'s lead. Throws std::invalid_argument for no window or a null one.
  double Together(const std::vector<ArrivalWindow>& windows, double* clarity = nullptr);
  std::size_t count() const { return count_; }

 private:
  struct Plans;
  // The response in `window` as an analytic spectrum (moved by its shift) into `z`.
  void Response(const ArrivalWindow& window, std::vector<std::complex<double>>& z);
  // power_: the envelope of the response whose analytic spectrum is `z`, squared and smoothed.
  void Envelope(const std::vector<std::complex<double>>& z);
  // The kFloorQuantile of power_ over its first `lead` delays (all of them for 0).
  double Floor(std::size_t lead);
  // The arrival (s) and the clarity from power_, its floor over `lead`.
  double Arrival(std::size_t lead, double* clarity);
  double rate_;
  std::size_t count_, reference_length_;
  std::unique_ptr<Plans> plans_;
  std::vector<std::complex<double>> inverse_;  // per bin: the band over the reference, regularised
  double rise_correction_ = 0.0, within_ = 0.0;
  // By distance in samples: under this share of a later peak's power an earlier peak is taken
  // for that peak's sidelobe (the reference's pulse's sidelobes, with a margin).
  std::vector<double> near_;
  std::size_t smooth_ = 1;  // samples the power envelope is averaged over (a ringing pulse's period)
  std::vector<double> power_, sorted_;  // scratch
  std::vector<std::complex<double>> z_, sum_;  // scratch
};

// The leading edge of a response's direct sound, seconds from its first sample: the truth a
// FirstArrival through that response is judged against. Read from kLeadingEdgeBeforeS before the
// response's largest sample, the floor over the first kLeadingEdgeLeadS of that (as a receiver
// reads a packet's). Throws as FirstArrival does, and for an empty response.
double LeadingEdge(const std::vector<float>& response, double sample_rate);

}  // namespace nava_modem
