#pragma once

#include <complex>
#include <cstdint>
#include <functional>
#include <vector>

#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"
#include "nava_modem/modem_options.h"

namespace nava_modem {

// The errors the search weighed and let pass: each the frame's data bits (byte * 8 + bit) that one
// competitor path would have changed together (a transition moved by a bit or two changes
// several), the weakest first; events that would change a start or stop bit are left out.
using ErrorEvents = std::vector<std::vector<int>>;

// Sequence estimation of a packet's bits through a room, from the complex outputs of the two
// tone filters (ToneFilters) at the end of each bit.
//
// Why complex: a room is linear and the same for the whole packet, but its early reflections
// (1.5 to 12 bits late at 300 bits/s) add to a bit's tone coherently, so a filter's power is
// not a sum of powers of earlier bits: whether an echo of an earlier MARK bit strengthens or
// cancels the present one depends on the phase between them. The modulator's phase is
// continuous, so in the MARK filter's frame a MARK bit keeps the phase of the MARK bit before
// it and each SPACE bit in between turns it by 2 pi (f_space - f_mark) / baud, known once the
// bits are. Each filter's output is then a linear function of the bits' complex symbols:
//
//   y_t(k) = sum over lags l of  a_t(l) [bit k-l sends tone t] e^{j phase_t(k-l)}
//                              + c_t(l) [bit k-l sends the other tone] e^{j phase_t(k-l)}
//
// with a sender's clock offset turning every output by a further e^{j dw_t n} (n the sample).
// The taps a, c (the room's response as each filter sees each tone, a bit early to 12 bits
// late) are fitted by least squares: first on the observations whose bits are all known (the
// break, the header with its start and stop bits), then on the whole packet with its other
// bits as decided; the sender's offset by a search on the fit. The frame's bits are decided by
// a Viterbi search over the last few bits, the older ones taken from each survivor's own path
// (per-survivor processing), with soft outputs (SOVA); then fitted and decided again. The
// frame's known bits are decided freely, not forced: its start and stop bits must all come
// out right (and its header, checked by RepairFrame) for a pass to count, which keeps the
// header's and framing's protection against a wrong packet passing the CRC.
class FskEqualizer {
 public:
  explicit FskEqualizer(const ModemOptions& modem);

  // heard[t][k], k = 0 .. kPacketBits - 1 (bit 0: the break's first SPACE bit): tone t's
  // (0 MARK, 1 SPACE) complex filter output at the end of bit k, taken at sample at[k].
  // `frequency_error`: the sender's estimated clock offset (fraction). The first fit is made on
  // the packet's known bits alone (the break and the header), so no first decisions on the frame
  // are asked for: where the room confuses the filters they would be wrong. Each pass of fitting
  // and deciding whose start and stop bits all came out right offers its soft decisions on the
  // frame to `accept`, until it returns true (later passes refit on the earlier decisions), with
  // the pass's error events. True when one was accepted.
  using Accept = std::function<bool(const SoftFrame&, const ErrorEvents&)>;
  bool Equalize(const std::complex<double>* const heard[2], const double* at, double frequency_error,
                const Accept& accept) const;

 private:
  ModemOptions modem_;
};

}  // namespace nava_modem
