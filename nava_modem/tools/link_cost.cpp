#include "link_cost.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "bench_support/child_process.h"
#include "nava_modem/nava_link.h"

namespace nava_modem::tools {
namespace {

// A sound card whose capture is its own playback `loop` samples later plus `others` (the
// teammates' packets and the room's noise, made beforehand so that the bench's own work does not
// count); it runs out at the end of `others`.
class SharedAir : public AudioDevice {
 public:
  SharedAir(double rate, std::size_t loop, const std::vector<float>& others) : rate_(rate), loop_(loop), others_(others) {}
  double sample_rate() const override { return rate_; }
  bool Read(float* out, std::size_t count) override {
    if (read_ + count > others_.size()) return false;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t n = read_ + k;
      out[k] = others_[n] + (n >= loop_ && n - loop_ < played_.size() ? played_[n - loop_] : 0.0f);
    }
    read_ += count;
    return true;
  }
  void Write(const float* in, std::size_t count) override { played_.insert(played_.end(), in, in + count); }
  std::size_t PlaybackDelay() override { return 0; }
  std::size_t PlaybackRoom() override { return std::numeric_limits<std::size_t>::max(); }
  std::size_t CaptureLag() override { return 0; }
  void Reopen() override {}
  std::uint64_t overruns() const override { return 0; }
  std::uint64_t underruns() const override { return 0; }

 private:
  double rate_;
  std::size_t loop_, read_ = 0;
  const std::vector<float>& others_;
  std::vector<float> played_;
};

struct Run {
  double cpu = std::numeric_limits<double>::infinity();
  std::size_t heard = 0, timed = 0, own_timed = 0, sent = 0;
};

Run RunLink(const LinkCostRequest& r, bool time_arrivals, const std::vector<float>& others) {
  LinkOptions o;
  o.profile = r.profile;
  o.modem = r.options;
  o.mac.calibration_time = 0.5;
  o.mac.fixed_threshold_db = -30.0;
  o.receiver.time_arrivals = time_arrivals;
  const double rate = o.modem.sample_rate;
  Run best;
  for (int k = 0; k < r.runs; ++k) {
    SharedAir air(rate, static_cast<std::size_t>(0.083 * rate), others);
    NavaLink link(o, air);
    std::vector<RxEvent> events;
    Run run;
    const double start = bench_support::CpuNow();
    double next_send = 1.0;
    std::uint8_t counter = 0;
    while (link.Tick(events)) {
      if (link.time() >= next_send) {
        link.Send({0x51, counter++, 0x00, 0x01});
        next_send += r.period;
      }
      for (const OwnTiming& t : link.TakeOwnTimings()) run.own_timed += std::isfinite(t.arrival);
    }
    run.cpu = bench_support::CpuNow() - start;
    for (const RxEvent& e : events) {
      run.heard += e.kind == RxEvent::Kind::kPacket;
      run.timed += std::isfinite(e.arrival);
    }
    run.sent = link.packets_sent();
    if (run.cpu < best.cpu) best = run;
  }
  return best;
}

}  // namespace

int LinkCostTable(const LinkCostRequest& r) {
  const std::unique_ptr<ModemProfile> profile = MakeProfile(r.profile, r.options);
  const double rate = r.options.sample_rate;
  // Two teammates, each a packet every period, a third of a period apart from each other and
  // from this link's own sends (which start at 1 s).
  std::vector<float> others(static_cast<std::size_t>(r.seconds * rate));
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 0.003f);
  for (float& v : others) v = noise(rng);
  std::uint8_t counter = 0;
  for (int mate = 1; mate <= 2; ++mate) {
    for (double t = 1.0 + mate * r.period / 3.0; t + profile->Airtime() < r.seconds; t += r.period) {
      const std::vector<float> burst = profile->ModulatePacket({0x60, static_cast<std::uint8_t>(mate), counter++, 0x02});
      const std::size_t at = static_cast<std::size_t>(t * rate);
      for (std::size_t k = 0; k < burst.size() && at + k < others.size(); ++k) others[at + k] += 0.3f * burst[k];
    }
  }
  const Run off = RunLink(r, false, others), on = RunLink(r, true, others);
  std::printf("link cost (%s profile, %.0f s of audio at %.0f Hz, a packet every %.1f s from this link and from each of two "
              "teammates, its own sound back after 83 ms; the least CPU of %d runs)\n",
              ProfileName(r.profile), r.seconds, rate, r.period, r.runs);
  std::printf("%-22s %10s %12s %8s %8s %10s\n", "timing", "cpu_s", "real_time_x", "sent", "heard", "timed");
  std::printf("%-22s %10.3f %12.0f %8zu %8zu %10s\n", "off", off.cpu, r.seconds / off.cpu, off.sent, off.heard, "-");
  std::printf("%-22s %10.3f %12.0f %8zu %8zu %4zu + %zu own\n", "on (ranging)", on.cpu, r.seconds / on.cpu, on.sent, on.heard, on.timed,
              on.own_timed);
  const double added = on.cpu / off.cpu - 1.0;
  std::printf("ranging adds %.1f %% to the link's CPU; target <= 10 %%: %s\n", 100.0 * added, added <= 0.10 ? "yes" : "NO");
  return 0;
}

}  // namespace nava_modem::tools
