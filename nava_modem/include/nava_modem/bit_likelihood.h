#pragma once

// How sure a nava bit is, from what its two tone filters heard: the log-likelihood ratio of MARK
// over SPACE, each tone's filter holding its direct sound if sent and a random part (noise, and
// the room's reverberation of earlier bits) of known mean power: Rician against Rayleigh. Used by
// the FSK receiver's frame reader and its acceptance step. No ROS.
namespace nava_modem {

// The noise a tone's decision assumes is at least this share of its level: the filters' leakage
// from neighbouring bits, which the break does not show, is about this large.
constexpr double kMinToneNoise = 0.01;

// The log-likelihood ratio of MARK over SPACE for one bit whose filters heard powers `mark` and
// `space`, each tone's direct power `level` and random part's mean power `noise` ([0] MARK,
// [1] SPACE).
double BitLlr(const double level[2], const double noise[2], double mark, double space);

// Two estimates of a quantity for MARK and SPACE, drawn towards their geometric mean as far as
// their ratio is within its standard error (var_log: the variance of the log ratio), so that the
// tones are told apart only where the audio shows a real difference.
void ShrinkTones(double value[2], double var_log);

}  // namespace nava_modem
