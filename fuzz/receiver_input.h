#pragma once

// Raw samples fed to a receiver the way a sound card or a WAV file would, for the receivers'
// fuzz targets.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "nava_modem/modem_profile.h"

namespace fuzz {

// The receivers' input: a header of 3 bytes, then raw samples.
//   byte 0: bit 0 set: the samples are 32-bit floats (as a float WAV holds them: any value,
//           NaN and infinities included), else 16-bit integers; the rest picks the sample
//           rate from `rates`;
//   byte 1: the samples handed to Process at a time (1 + 97 * byte), as a sound card's periods;
//   byte 2: bits 0-1 the bits the CRC may repair (mod 3), bit 2 a carrier threshold of -40 dB.
// The samples are little-endian, as on the machines the project runs on.
inline void FeedReceiver(nava_modem::Profile kind, const std::vector<double>& rates, const std::uint8_t* data,
                         std::size_t size) {
  if (size < 3) return;
  const bool floats = data[0] & 1;
  nava_modem::ModemOptions modem;
  modem.sample_rate = rates[(data[0] >> 1) % rates.size()];
  const std::size_t chunk = 1 + 97 * static_cast<std::size_t>(data[1]);
  nava_modem::ReceiverOptions options;
  options.max_fixed_bits = (data[2] & 3) % 3;
  if (data[2] & 4) options.carrier_threshold_db = -40.0;
  data += 3;
  size -= 3;

  std::vector<float> samples;
  if (floats) {
    samples.resize(size / sizeof(float));
    // An empty vector's data() may be null, and memcpy's arguments must never be, even for 0 bytes.
    if (!samples.empty()) std::memcpy(samples.data(), data, samples.size() * sizeof(float));
  } else {
    samples.resize(size / sizeof(std::int16_t));
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const auto v = static_cast<std::int16_t>(data[2 * k] | (data[2 * k + 1] << 8));
      samples[k] = static_cast<float>(v) / 32768.0f;
    }
  }
  const auto receiver = nava_modem::MakeProfile(kind, modem)->MakeReceiver(options);
  std::vector<nava_modem::RxEvent> events;
  for (std::size_t at = 0; at < samples.size(); at += chunk) {
    receiver->Process(samples.data() + at, std::min(chunk, samples.size() - at), events);
  }
  receiver->Flush(events);
  for (const nava_modem::RxEvent& e : events) {
    // A packet carries exactly its data bytes; anything else is a receiver bug.
    if (e.kind == nava_modem::RxEvent::Kind::kPacket && e.data.size() != 4) std::abort();
  }
}

}  // namespace fuzz
