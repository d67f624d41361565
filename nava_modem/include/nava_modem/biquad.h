#pragma once

// Second-order IIR sections and Butterworth filters built from them: the band edges of carrier
// sense (BandLevel) and of the figures read from impulse responses (MeasureResponse). No ROS.
#include <vector>

namespace nava_modem {

// One second-order section, direct form I, with its state.
struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0;
  double Run(double x);
};

// A 2nd-order high- or low-pass section at `hz` with quality `q` (1/sqrt 2: the 2nd-order
// Butterworth), from the bilinear transform, as in R. Bristow-Johnson's audio EQ cookbook.
Biquad PassSection(double sample_rate, double hz, bool high_pass, double q);

// A peaking section at `hz`: `gain_db` at its centre, 0 dB far from it, with quality `q` (the
// cookbook's peaking EQ). Minimum phase, as a loudspeaker's or a microphone's resonance is.
// Throws std::invalid_argument for a centre not between 0 and half the sample rate, q not above 0
// or a gain not finite.
Biquad PeakingSection(double sample_rate, double hz, double gain_db, double q);

// An `order`-th order Butterworth high- or low-pass (order even, 2..16) as order / 2 sections.
std::vector<Biquad> Butterworth(double sample_rate, double hz, bool high_pass, int order);

// `x` through the sections in turn (causal: each starts from rest).
std::vector<double> FilterForward(std::vector<double> x, const std::vector<Biquad>& sections);

// `x` through the sections in turn, then through fresh copies of them backwards in time: zero
// phase, the magnitude response squared (as scipy's sosfiltfilt, without its edge padding).
std::vector<double> FilterForwardBackward(std::vector<double> x, const std::vector<Biquad>& sections);

}  // namespace nava_modem
