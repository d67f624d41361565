#include "sounds_good_explorer/statistics.h"

#include <cmath>
#include <limits>
#include <numeric>

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

}  // namespace sounds_good_explorer
