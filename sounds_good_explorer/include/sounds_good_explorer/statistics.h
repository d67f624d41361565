#pragma once

#include <vector>

namespace sounds_good_explorer {

struct SampleSummary {
  int n = 0;
  double mean = 0.0;
  double sd = 0.0;               // sample standard deviation (n - 1)
  double ci95 = 0.0;             // half-width of the 95 % confidence interval of the mean (t)
};

SampleSummary Summarize(const std::vector<double>& values);

// Two-tailed Student's t-test for two independent samples with a pooled variance, as the thesis
// reports in Table 3.2. `gain` is the performance gain of method b over method a:
// mean(a) / mean(b) - 1 (times taken, so a faster b gains).
struct TTest {
  double t = 0.0;   // (mean a - mean b) / standard error; positive when b is faster
  double p = 1.0;   // two-tailed
  double gain = 0.0;
};

TTest StudentTTest(const std::vector<double>& a, const std::vector<double>& b);

// Stouffer's combination of independent two-tailed tests of the same direction of effect
// (one per configuration): each signed t becomes the normal z of its p, and
// Z = sum z / sqrt(k) is tested two-tailed. Unlike one t-test on all trials pooled, it does not
// drown a consistent effect in the spread between configurations. `gain` is the geometric mean
// of the per-test gains (1 + gain).
struct CombinedTest {
  double z = 0.0;
  double p = 1.0;
  double gain = 0.0;
};

CombinedTest Stouffer(const std::vector<TTest>& tests);

}  // namespace sounds_good_explorer
