#include "nava_modem/bit_likelihood.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

// ln I0(x), the log of the modified Bessel function of order 0 (Abramowitz and Stegun 9.8.1,
// 9.8.2), for x >= 0.
double LogBesselI0(double x) {
  if (x < 3.75) {
    const double t = (x / 3.75) * (x / 3.75);
    return std::log(1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813))))));
  }
  const double t = 3.75 / x;
  return x - 0.5 * std::log(x) +
         std::log(0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281 +
                  t * (-0.02057706 + t * (0.02635537 + t * (-0.01647633 + t * 0.00392377))))))));
}

}  // namespace

double BitLlr(const double level[2], const double noise[2], double mark, double space) {
  const double heard[2] = {mark, space};
  double llr = 0.0;
  for (int t = 0; t < 2; ++t) {
    const double n = std::max(noise[t], kMinToneNoise * level[t]);
    const double l = LogBesselI0(2.0 * std::sqrt(level[t] * heard[t]) / n) - level[t] / n;
    llr += t == 0 ? l : -l;
  }
  return llr;
}

void ShrinkTones(double value[2], double var_log) {
  const double lr = std::log(value[0] / value[1]);
  const double kept = lr * lr / (lr * lr + var_log + kTiny) * lr;
  const double mid = std::sqrt(value[0] * value[1]);
  value[0] = mid * std::exp(kept / 2.0);
  value[1] = mid * std::exp(-kept / 2.0);
}

}  // namespace nava_modem
