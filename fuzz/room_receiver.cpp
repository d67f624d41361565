// The room profile's receiver on raw samples (receiver_input.h has the input's layout).
#include "receiver_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FeedReceiver(nava_modem::Profile::kRoom, {12000.0, 16000.0, 48000.0}, data, size);
  return 0;
}
