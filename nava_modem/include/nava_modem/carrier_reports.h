#pragma once

namespace nava_modem {

// When a link's carrier sense is worth reporting: at every change, and otherwise every `period`
// s of the link's clock (so that a listener that joins late learns it, without a message a tick).
class CarrierReports {
 public:
  explicit CarrierReports(double period) : period_(period) {}
  // True when the carrier heard at `time` is to be reported now (it is then taken as reported).
  bool Due(bool carrier, double time) {
    if (carrier == last_ && time - last_time_ < period_) return false;
    last_ = carrier;
    last_time_ = time;
    return true;
  }

 private:
  double period_;
  bool last_ = false;
  double last_time_ = -1e300;
};

}  // namespace nava_modem
