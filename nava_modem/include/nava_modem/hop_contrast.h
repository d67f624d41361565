#pragma once

#include <vector>

namespace nava_modem {

// How clearly the `room` profile's symbols stand out in their own sub-bands, read from the tone
// energies of a packet's 42 symbol windows (kSymbols rows of kBins, as the receiver reads them):
// the mean over symbols of log(strongest tone of the symbol's sub-band over the mean of its
// sub-band's other tones). Windows laid where the sender put its symbols score high; windows
// laid at a wrong clock slide off the tones within a few symbols and score like noise (about
// 1.36, log 3.9, for 16 equal tones in white noise, 0.33 the spread of one symbol's). Throws
// std::invalid_argument for a size other
// than kSymbols * kBins or a stride below 1. With `stride` k, only every k-th symbol from the
// first counts (a cheaper first look: the others need not have been read).
double HopContrast(const std::vector<double>& energy, int stride = 1);

}  // namespace nava_modem
