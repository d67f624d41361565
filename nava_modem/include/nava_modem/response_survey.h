#pragma once

// A survey of a room from the robots' own packets (nava_survey): what one robot recorded of
// another's `room` packets gives the link's impulse response, because every packet it decodes
// is then known as it was sent. From the response come the room's RT60 and DRR (the figures of
// measured_response.h), and from what the packets do not explain, the room's noise. No ROS.
//
// The estimate: each decoded packet is modulated again, stretched to the sender's clock (the
// receiver's rate_error, then timed again: its two halves through a first estimate of the
// response, matched with the recording apart) and lined up with the recording by
// cross-correlation, to a fraction of a sample; all of them together are the signal that was
// sent. The response is the regularised
// least-squares deconvolution of the recording by that signal, in one transform over the whole
// recording (so one packet's reverberation running into the next is explained, not noise),
// in the modems' band (600-5400 Hz). Packets that were not decoded stay in the recording as
// noise.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "nava_modem/measured_response.h"

namespace nava_modem {

// A recording the survey cannot use: no packet decoded in it, or a rate the room profile
// cannot run at. what() is one line saying what was expected.
class SurveyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SurveyOptions {
  // The estimated response starts this long before the direct sound (where the packets line up).
  double lead_s = 0.05;
  // How far from where its decode put it a packet's best alignment is looked for, s.
  double search_s = 0.02;
  // Tikhonov weight: the deconvolution divides by |sent|^2 + this x its mean over the band, so
  // that frequencies the packets hardly sent do not blow the estimate's noise up.
  double regularisation = 0.01;
  // The longest response kept, s after its start (a basement's 5 s RT60 fits).
  double max_response_s = 8.0;
  // Preconditioned conjugate-gradient steps of the least squares on the response's lags (see
  // the .cpp): 10 reach within 0.5 % of RT60 what 100 do.
  int iterations = 10;
};

// One packet found in a recording, as the room receiver reported it.
struct SurveyPacket {
  std::vector<std::uint8_t> data;  // the 4 data bytes
  double start_s = 0.0;            // where the receiver put its start
  double rate_error = 0.0;         // the sender's clock over ours, minus 1
};

// What the room receiver heard in a recording.
struct SurveyHeard {
  std::vector<SurveyPacket> packets;  // decoded
  // Where packets began that were heard (a chirp) but not decoded (one_byte or bad_crc), s.
  std::vector<double> undecoded_s;
};

// The room profile's 12 sub-bands (room_phy.h), 400 Hz each from 600 Hz.
constexpr int kSurveyBands = 12;

struct SurveyResult {
  // The packets used, each with the clock the survey timed it by (its rate_error measured on
  // the recording through the response, not the receiver's).
  std::vector<SurveyPacket> packets;
  std::size_t undecoded = 0;          // packets heard but not decoded, left out of the fit
  std::vector<float> response;        // the estimated impulse response, direct sound near lead_s
  // The estimate's own noise: mean square per sample (from the recording's noise and how little
  // of each frequency the packets sent).
  double response_noise_power = 0.0;
  ResponseMeasures figures;  // MeasureResponseOverNoise(response, response_noise_power)
  // The recording less what the packets explain, in 600-5400 Hz: its level over the whole
  // recording (dB of full scale, 10 log10 of the mean square) and in each sub-band.
  double noise_db = 0.0;
  std::array<double, kSurveyBands> band_noise_db{};
  // The packets' received level (direct and reverberant) while they sound, in the same band and
  // scale, and the direct sound's alone (its energy over one packet's length).
  double signal_db = 0.0;
  double direct_db = 0.0;
};

// What one robot plays for another to survey the room by: `count` room packets with random data
// (from `seed`), silences of 0.5 to 1.5 times `gap` s (drawn) before, between and after them, at
// `sample_rate`. Throws
// std::invalid_argument for a rate the room profile cannot run at, or count < 1, or gap < 0.
std::vector<float> SurveyTrain(double sample_rate, int count, double gap, unsigned seed);

// What the room receiver hears in `recording` (a mono recording at `sample_rate`). Throws
// SurveyError for a rate the room profile cannot run at.
SurveyHeard FindSurveyPackets(const std::vector<float>& recording, double sample_rate);

// The survey of `recording` from what was heard in it (FindSurveyPackets). Throws SurveyError
// when no packet was decoded or the recording is too short (under two packets' length),
// std::invalid_argument for impossible options.
SurveyResult SurveyResponse(const std::vector<float>& recording, double sample_rate, const SurveyHeard& heard,
                            const SurveyOptions& options = {});

}  // namespace nava_modem
