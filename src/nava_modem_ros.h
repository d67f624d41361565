#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <multirobot_audio/AudioPacket.h>
#include <ros/ros.h>

#include "input_guard.h"
#include "nava_modem/alsa_device.h"
#include "nava_modem/nava_link.h"
#include "ranging_ros.h"

namespace multirobot_audio {

// Options of the nava_modem node, filled from its private parameters.
struct NavaModemOptions {
  nava_modem::AlsaOptions alsa;   // ~device, ~sample_rate, ~latency, ~channels
  nava_modem::LinkOptions link;   // modem, MAC, receiver and device-fault settings (see docs/nodes.md)
  std::string frame_id = "base_link";  // ~frame_id: stamped on what is published
  double carrier_rate = 10.0;     // ~carrier_rate: Hz of audio/carrier besides every change
  bool ranging_on = true;         // ~ranging: time packets and range the team (off: no timings at all)
  RangingRosOptions ranging;      // ~robot, ~team, ~timings_topic, ... (ranging_ros.h)
};

NavaModemOptions ReadNavaModemOptions(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

// A robot's audio link on its sound card: audio/tx in, audio/rx and audio/carrier out (the
// interface audio_propagation serves in simulation), diagnostics on /diagnostics. The link runs
// in a thread of its own, paced by the sound card.
class NavaModemRos {
 public:
  NavaModemRos(ros::NodeHandle nh, ros::NodeHandle pnh, const NavaModemOptions& options);
  ~NavaModemRos();

 private:
  InputGuard::Verdict OnTx(const multirobot_audio::AudioPacket::ConstPtr& msg);
  void AudioLoop();
  // Logs what changed between two of the link's states: a failure, a reopen, a catch-up, a cut
  // packet, an overrun.
  void Report(const nava_modem::LinkStatus& before, const nava_modem::LinkStatus& now);
  void DiagnoseDevice(diagnostic_updater::DiagnosticStatusWrapper& status);
  void Publish(const nava_modem::RxEvent& event, double ago);
  double RangingRateError(const nava_modem::RxEvent& e) const;
  // The capture clock's life for ranging: it restarts with the device, and loses samples (so no
  // longer runs with true time) at a capture overrun.
  std::uint32_t ClockEpoch() const { return static_cast<std::uint32_t>(link_->device_faults() + link_->overruns()); }
  void Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_, pnh_;
  NavaModemOptions options_;
  std::unique_ptr<nava_modem::AlsaDevice> device_;
  std::unique_ptr<nava_modem::NavaLink> link_;
  ros::Subscriber tx_sub_;
  ros::Publisher rx_pub_, carrier_pub_, direction_pub_;  // ~directions: an arrow per reception with a direction
  std::uint32_t direction_id_ = 0;
  diagnostic_updater::Updater updater_;
  InputGuard guard_;  // audio/tx's and the team's timings' checks and counts, on updater_
  std::unique_ptr<RangingRos> ranging_;
  ros::WallTimer diagnostics_timer_;
  std::mutex mutex_;  // guards inbox_, status_ and down_since_
  std::deque<std::vector<std::uint8_t>> inbox_;  // audio/tx for the audio thread; at most the MAC queue's capacity
  nava_modem::LinkStatus status_;  // as the audio thread last read it
  ros::WallTime down_since_;       // when the device last failed
  std::atomic<bool> running_{true};
  std::thread audio_thread_;
};

}  // namespace multirobot_audio
