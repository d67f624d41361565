#include "world_sim/acoustics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace world_sim {

std::optional<NoiseKind> ParseNoiseKind(const std::string& name) {
  if (name == "white") return NoiseKind::kWhite;
  if (name == "pink") return NoiseKind::kPink;
  if (name == "speech") return NoiseKind::kSpeech;
  if (name == "whine") return NoiseKind::kWhine;
  if (name == "recording") return NoiseKind::kRecording;
  return std::nullopt;
}

const char* NoiseKindName(NoiseKind kind) {
  switch (kind) {
    case NoiseKind::kWhite: return "white";
    case NoiseKind::kPink: return "pink";
    case NoiseKind::kSpeech: return "speech";
    case NoiseKind::kWhine: return "whine";
    case NoiseKind::kRecording: return "recording";
  }
  return "?";
}

double CriticalDistance(const RoomAcoustics& room) {
  if (room.critical_distance > 0.0) return room.critical_distance;
  // Sabine: absorption area A = 0.161 V / RT60; r_c = sqrt(A / (16 pi)) for an omni source.
  return std::sqrt(0.161 * room.volume / (16.0 * M_PI * room.rt60));
}

namespace {
// Seconds since the start of the period holding `t`, in [0, period).
double CycleTime(const NoiseSourceSpec& source, double t) {
  double cycle = std::fmod(t - source.phase, source.period);
  if (cycle < 0.0) cycle += source.period;
  return cycle;
}
}  // namespace

bool Sounding(const NoiseSourceSpec& source, double t) {
  if (source.duty >= 1.0) return true;
  return CycleTime(source, t) < source.duty * source.period;
}

double SoundingFor(const NoiseSourceSpec& source, double t) {
  if (source.duty >= 1.0) return std::numeric_limits<double>::infinity();
  const double cycle = CycleTime(source, t);
  return cycle < source.duty * source.period ? cycle : 0.0;
}

double SoundingFraction(const NoiseSourceSpec& source, double t0, double t1) {
  if (!(t1 > t0)) return Sounding(source, t0) ? 1.0 : 0.0;
  if (source.duty >= 1.0) return 1.0;
  const double period = source.period, on = source.duty * period;
  // The time it has sounded from the start of the period holding `phase` up to `t`.
  auto sounded = [&](double t) {
    const double u = t - source.phase;
    const double cycles = std::floor(u / period);
    return cycles * on + std::min(u - cycles * period, on);
  };
  return std::clamp((sounded(t1) - sounded(t0)) / (t1 - t0), 0.0, 1.0);
}

const RoomAcoustics& Acoustics::RoomAt(double x, double y) const {
  for (const AcousticRegion& r : regions) {
    if (r.Contains(x, y)) return r.room;
  }
  return room;
}

}  // namespace world_sim
