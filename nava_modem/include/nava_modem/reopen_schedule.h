#pragma once

namespace nava_modem {

// How a link comes back after its audio device failed.
struct ReopenOptions {
  double first_wait = 0.1;  // s from the failure to the first try at reopening
  double max_wait = 2.0;    // s: the wait doubles after each failed try, up to this
  // s a reopened link listens before it sends: a sound server's new stream often underruns
  // as it starts (which would cut a packet), and other links that lost the same device or
  // server need a moment to be back and hearing.
  double settle_time = 0.5;
};

// Throws std::invalid_argument naming the option when it is impossible.
void ValidateReopenOptions(const ReopenOptions& options);

// When to try reopening a failed device: first_wait after the failure, then after waits that
// double from there up to max_wait (0.1, 0.3, 0.7, 1.5, 3.1, 5.1, ... s with the defaults), so
// that a card gone for a moment is back at once and one gone for good costs a try every
// max_wait. Times are the caller's clock's (s).
class ReopenSchedule {
 public:
  explicit ReopenSchedule(const ReopenOptions& options);

  void Start(double now);   // the device has just failed
  void Failed(double now);  // a try at `now` failed: the next comes a doubled wait later
  double next_try() const { return next_; }
  int failed_tries() const { return failed_; }  // since Start()

 private:
  ReopenOptions options_;
  double wait_ = 0.0, next_ = 0.0;
  int failed_ = 0;
};

}  // namespace nava_modem
