#include "nava_modem/measured_like_response.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/biquad.h"
#include "nava_modem/math_constants.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/room_impulse_response.h"

namespace nava_modem {
namespace {

constexpr double kSoundSpeed = 343.0;  // m/s
// A pulse between samples: a Hann-windowed sinc this many samples either side.
constexpr int kSincHalf = 8;
static_assert(kMeasuredLikeDelay >= kSincHalf, "the direct sound's pulse must fit before it");
// The tail's bands (tops, Hz) and the frequency whose T60 is the asked one. 1500 Hz: the band's
// Schroeder curve, which the lower, slower bands carry at its end, then reads about the asked
// RT60 (held in the tests).
constexpr std::array<double, 5> kBandTopsHz = {500.0, 1000.0, 2000.0, 4000.0, std::numeric_limits<double>::infinity()};
constexpr std::array<double, 5> kBandCentresHz = {350.0, 707.0, 1414.0, 2828.0, 5657.0};
constexpr double kReferenceHz = 1500.0;
constexpr double kSabine = 0.057;  // critical distance = kSabine sqrt(V / RT60), m

double Draw(RandomSource& random, double lo, double hi) { return lo + (hi - lo) * random.Uniform(); }
double DrawLog(RandomSource& random, double lo, double hi) { return lo * std::pow(hi / lo, random.Uniform()); }

// Adds `amplitude` at the fractional sample `at` (a windowed sinc).
void AddPulse(std::vector<double>& h, double at, double amplitude) {
  const long centre = std::lround(at);
  for (long k = centre - kSincHalf; k <= centre + kSincHalf; ++k) {
    if (k < 0 || k >= static_cast<long>(h.size())) continue;
    const double x = static_cast<double>(k) - at;
    const double sinc = std::fabs(x) < 1e-12 ? 1.0 : std::sin(kPi * x) / (kPi * x);
    h[static_cast<std::size_t>(k)] += amplitude * sinc * (0.5 + 0.5 * std::cos(kPi * x / (kSincHalf + 1)));
  }
}

struct Point {
  double x, y, z;
};

double Distance(const Point& a, const Point& b) { return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z)); }

// The box room and where the sender and listener stand in it.
struct Room {
  double length = 0.0, width = 0.0, height = 0.0;
  Point source{}, microphone{};
  double volume = 0.0;
};

void CheckGeometry(const ResponseGeometry& g) {
  const auto check = [](double v, const char* field) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      throw std::invalid_argument(std::string("geometry ") + field + " " + std::to_string(v) + ": expected 0 (drawn) or above");
    }
  };
  check(g.distance_m, "distance_m");
  check(g.source_height_m, "source_height_m");
  check(g.microphone_height_m, "microphone_height_m");
  check(g.ceiling_m, "ceiling_m");
  for (const auto& [height, field] :
       {std::pair{g.source_height_m, "source_height_m"}, std::pair{g.microphone_height_m, "microphone_height_m"}}) {
    if (g.ceiling_m > 0.0 && height >= g.ceiling_m) {
      throw std::invalid_argument(std::string("geometry ") + field + " " + std::to_string(height) +
                                  " m: expected below the ceiling (ceiling_m " + std::to_string(g.ceiling_m) + " m)");
    }
  }
  if (g.distance_m > 0.0 && g.source_height_m > 0.0 && g.microphone_height_m > 0.0 &&
      g.distance_m <= std::fabs(g.source_height_m - g.microphone_height_m)) {
    throw std::invalid_argument("geometry distance_m " + std::to_string(g.distance_m) +
                                " m: expected more than the heights' difference (" +
                                std::to_string(std::fabs(g.source_height_m - g.microphone_height_m)) + " m)");
  }
}

