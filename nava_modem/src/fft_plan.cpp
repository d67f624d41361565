#include "nava_modem/fft_plan.h"

#include <algorithm>
#include <climits>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>

#include <fftw3.h>

namespace nava_modem {
namespace {

// FFTW's planner keeps global state (its wisdom, the twiddle tables): making or destroying a
// plan from two threads at once corrupts it. Only this file makes or destroys plans.
std::mutex& PlannerMutex() {
  static std::mutex m;
  return m;
}

bool RealInput(FftKind kind) { return kind == FftKind::kRealToComplex; }
bool RealOutput(FftKind kind) { return kind == FftKind::kComplexToReal; }

std::size_t HalfSpectrum(std::size_t n) { return n / 2 + 1; }

void* Allocate(bool real, std::size_t length) {
  void* p = real ? static_cast<void*>(fftw_alloc_real(length)) : static_cast<void*>(fftw_alloc_complex(length));
  if (!p) throw std::bad_alloc();
  return p;
}

void Zero(void* p, bool real, std::size_t length) {
  double* d = static_cast<double*>(p);
  std::fill(d, d + (real ? length : 2 * length), 0.0);
}

[[noreturn]] void WrongArray(const char* which, FftKind kind) {
  static const char* const kNames[] = {"real-to-complex", "complex-to-real", "complex backward"};
  throw std::logic_error(std::string("FFT: a ") + kNames[static_cast<int>(kind)] + " transform has no " + which);
}

}  // namespace

void FftBuffers::Free::operator()(void* p) const { fftw_free(p); }

FftBuffers::FftBuffers(FftKind kind, std::size_t size) : kind_(kind), size_(size) {
  if (size == 0) throw std::invalid_argument("FFT: size 0");
  input_.reset(Allocate(RealInput(kind), input_length()));
  output_.reset(Allocate(RealOutput(kind), output_length()));
  // Zeroed, so that nothing reads memory no one wrote (a caller that fills only the first bins).
  Zero(input_.get(), RealInput(kind), input_length());
  Zero(output_.get(), RealOutput(kind), output_length());
}

std::size_t FftBuffers::input_length() const { return kind_ == FftKind::kComplexToReal ? HalfSpectrum(size_) : size_; }

std::size_t FftBuffers::output_length() const { return kind_ == FftKind::kRealToComplex ? HalfSpectrum(size_) : size_; }

double* FftBuffers::real_input() {
  if (!RealInput(kind_)) WrongArray("real input", kind_);
  return static_cast<double*>(input_.get());
}

std::complex<double>* FftBuffers::complex_input() {
  if (RealInput(kind_)) WrongArray("complex input", kind_);
  return static_cast<std::complex<double>*>(input_.get());
}

const double* FftBuffers::real_output() const {
  if (!RealOutput(kind_)) WrongArray("real output", kind_);
  return static_cast<const double*>(output_.get());
}

const std::complex<double>* FftBuffers::complex_output() const {
  if (RealOutput(kind_)) WrongArray("complex output", kind_);
  return static_cast<const std::complex<double>*>(output_.get());
}

void FftPlan::Destroy::operator()(fftw_plan_s* plan) const {
  const std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(plan);
}

FftPlan::FftPlan(FftKind kind, std::size_t size) : buffers_(kind, size) {
  if (size > static_cast<std::size_t>(INT_MAX)) {
    throw std::invalid_argument("FFT: size " + std::to_string(size) + " is beyond FFTW's int sizes");
  }
  const int n = static_cast<int>(size);
  // std::complex<double> and fftw_complex share their layout (FFTW's manual, section 4.1.1).
  void* in = buffers_.input_.get();
  void* out = buffers_.output_.get();
  fftw_plan plan = nullptr;
  {
    const std::lock_guard<std::mutex> lock(PlannerMutex());
    switch (kind) {
      case FftKind::kRealToComplex:
        plan = fftw_plan_dft_r2c_1d(n, static_cast<double*>(in), static_cast<fftw_complex*>(out), FFTW_ESTIMATE);
        break;
      case FftKind::kComplexToReal:
        plan = fftw_plan_dft_c2r_1d(n, static_cast<fftw_complex*>(in), static_cast<double*>(out), FFTW_ESTIMATE);
        break;
      case FftKind::kComplexBackward:
        plan = fftw_plan_dft_1d(n, static_cast<fftw_complex*>(in), static_cast<fftw_complex*>(out), FFTW_BACKWARD,
                                FFTW_ESTIMATE);
        break;
    }
  }
  if (!plan) throw std::runtime_error("FFT: FFTW could not plan a transform of size " + std::to_string(size));
  plan_.reset(plan);
}

void FftPlan::Execute() { Execute(buffers_); }

void FftPlan::Execute(FftBuffers& buffers) const {
  if (!plan_) throw std::logic_error("FFT: Execute on a moved-from plan");
  if (buffers.kind() != kind() || buffers.size() != size()) {
    throw std::invalid_argument("FFT: buffers of another kind or size than the plan's (size " + std::to_string(buffers.size()) +
                                ", plan size " + std::to_string(size()) + ")");
  }
  void* in = buffers.input_.get();
  void* out = buffers.output_.get();
  if (!in || !out) throw std::logic_error("FFT: Execute on moved-from buffers");
  // The new-array execute functions are thread-safe and do not plan; on the plan's own arrays
  // they are fftw_execute.
  switch (kind()) {
    case FftKind::kRealToComplex:
      fftw_execute_dft_r2c(plan_.get(), static_cast<double*>(in), static_cast<fftw_complex*>(out));
      break;
    case FftKind::kComplexToReal:
      fftw_execute_dft_c2r(plan_.get(), static_cast<fftw_complex*>(in), static_cast<double*>(out));
      break;
    case FftKind::kComplexBackward:
      fftw_execute_dft(plan_.get(), static_cast<fftw_complex*>(in), static_cast<fftw_complex*>(out));
      break;
  }
}

}  // namespace nava_modem
