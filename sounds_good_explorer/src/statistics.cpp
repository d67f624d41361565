#include "sounds_good_explorer/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace sounds_good_explorer {

SampleSummary Summarize(const std::vector<double>& values) {
  SampleSummary s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / s.n;
  if (s.n < 2) return s;
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / (s.n - 1));
  const boost::math::students_t t(s.n - 1);
  s.ci95 = boost::math::quantile(boost::math::complement(t, 0.025)) * s.sd / std::sqrt(s.n);
  return s;
}

TTest StudentTTest(const std::vector<double>& a, const std::vector<double>& b) {
  const SampleSummary sa = Summarize(a), sb = Summarize(b);
  TTest result;
  if (sa.n == 0 || sb.n == 0) return result;
  result.gain = sb.mean > 0.0 ? sa.mean / sb.mean - 1.0 : std::numeric_limits<double>::quiet_NaN();
  const int dof = sa.n + sb.n - 2;
  if (dof < 1) return result;
  const double pooled = ((sa.n - 1) * sa.sd * sa.sd + (sb.n - 1) * sb.sd * sb.sd) / dof;
  const double error = std::sqrt(pooled * (1.0 / sa.n + 1.0 / sb.n));
  if (error == 0.0) {
    // Two constant samples: equal means are no difference, unequal ones are certain.
    result.t = sa.mean == sb.mean ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(),
                                                        sa.mean - sb.mean);
    result.p = sa.mean == sb.mean ? 1.0 : 0.0;
    return result;
  }
  result.t = (sa.mean - sb.mean) / error;
  result.p = 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(dof),
                                                            std::abs(result.t)));
  return result;
}

CombinedTest Stouffer(const std::vector<TTest>& tests) {
  CombinedTest result;
  if (tests.empty()) return result;
  const boost::math::normal unit;
  double z_sum = 0.0, log_gain = 0.0;
  for (const TTest& t : tests) {
    // p of 0 (constant samples) would give an infinite z: cap it at a p of 1e-300.
    const double p = std::clamp(t.p, 1e-300, 1.0);
    const double z = boost::math::quantile(boost::math::complement(unit, p / 2.0));
    z_sum += t.t >= 0.0 ? z : -z;
    log_gain += std::log1p(t.gain);
  }
  result.z = z_sum / std::sqrt(static_cast<double>(tests.size()));
  result.p = 2.0 * boost::math::cdf(boost::math::complement(unit, std::abs(result.z)));
  result.gain = std::expm1(log_gain / tests.size());
  return result;
}

}  // namespace sounds_good_explorer