Room DrawRoom(double rt60, double drr_db, const ResponseGeometry& g, RandomSource& random) {
  Room room;
  const double source_h = g.source_height_m > 0.0 ? g.source_height_m : Draw(random, 1.0, 1.7);
  const double mic_h = g.microphone_height_m > 0.0 ? g.microphone_height_m : Draw(random, 1.0, 1.7);
  room.height = g.ceiling_m > 0.0 ? g.ceiling_m : Draw(random, 2.5, 4.0);
  room.height = std::max(room.height, std::max(source_h, mic_h) + 0.1);
  const double critical = DrawLog(random, 0.7, 4.0);
  room.volume = (critical / kSabine) * (critical / kSabine) * rt60;
  const double aspect = Draw(random, 0.4, 1.0);
  room.length = std::max(2.0, std::sqrt(room.volume / (room.height * aspect)));
  room.width = std::max(2.0, aspect * room.length);
  const double distance = g.distance_m > 0.0 ? g.distance_m : std::clamp(critical * std::pow(10.0, -drr_db / 20.0), 0.3, 60.0);
  // (With drawn heights a given distance can be shorter than their difference: then the two
  // stand 10 cm apart across the floor.)
  const double across = std::sqrt(std::max(distance * distance - (source_h - mic_h) * (source_h - mic_h), 0.01));
  // A room too small for the distance is a hall that long.
  constexpr double kMargin = 0.3;
  room.length = std::max(room.length, across + 2.0 * kMargin);
  room.volume = room.length * room.width * room.height;
  const double angle = Draw(random, 0.0, 2.0 * kPi);
  // Where the pair fits at its angle, drawn uniformly; along the room's length if it does not.
  const double dx = across * std::cos(angle), dy = across * std::sin(angle);
  const double free_x = room.length - 2.0 * kMargin - std::fabs(dx), free_y = room.width - 2.0 * kMargin - std::fabs(dy);
  const double u = random.Uniform(), v = random.Uniform();
  if (free_x >= 0.0 && free_y >= 0.0) {
    const double sx = kMargin + u * free_x + std::max(0.0, -dx), sy = kMargin + v * free_y + std::max(0.0, -dy);
    room.source = {sx, sy, source_h};
    room.microphone = {sx + dx, sy + dy, mic_h};
  } else {
    const double y = kMargin + v * (room.width - 2.0 * kMargin);
    room.source = {kMargin, y, source_h};
    room.microphone = {kMargin + across, y, mic_h};
  }
  return room;
}

// The first-order image sources: their delays after the direct sound (s) and amplitudes
// relative to it (the surface's reflection factor over the longer path).
struct Image {
  double delay_s;
  double amplitude;
};

std::vector<Image> Images(const Room& room, RandomSource& random) {
  const Point& s = room.source;
  const Point mirrored[6] = {{-s.x, s.y, s.z},
                             {2.0 * room.length - s.x, s.y, s.z},
                             {s.x, -s.y, s.z},
                             {s.x, 2.0 * room.width - s.y, s.z},
                             {s.x, s.y, -s.z},
                             {s.x, s.y, 2.0 * room.height - s.z}};
  // Reflection factors (pressure): walls, the floor (hard), the ceiling (often absorbent tiles).
  const double factor[6] = {Draw(random, 0.5, 0.9), Draw(random, 0.5, 0.9), Draw(random, 0.5, 0.9),
                            Draw(random, 0.5, 0.9), Draw(random, 0.7, 0.95), Draw(random, 0.4, 0.8)};
  const double direct = Distance(s, room.microphone);
  std::vector<Image> images;
  for (int i = 0; i < 6; ++i) {
    const double path = Distance(mirrored[i], room.microphone);
    images.push_back({(path - direct) / kSoundSpeed, factor[i] * direct / path});
  }
  return images;
}

// The loudspeaker's and microphone's colouring (on everything) and the loudspeaker's directivity
// (on the direct sound): a high-pass and resonances, each a minimum-phase section.
// The highest centre of a resonance at `sample_rate`: `hz`, or below Nyquist at low rates.
double Highest(double hz, double sample_rate) { return std::min(hz, 0.45 * sample_rate); }

