// The nava profile's FSK receiver on raw samples (receiver_input.h has the input's layout): what
// a sound card or a WAV file hands nava_modem and nava_decode.
#include "receiver_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FeedReceiver(nava_modem::Profile::kNava, {16000.0, 44100.0, 48000.0, 8000.0}, data, size);
  return 0;
}
