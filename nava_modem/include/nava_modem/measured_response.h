#pragma once

// Room impulse responses measured in real rooms (a loudspeaker's sweep or a clap, recorded by a
// microphone): read from a file to render through them (nava_room --rir, nava_bench --rir-dir),
// and the two figures rooms are told apart by (RT60 and the direct-to-reverberant ratio), read in
// the modems' band. No ROS.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace nava_modem {

// A response file that cannot serve: unreadable, silent, or with more channels than asked for.
// what() is one line naming the file and what was expected.
class ResponseFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Channel `channel` (0-based) of the response in `path`, resampled (libsamplerate) to
// `sample_rate`. The response's own delay (the samples before its direct sound) is kept, so a
// rendering through it is as late as the measurement was. With no channel asked for, the file
// must have one. Throws ResponseFileError naming the file when it cannot be read, has more
// channels than asked for (no channel given and more than one) or fewer (the channel is not
// there), or when the channel is silent; std::invalid_argument for a sample rate not above 0.
std::vector<float> LoadImpulseResponse(const std::string& path, std::optional<int> channel, double sample_rate);

// The band the figures are read in: the modems' (600-5400 Hz).
constexpr double kResponseBandLowHz = 600.0;
constexpr double kResponseBandHighHz = 5400.0;
// The direct sound: the response within this long of its main peak, either side.
constexpr double kDirectHalfWidthS = 0.0025;

struct ResponseMeasures {
  std::size_t peak = 0;  // sample of the main (largest in-band) peak: the direct sound's arrival
  // T30 by Schroeder's backward integration (the decay from -5 to -35 dB, line-fitted and
  // extended to 60 dB); T20 (-5 to -25 dB) when the response's end or noise floor stops the
  // decay before -35 dB; NaN when it does not even reach -25 dB.
  double rt60_s = 0.0;
  // Energy within kDirectHalfWidthS of the peak over the energy after it, dB (+inf with
  // nothing after it).
  double drr_db = 0.0;
  // Energy before the direct sound over the energy within it, dB (-inf with nothing before).
  double before_db = 0.0;
  double after_s = 0.0;  // s of response after the direct sound
};

// Both figures in 600-5400 Hz, the definitions of ../shared/realrooms/README.md: the response
// through 4th-order Butterworth high- and low-pass filters run forwards and backwards (zero phase).
// Throws std::invalid_argument for an empty or silent response or a sample rate not above
// 2 x kResponseBandHighHz.
ResponseMeasures MeasureResponse(const std::vector<float>& response, double sample_rate);

// The same room with less reverberation: everything from kDirectHalfWidthS after the main peak
// on scaled by one gain, found so that MeasureResponse reads `drr_db` (within kDrierToleranceDb). Homes and
// small furnished rooms, whose direct sound is 7 to 12 dB above the rest, are stood in for so by
// measured responses, their colouring and early sound kept. Throws std::invalid_argument when
// drr_db is not finite, below the response's own DRR (it only makes a room drier) or out of reach
// within kDrierToleranceDb (the direct sound alone reads less), or as MeasureResponse does.
constexpr double kDrierToleranceDb = 0.01;
std::vector<float> DrierResponse(const std::vector<float>& response, double sample_rate, double drr_db);

// The same figures for a response that carries a noise floor of its own: one estimated from
// recorded packets (response_survey.h), whose every sample holds estimation noise as well as the
// room. `noise_power` is that noise's mean square per sample in 600-5400 Hz; it is taken out of
// every sample's energy. The decay is followed down to where it meets that floor, after
// Lundeby's method: the response's 10 ms energies are fitted (least squares, in dB) with an
// exponential decay over the floor, from where Schroeder's curve has fallen 5 dB (or over the
// last kLateFitDb above the floor, when the decay stands higher) to the end; the response is cut
// where the decay meets the floor, and the energy the decay puts beyond the cut is added back to
// Schroeder's integral, which then follows the decay down to where T30 is read, and to the
// reverberant energy. after_s is the time from the direct sound to the cut; a decay that never
// stands kFloorMarginDb above the floor is cut at the direct sound (too short). With a noise
// power of 0 the figures are MeasureResponse's. Throws std::invalid_argument as MeasureResponse
// does, and for a noise power below 0 or not finite.
ResponseMeasures MeasureResponseOverNoise(const std::vector<float>& response, double noise_power, double sample_rate);
constexpr double kFloorMarginDb = 10.0;
constexpr double kLateFitDb = 20.0;
// Silence put before a response before it is band-passed for its figures: a response whose direct
// sound is at its first samples (a file cut at its direct sound, or one rendered here) would
// otherwise lose the half of the filtered pulse that the zero-phase filters spread before it, and
// read its DRR 3 dB low (-2.9 dB for a rendered room of DRR 0).
constexpr double kMeasureLeadS = 0.010;
std::size_t MeasureLeadSamples(double sample_rate);
// `response` with MeasureLeadSamples() of silence before it; and that in 600-5400 Hz (the band
// every figure is read in, sample k of the response at k + MeasureLeadSamples()).
std::vector<float> WithLead(const std::vector<float>& response, double sample_rate);
std::vector<double> LeadBand(const std::vector<float>& response, double sample_rate);

// `x` in [lo, hi] Hz: 4th-order Butterworth high- and low-pass filters run forwards and backwards
// (zero phase), as every figure here is read.
std::vector<double> ResponseBand(const std::vector<float>& x, double sample_rate, double lo, double hi);
// The decay time from Schroeder's curve (dB, 0 at its start) between -from and -to dB: the
// least-squares line's slope extended to 60 dB; NaN when the curve does not reach -to dB.
double DecayTime(const std::vector<double>& curve_db, double sample_rate, double from, double to);

// The mean square of `x` in 600-5400 Hz, through the same filters as the figures (0 for empty x).
double InBandPower(const std::vector<float>& x, double sample_rate);

// The least a response must go on after its direct sound to give its figures.
constexpr double kMinTailS = 0.05;
// The most sound a response may hold before its direct sound, over the direct sound's, dB. A
// clap's own sound can come as loud as its peak (the seminar room's dummy head: +0.2 dB), and in
// a room heard behind an obstacle the loudest arrival can follow others that together hold more
// (an empty bedroom's far ear: +5.6 dB, and +6.2 dB in its survey from packets, which 6 dB
// refused); a noise's largest sample has some 20 dB more before it.
constexpr double kMaxBeforeDb = 10.0;

// Why `m`'s response cannot stand for a room, in words to follow its file's name, or nothing:
// too short (under kMinTailS after the direct sound), no direct peak (kMaxBeforeDb more sound
// before the loudest peak than within it: noise, not a response), or a decay that gives no RT60.
std::optional<std::string> ResponseProblem(const ResponseMeasures& m);

}  // namespace nava_modem