std::vector<Biquad> Transducers(double sample_rate, RandomSource& random) {
  std::vector<Biquad> sections = {PassSection(sample_rate, Draw(random, 200.0, 500.0), true, 1.0 / std::sqrt(2.0))};
  for (int k = 0; k < 5; ++k) {
    const double hz = DrawLog(random, 500.0, Highest(7000.0, sample_rate));
    const double gain = std::clamp(8.0 * random.Gaussian(), -18.0, 18.0);
    sections.push_back(PeakingSection(sample_rate, hz, gain, DrawLog(random, 0.5, 3.0)));
  }
  // A broad tilt of the highs (a small speaker's rising or falling top, a microphone's presence).
  const double tilt_hz = DrawLog(random, 3000.0, Highest(8000.0, sample_rate));
  sections.push_back(PeakingSection(sample_rate, tilt_hz, 5.0 * random.Gaussian(), 0.5));
  return sections;
}

std::vector<Biquad> Directivity(double sample_rate, RandomSource& random) {
  std::vector<Biquad> sections;
  for (int k = 0; k < 3; ++k) {
    const double hz = DrawLog(random, 1000.0, Highest(7000.0, sample_rate));
    const double gain = std::clamp(7.0 * random.Gaussian(), -15.0, 15.0);
    sections.push_back(PeakingSection(sample_rate, hz, gain, DrawLog(random, 0.7, 2.0)));
  }
  return sections;
}

// In-band energy of x's samples inside [begin, end) and after `end` (with silence before x, as
// MeasureResponse reads it: the direct sound's filtered pulse is whole).
std::pair<double, double> Energies(const std::vector<double>& x, double sample_rate, std::size_t begin, std::size_t end) {
  const std::size_t lead = MeasureLeadSamples(sample_rate);
  const std::vector<double> band = LeadBand(std::vector<float>(x.begin(), x.end()), sample_rate);
  double inside = 0.0, after = 0.0;
  for (std::size_t k = lead + begin; k < band.size(); ++k) (k < lead + end ? inside : after) += band[k] * band[k];
  return {inside, after};
}

std::vector<float> Sum(const std::vector<double>& a, double k, const std::vector<double>& b, double g,
                       const std::vector<double>& c) {
  std::vector<float> h(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) h[i] = static_cast<float>(a[i] + k * b[i] + g * c[i]);
  return h;
}

}  // namespace

