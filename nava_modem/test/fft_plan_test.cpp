#include "nava_modem/fft_plan.h"

#include <atomic>
#include <cmath>
#include <complex>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/real_fft.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;

// The DFT by its definition, sign -1 (forward) or +1 (backward): the reference the plans are
// held to, slow but beyond doubt.
std::vector<Complex> Dft(const std::vector<Complex>& x, int sign) {
  const std::size_t n = x.size();
  std::vector<Complex> y(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t t = 0; t < n; ++t) {
      // k * t mod n keeps the angle small, so that the reference itself is accurate.
      const double angle = sign * 2.0 * M_PI * static_cast<double>((k * t) % n) / static_cast<double>(n);
      y[k] += x[t] * std::polar(1.0, angle);
    }
  }
  return y;
}

std::vector<double> RandomReal(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

// Sizes with large prime factors too: FFTW plans those differently from powers of two.
const std::vector<std::size_t> kSizes = {1, 2, 3, 7, 12, 90, 97, 210, 256, 1000, 1024, 4099};

TEST(FftPlanTest, ForwardOfACosineLandsInItsBinWithHalfTheSizeTimesItsAmplitude) {
  for (std::size_t n : {64, 90, 97}) {
    const std::size_t bin = 5;
    const double amplitude = 0.7;
    FftPlan plan(FftKind::kRealToComplex, n);
    ASSERT_EQ(plan.input_length(), n);
    ASSERT_EQ(plan.output_length(), n / 2 + 1);
    for (std::size_t t = 0; t < n; ++t) {
      plan.real_input()[t] = amplitude * std::cos(2.0 * M_PI * static_cast<double>(bin * t) / static_cast<double>(n));
    }
    plan.Execute();
    for (std::size_t k = 0; k <= n / 2; ++k) {
      const Complex expected = k == bin ? Complex(amplitude * static_cast<double>(n) / 2.0, 0.0) : Complex(0.0, 0.0);
      EXPECT_NEAR(plan.complex_output()[k].real(), expected.real(), 1e-9) << "n " << n << " bin " << k;
      EXPECT_NEAR(plan.complex_output()[k].imag(), expected.imag(), 1e-9) << "n " << n << " bin " << k;
    }
  }
}

TEST(FftPlanTest, ForwardUsesTheMinusSignInTheExponent) {
  // sin = (e^{+i} - e^{-i}) / 2i: with exp(-i...) in the forward transform, bin k of a sine is
  // -i n/2.
  const std::size_t n = 48, bin = 3;
  FftPlan plan(FftKind::kRealToComplex, n);
  for (std::size_t t = 0; t < n; ++t) plan.real_input()[t] = std::sin(2.0 * M_PI * static_cast<double>(bin * t) / n);
  plan.Execute();
  EXPECT_NEAR(plan.complex_output()[bin].real(), 0.0, 1e-9);
  EXPECT_NEAR(plan.complex_output()[bin].imag(), -static_cast<double>(n) / 2.0, 1e-9);
}

TEST(FftPlanTest, RealForwardMatchesTheDefinitionAtEverySize) {
  for (std::size_t n : kSizes) {
    if (n > 1024) continue;  // the reference is quadratic
    const std::vector<double> x = RandomReal(n, static_cast<unsigned>(n));
    FftPlan plan(FftKind::kRealToComplex, n);
    std::copy(x.begin(), x.end(), plan.real_input());
    plan.Execute();
    const std::vector<Complex> expected = Dft(std::vector<Complex>(x.begin(), x.end()), -1);
    for (std::size_t k = 0; k <= n / 2; ++k) {
      EXPECT_NEAR(std::abs(plan.complex_output()[k] - expected[k]), 0.0, 1e-9) << "n " << n << " bin " << k;
    }
  }
}

TEST(FftPlanTest, InverseOfForwardGivesBackTheSignal) {
  for (std::size_t n : kSizes) {
    const std::vector<double> x = RandomReal(n, 1000 + static_cast<unsigned>(n));
    FftPlan forward(FftKind::kRealToComplex, n);
    FftPlan inverse(FftKind::kComplexToReal, n);
    ASSERT_EQ(inverse.input_length(), n / 2 + 1);
    ASSERT_EQ(inverse.output_length(), n);
    std::copy(x.begin(), x.end(), forward.real_input());
    forward.Execute();
    std::copy(forward.complex_output(), forward.complex_output() + forward.output_length(), inverse.complex_input());
    inverse.Execute();
    for (std::size_t t = 0; t < n; ++t) {
      EXPECT_NEAR(inverse.real_output()[t] / static_cast<double>(n), x[t], 1e-12) << "n " << n << " sample " << t;
    }
    // The convenience functions on top, which also scale by 1/n.
    const std::vector<double> y = InverseFft(ForwardFft(x, n), n);
    ASSERT_EQ(y.size(), n);
    for (std::size_t t = 0; t < n; ++t) EXPECT_NEAR(y[t], x[t], 1e-12) << "n " << n << " sample " << t;
  }
}

TEST(FftPlanTest, ComplexToRealOfOneBinIsACosineCountedWithItsMirror) {
  const std::size_t n = 100, bin = 7;
  FftPlan plan(FftKind::kComplexToReal, n);
  plan.complex_input()[bin] = Complex(0.5, 0.0);
  plan.Execute();
  for (std::size_t t = 0; t < n; ++t) {
    EXPECT_NEAR(plan.real_output()[t], std::cos(2.0 * M_PI * static_cast<double>(bin * t) / n), 1e-12) << t;
  }
}

TEST(FftPlanTest, ComplexBackwardOfOneBinIsAPhasorTurningForwards) {
  for (std::size_t n : {16, 30, 97}) {
    const std::size_t bin = 3;
    FftPlan plan(FftKind::kComplexBackward, n);
    ASSERT_EQ(plan.input_length(), n);
    ASSERT_EQ(plan.output_length(), n);
    plan.complex_input()[bin] = Complex(2.0, 0.0);
    plan.Execute();
    for (std::size_t t = 0; t < n; ++t) {
      const Complex expected = std::polar(2.0, 2.0 * M_PI * static_cast<double>((bin * t) % n) / static_cast<double>(n));
      EXPECT_NEAR(std::abs(plan.complex_output()[t] - expected), 0.0, 1e-12) << "n " << n << " sample " << t;
    }
  }
}

TEST(FftPlanTest, ComplexBackwardMatchesTheDefinition) {
  for (std::size_t n : {1, 5, 64, 210}) {
    std::mt19937 rng(static_cast<unsigned>(n));
    std::normal_distribution<double> g;
    std::vector<Complex> spectrum(n);
    for (Complex& v : spectrum) v = Complex(g(rng), g(rng));
    FftPlan plan(FftKind::kComplexBackward, n);
    std::copy(spectrum.begin(), spectrum.end(), plan.complex_input());
    plan.Execute();
    const std::vector<Complex> expected = Dft(spectrum, +1);
    for (std::size_t t = 0; t < n; ++t) {
      EXPECT_NEAR(std::abs(plan.complex_output()[t] - expected[t]), 0.0, 1e-9) << "n " << n << " sample " << t;
    }
  }
}

TEST(FftPlanTest, ArraysStartZeroed) {
  FftPlan plan(FftKind::kComplexBackward, 33);
  for (std::size_t k = 0; k < 33; ++k) {
    EXPECT_EQ(plan.complex_input()[k], Complex(0.0, 0.0));
    EXPECT_EQ(plan.complex_output()[k], Complex(0.0, 0.0));
  }
  FftBuffers buffers = FftPlan(FftKind::kRealToComplex, 9).MakeBuffers();
  for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(buffers.real_input()[k], 0.0);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(buffers.complex_output()[k], Complex(0.0, 0.0));
}

TEST(FftPlanTest, ExecutingOnOtherBuffersGivesTheSameBitsAndLeavesThePlansOwnAlone) {
  const std::size_t n = 360;
  const std::vector<double> x = RandomReal(n, 7);
  FftPlan plan(FftKind::kRealToComplex, n);
  std::copy(x.begin(), x.end(), plan.real_input());
  plan.Execute();
  const std::vector<Complex> own(plan.complex_output(), plan.complex_output() + plan.output_length());

  FftBuffers other = plan.MakeBuffers();
  ASSERT_EQ(other.input_length(), n);
  std::copy(x.begin(), x.end(), other.real_input());
  other.real_input()[0] += 1.0;  // a different signal, so that mixing up the arrays shows
  static_cast<const FftPlan&>(plan).Execute(other);
  EXPECT_EQ(std::vector<Complex>(plan.complex_output(), plan.complex_output() + n / 2 + 1), own);
  for (std::size_t k = 0; k <= n / 2; ++k) {
    EXPECT_NEAR(std::abs(other.complex_output()[k] - own[k] - Complex(1.0, 0.0)), 0.0, 1e-12) << k;
  }
  std::copy(x.begin(), x.end(), other.real_input());
  plan.Execute(other);
  for (std::size_t k = 0; k <= n / 2; ++k) EXPECT_EQ(other.complex_output()[k], own[k]) << k;
}

TEST(FftPlanTest, MisuseIsRefused) {
  EXPECT_THROW(FftPlan(FftKind::kRealToComplex, 0), std::invalid_argument);
  EXPECT_THROW(FftBuffers(FftKind::kComplexBackward, 0), std::invalid_argument);

  FftPlan forward(FftKind::kRealToComplex, 8);
  EXPECT_THROW(forward.complex_input(), std::logic_error);
  EXPECT_THROW(forward.real_output(), std::logic_error);
  FftPlan inverse(FftKind::kComplexToReal, 8);
  EXPECT_THROW(inverse.real_input(), std::logic_error);
  EXPECT_THROW(inverse.complex_output(), std::logic_error);
  FftPlan backward(FftKind::kComplexBackward, 8);
  EXPECT_THROW(backward.real_input(), std::logic_error);
  EXPECT_THROW(backward.real_output(), std::logic_error);

  FftBuffers wrong_size(FftKind::kRealToComplex, 16);
  EXPECT_THROW(forward.Execute(wrong_size), std::invalid_argument);
  FftBuffers wrong_kind(FftKind::kComplexBackward, 8);
  EXPECT_THROW(forward.Execute(wrong_kind), std::invalid_argument);
}

TEST(FftPlanTest, MovingHandsThePlanAndItsArraysOver) {
  const std::size_t n = 20;
  const std::vector<double> x = RandomReal(n, 3);
  FftPlan first(FftKind::kRealToComplex, n);
  std::copy(x.begin(), x.end(), first.real_input());
  const double* arrays = first.real_input();

  FftPlan moved(std::move(first));
  EXPECT_EQ(moved.real_input(), arrays);  // the same arrays, not copies
  moved.Execute();
  const std::vector<Complex> expected = Dft(std::vector<Complex>(x.begin(), x.end()), -1);
  for (std::size_t k = 0; k <= n / 2; ++k) EXPECT_NEAR(std::abs(moved.complex_output()[k] - expected[k]), 0.0, 1e-12);
  EXPECT_THROW(first.Execute(), std::logic_error);  // NOLINT(bugprone-use-after-move): what is left must not run

  // Assignment destroys the target's own plan and takes the other's (a leak would show under
  // the sanitizer build).
  FftPlan assigned(FftKind::kComplexBackward, 5);
  assigned = std::move(moved);
  EXPECT_EQ(assigned.kind(), FftKind::kRealToComplex);
  EXPECT_EQ(assigned.size(), n);
  assigned.Execute();
  for (std::size_t k = 0; k <= n / 2; ++k) EXPECT_NEAR(std::abs(assigned.complex_output()[k] - expected[k]), 0.0, 1e-12);
}

// The planner is not thread-safe: plans made and destroyed on several threads at once, of many
// sizes, must all still transform correctly (without the lock this corrupts FFTW's tables or
// crashes).
TEST(FftPlanTest, PlansMadeOnSeveralThreadsAtOnceAreAllCorrect) {
  constexpr int kThreads = 8, kRounds = 40;
  std::atomic<int> wrong{0}, done{0};
  std::vector<std::thread> threads;
  for (int th = 0; th < kThreads; ++th) {
    threads.emplace_back([th, &wrong, &done] {
      for (int round = 0; round < kRounds; ++round) {
        const std::size_t n = kSizes[static_cast<std::size_t>(th + round) % kSizes.size()] + static_cast<std::size_t>(round % 3);
        const std::vector<double> x = RandomReal(n, static_cast<unsigned>(th * 1000 + round));
        FftPlan forward(FftKind::kRealToComplex, n);
        FftPlan inverse(FftKind::kComplexToReal, n);
        FftPlan backward(FftKind::kComplexBackward, n);
        std::copy(x.begin(), x.end(), forward.real_input());
        forward.Execute();
        std::copy(forward.complex_output(), forward.complex_output() + forward.output_length(), inverse.complex_input());
        inverse.Execute();
        for (std::size_t t = 0; t < n; ++t) {
          if (std::abs(inverse.real_output()[t] / static_cast<double>(n) - x[t]) > 1e-12) ++wrong;
        }
        // The complex transform of the full (Hermitian) spectrum gives back the real signal too.
        for (std::size_t k = 0; k < n; ++k) {
          backward.complex_input()[k] = k <= n / 2 ? forward.complex_output()[k] : std::conj(forward.complex_output()[n - k]);
        }
        backward.Execute();
        for (std::size_t t = 0; t < n; ++t) {
          const Complex y = backward.complex_output()[t] / static_cast<double>(n);
          if (std::abs(y - x[t]) > 1e-12) ++wrong;
        }
        ++done;
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(done.load(), kThreads * kRounds);
  EXPECT_EQ(wrong.load(), 0);
}

TEST(FftPlanTest, OnePlanRunsOnSeveralThreadsAtOnceEachWithItsOwnBuffers) {
  const std::size_t n = 1024;
  const FftPlan plan(FftKind::kRealToComplex, n);
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int th = 0; th < 4; ++th) {
    threads.emplace_back([th, &plan, &wrong] {
      const std::vector<double> x = RandomReal(n, 50 + static_cast<unsigned>(th));
      const std::vector<Complex> expected = ForwardFft(x, n);
      FftBuffers buffers = plan.MakeBuffers();
      for (int round = 0; round < 200; ++round) {
        std::copy(x.begin(), x.end(), buffers.real_input());
        plan.Execute(buffers);
        for (std::size_t k = 0; k <= n / 2; ++k) {
          if (buffers.complex_output()[k] != expected[k]) ++wrong;
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
}

}  // namespace
}  // namespace nava_modem
