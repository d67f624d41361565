// The audio file reader (libsndfile, any format it knows), on a file's bytes in memory: what
// nava_decode and nava_room read when a user names a file. A file it cannot read must be
// refused with std::runtime_error; one it reads must hold whole, equal-length channels.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "nava_modem/wav_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const nava_modem::MultiAudio audio = nava_modem::ReadAudioChannelsFromMemory(data, size, "fuzz.wav");
    if (audio.channels.empty() || !(audio.sample_rate > 0.0)) std::abort();
    for (const auto& channel : audio.channels) {
      if (channel.size() != audio.channels[0].size()) std::abort();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