std::vector<float> MeasuredLikeResponse(double rt60, double drr_db, double sample_rate, std::uint32_t seed,
                                        const ResponseGeometry& geometry) {
  ValidateRoomResponseArguments(rt60, drr_db, sample_rate);
  if (!(rt60 > 0.0)) throw std::invalid_argument("rt60 " + std::to_string(rt60) + " s: expected above 0 for a room");
  if (!(sample_rate > 2.0 * kResponseBandHighHz)) {
    throw std::invalid_argument("sample rate " + std::to_string(sample_rate) + " Hz: expected above " +
                                std::to_string(2.0 * kResponseBandHighHz));
  }
  CheckGeometry(geometry);
  RandomSource random(seed, kImpulseResponseStream);
  const Room room = DrawRoom(rt60, drr_db, geometry, random);
  const std::vector<Image> images = Images(room, random);
  const std::vector<Biquad> transducers = Transducers(sample_rate, random);
  const std::vector<Biquad> directivity = Directivity(sample_rate, random);
  const double slope = Draw(random, 0.15, 0.3);

  const std::size_t n = kMeasuredLikeDelay + RoomResponseSamples(rt60, sample_rate);
  const double at = static_cast<double>(kMeasuredLikeDelay);
  // The direct sound (with the loudspeaker's directivity) and what arrives within the direct
  // sound's window of the README's DRR (the floor, for robots): `near`; the later images: `far`.
  std::vector<double> near(n, 0.0), far(n, 0.0);
  near[kMeasuredLikeDelay] = 1.0;
  near = FilterForward(std::move(near), directivity);
  double first_far = std::numeric_limits<double>::infinity();
  for (const Image& image : images) {
    const bool within = image.delay_s < kDirectHalfWidthS;
    AddPulse(within ? near : far, at + image.delay_s * sample_rate, image.amplitude);
    if (!within) first_far = std::min(first_far, image.delay_s);
  }
  // The diffuse tail: from the first reflection after the direct window (a wall's or the
  // ceiling's), but not before 5 ms, building up over the mixing time.
  const double mixing = std::clamp(1e-3 * std::sqrt(room.volume), 0.005, 0.080);
  const double start = std::max(0.005, std::isfinite(first_far) ? first_far : 0.005);
  const RandomSource tail_random = random;
  const auto tail_of = [&](double scale) {
    std::vector<TailBand> bands;
    for (std::size_t b = 0; b < kBandTopsHz.size(); ++b) {
      bands.push_back({kBandTopsHz[b], scale * rt60 * std::pow(kBandCentresHz[b] / kReferenceHz, -slope)});
    }
    RandomSource draw = tail_random;  // the same noise at every scale
    const std::vector<double> shaped = BandedTail(n - kMeasuredLikeDelay, bands, start, mixing, sample_rate, draw);
    std::vector<double> tail(n, 0.0);
    std::copy(shaped.begin(), shaped.end(), tail.begin() + static_cast<std::ptrdiff_t>(kMeasuredLikeDelay));
    return FilterForward(std::move(tail), transducers);
  };

  const std::vector<double> a = FilterForward(near, transducers);
  const std::vector<double> b = FilterForward(far, transducers);
  // The direct window about the in-band peak of what arrives first: the DRR is read there (the
  // README's definition reads it about the largest peak, which far below DRR 0 can be the
  // reverberation's; the ratio asked for is the room's, direct over reverberant energy).
  const ResponseMeasures first = MeasureResponse(std::vector<float>(a.begin(), a.end()), sample_rate);
  const std::size_t half = static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate));
  const std::size_t begin = first.peak >= half ? first.peak - half : 0, end = first.peak + half + 1;
  // (Named, not a structured binding: a lambda below uses them, which C++17 does not allow.)
  const std::pair<double, double> direct = Energies(a, sample_rate, begin, end);
  const double direct_in = direct.first, direct_out = direct.second;
  const double far_out = Energies(b, sample_rate, begin, end).second;
  const double budget = direct_in * std::pow(10.0, -drr_db / 10.0);
  // The later images as the geometry made them and the tail for the rest of the reverberant
  // energy; where the images alone hold more than half of it (a high DRR near walls), both are
  // scaled. Then, as what the response reads is the definition, a few corrections of the
  // reverberant scale.
  const auto assemble = [&](const std::vector<double>& c) {
    const double tail_out = std::max(Energies(c, sample_rate, begin, end).second, 1e-300);
    double k = 1.0;
    if (far_out > 0.5 * budget) k = std::sqrt(0.5 * budget / far_out);
    double g = std::sqrt(std::max(budget - k * k * far_out - direct_out, 0.05 * budget) / tail_out);
    std::vector<float> h = Sum(a, k, b, g, c);
    for (int pass = 0; pass < 4; ++pass) {
      const auto [inside, after] = Energies(std::vector<double>(h.begin(), h.end()), sample_rate, begin, end);
      const double read = 10.0 * std::log10(inside / std::max(after, 1e-300));
      if (std::fabs(read - drr_db) < 0.05) break;
      const double factor = std::pow(10.0, (read - drr_db) / 20.0);
      k *= factor;
      g *= factor;
      h = Sum(a, k, b, g, c);
    }
    return h;
  };
  std::vector<float> h = assemble(tail_of(1.0));
  // The bands' decays together read a T30 a little off the reference band's (by up to 15 %, with
  // the slope): once more with them scaled so that it reads the asked RT60.
  const double read = MeasureResponse(h, sample_rate).rt60_s;
  if (std::isfinite(read) && std::fabs(read / rt60 - 1.0) > 0.02) h = assemble(tail_of(rt60 / read));
  return h;
}

}  // namespace nava_modem
