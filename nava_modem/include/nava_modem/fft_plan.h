#pragma once

// One FFT of one kind and size, planned once and executed many times: the one place in
// nava_modem that talks to FFTW's planner. In the manner of liquid-dsp's fftplan (create,
// execute, destroy): the constructor plans, Execute() transforms, the destructor destroys.
//
// Why one object: FFTW's planner (making and destroying plans) is not thread-safe, only
// executing a plan is, and decode_table_bench renders rooms and decodes them on several threads
// at once (ForwardFft, the receivers' plans), while copies of a DirectionEstimator share theirs.
// Every plan made here takes the planner lock in fft_plan.cpp and nowhere else, so no caller can
// forget it. Plans are made with FFTW_ESTIMATE: the sizes here are used a few times each, or are
// powers of two, so measuring would cost more than it saves, and an estimated plan does not
// depend on timing, which keeps every transform bit-identical from run to run.
#include <complex>
#include <cstddef>
#include <memory>

// FFTW's opaque plan (fftw3.h: typedef struct fftw_plan_s* fftw_plan), so that this header
// does not pull fftw3.h into every user.
struct fftw_plan_s;

namespace nava_modem {

// All transforms are unnormalised, as FFTW's are: a forward then a backward transform of size n
// gives back n times the input.
enum class FftKind {
  kRealToComplex,    // forward: n real samples -> bins 0..n/2 (r2c)
  kComplexToReal,    // backward: bins 0..n/2 -> n real samples (c2r); overwrites its input
  kComplexBackward,  // backward, exponent +i: n complex bins -> n complex samples
};

// The input and output arrays of one transform's kind and size. Allocated by FFTW (SIMD-aligned,
// so that a plan's fast code paths apply) and zeroed. A plan owns one set; more come from
// FftPlan::MakeBuffers() for threads that share one plan (see FftPlan::Execute(FftBuffers&)).
// Accessors for the other kind's arrays throw std::logic_error: asking a real-to-complex
// transform for a complex input is a mistake in the caller, not in the data.
class FftBuffers {
 public:
  FftBuffers(FftKind kind, std::size_t size);

  FftKind kind() const { return kind_; }
  std::size_t size() const { return size_; }
  // Elements in the input and output arrays: n, or n/2 + 1 on the half-spectrum side.
  std::size_t input_length() const;
  std::size_t output_length() const;

  double* real_input();                          // kRealToComplex
  std::complex<double>* complex_input();         // kComplexToReal, kComplexBackward
  const double* real_output() const;             // kComplexToReal
  const std::complex<double>* complex_output() const;  // kRealToComplex, kComplexBackward

 private:
  friend class FftPlan;  // hands the raw arrays to FFTW
  struct Free {
    void operator()(void* p) const;
  };

  FftKind kind_;
  std::size_t size_;
  std::unique_ptr<void, Free> input_, output_;
};

class FftPlan {
 public:
  // Throws std::invalid_argument for size 0 or one beyond FFTW's int sizes, and
  // std::runtime_error if FFTW cannot plan it.
  FftPlan(FftKind kind, std::size_t size);

  FftKind kind() const { return buffers_.kind(); }
  std::size_t size() const { return buffers_.size(); }
  std::size_t input_length() const { return buffers_.input_length(); }
  std::size_t output_length() const { return buffers_.output_length(); }

  // This plan's own arrays: write the input, Execute(), read the output.
  double* real_input() { return buffers_.real_input(); }
  std::complex<double>* complex_input() { return buffers_.complex_input(); }
  const double* real_output() const { return buffers_.real_output(); }
  const std::complex<double>* complex_output() const { return buffers_.complex_output(); }

  // Transforms this plan's own input into its own output.
  void Execute();

  // Arrays of this plan's kind and size, for Execute(FftBuffers&).
  FftBuffers MakeBuffers() const { return FftBuffers(kind(), size()); }
  // Transforms `buffers`' input into its output with this plan. Const and thread-safe: several
  // threads may run one plan at once, each on arrays of its own, with no planning and no lock
  // (FFTW's new-array execute; the arrays must be FFTW-aligned, which FftBuffers are). Throws
  // std::invalid_argument if `buffers` are of another kind or size.
  void Execute(FftBuffers& buffers) const;

 private:
  struct Destroy {
    void operator()(fftw_plan_s* plan) const;  // under the planner lock
  };

  FftBuffers buffers_;
  std::unique_ptr<fftw_plan_s, Destroy> plan_;
};

}  // namespace nava_modem
