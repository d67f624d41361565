#ifndef NAVA_MODEM_MATH_CONSTANTS_H
#define NAVA_MODEM_MATH_CONSTANTS_H

namespace nava_modem {

// C++17 has no std::numbers, and M_PI is POSIX, not standard.
inline constexpr double kPi = 3.141592653589793;
inline constexpr double kTwoPi = 2.0 * kPi;
// Added to powers and variances before they divide or go into a logarithm, so that a silent
// window gives a finite number: far under any level a sound card delivers (16-bit full scale
// squared is 1, its least step squared about 1e-9).
inline constexpr double kTiny = 1e-20;

}  // namespace nava_modem

#endif  // NAVA_MODEM_MATH_CONSTANTS_H
