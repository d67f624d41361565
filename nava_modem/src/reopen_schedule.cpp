#include "nava_modem/reopen_schedule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nava_modem {

void ValidateReopenOptions(const ReopenOptions& o) {
  if (!(o.first_wait > 0.0 && o.first_wait <= 60.0)) {
    throw std::invalid_argument("reopen first wait " + std::to_string(o.first_wait) + " s: expected above 0 and at most 60");
  }
  if (!(o.max_wait >= o.first_wait && o.max_wait <= 600.0)) {
    throw std::invalid_argument("reopen max wait " + std::to_string(o.max_wait) + " s: expected at least the first wait (" +
                                std::to_string(o.first_wait) + " s) and at most 600");
  }
  if (!(o.settle_time >= 0.0 && o.settle_time <= 60.0)) {
    throw std::invalid_argument("reopen settle time " + std::to_string(o.settle_time) + " s: expected 0 to 60");
  }
}

ReopenSchedule::ReopenSchedule(const ReopenOptions& options) : options_(options) { ValidateReopenOptions(options_); }

void ReopenSchedule::Start(double now) {
  wait_ = options_.first_wait;
  next_ = now + wait_;
  failed_ = 0;
}

void ReopenSchedule::Failed(double now) {
  ++failed_;
  wait_ = std::min(2.0 * wait_, options_.max_wait);
  next_ = now + wait_;
}

}  // namespace nava_modem
