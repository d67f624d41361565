#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace nava_modem {

// The `room` profile's physical layer, for reverberant rooms. One packet on the air:
//
//   [chirp 0.12 s] [42 data symbols of 40 ms: 16-ary FSK, hopping over 12 sub-bands] [chirp 0.12 s]
//
// - Chirps: linear sweeps 600 -> 5400 Hz, found by a matched filter however loud the room's
//   tail: the filter compresses the 0.12 s sweep into a peak ~0.2 ms wide (time-bandwidth
//   product 576), while the reverberation it meets is spread over the room's decay. The
//   distance between the two chirps measures the sender's clock against ours (0.06 ms over
//   1.8 s is 0.003 %), so the receiver scales symbol times and tone frequencies to it.
// - Data: each symbol is one of 16 tones 25 Hz apart (1/T, orthogonal over the 40 ms symbol)
//   inside one 400 Hz sub-band; consecutive symbols hop through all 12 sub-bands in an order
//   that keeps neighbours far apart, so that a tone's own reverberant tail has decayed for
//   480 ms before its sub-band is used again, and a fade or a whine hits few symbols.
// - Code: the 4 data bytes and the Nava CRC (6 bytes) through the rate-1/3, K=9 convolutional
//   code (libfec's Viterbi decoder, soft decisions), scrambled, and interleaved so that the
//   4 coded bits a symbol carries lie 14 trellis steps apart.
namespace room_phy {

constexpr double kSymbolSeconds = 0.040;
constexpr double kToneSpacingHz = 25.0;  // 1 / kSymbolSeconds
constexpr int kTonesPerBand = 16;        // 4 coded bits per symbol
constexpr int kBitsPerSymbol = 4;
constexpr int kBands = 12;
constexpr double kLowestToneHz = 600.0;  // a multiple of kToneSpacingHz
constexpr int kLowestBin = 24;           // kLowestToneHz / kToneSpacingHz
constexpr int kBins = kBands * kTonesPerBand;  // 192 tones from 600 to 5375 Hz
constexpr double kChirpSeconds = 0.120;
constexpr double kChirpLowHz = 600.0, kChirpHighHz = 5400.0;
constexpr double kHighestHz = 5400.0;    // nothing is sent above this

constexpr int kPayloadBytes = 6;  // 4 data bytes + the 2 CRC bytes (header 0x55 implied)
constexpr int kPayloadBits = kPayloadBytes * 8;
constexpr int kConstraint = 9;
constexpr int kCodeRate = 3;  // coded bits per trellis step
constexpr int kCodedBits = (kPayloadBits + kConstraint - 1) * kCodeRate;  // 168
constexpr int kSymbols = kCodedBits / kBitsPerSymbol;                     // 42
static_assert(kCodedBits % kBitsPerSymbol == 0, "coded bits must fill whole symbols");

// Where each part starts, in seconds from the start of the packet.
constexpr double kDataStart = kChirpSeconds;
constexpr double kPostChirpStart = kDataStart + kSymbols * kSymbolSeconds;  // 1.80 s
constexpr double kPacketSeconds = kPostChirpStart + kChirpSeconds;           // 1.92 s

// The sub-band symbol s uses (0..kBands-1).
int Band(int symbol);
// The sub-band of the `slot`-th of the `tones` tones symbol s sounds at once (faster rates,
// room_frame.h): the hop order walked `tones` steps a symbol, so that a symbol's tones lie far
// apart and each sub-band rests kBands / tones - 1 symbols between uses. BandOf(s, 0, 1) is Band(s).
int BandOf(int symbol, int slot, int tones);
// Tone bin (in units of kToneSpacingHz) of tone `tone` of symbol s's sub-band.
inline int Bin(int symbol, int tone) { return kLowestBin + Band(symbol) * kTonesPerBand + tone; }

// The chirp at `sample_rate`, amplitude 1, its ends tapered over 5 ms (no click).
std::vector<float> Chirp(double sample_rate);

}  // namespace room_phy
}  // namespace nava_modem
