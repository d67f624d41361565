#include "nava_modem_ros.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>

#include "conversions.h"
#include "rviz_markers.h"
#include "input_checks.h"
#include "nava_modem/carrier_reports.h"
#include "nava_modem/frame.h"
#include "params.h"

namespace multirobot_audio {

NavaModemRos::NavaModemRos(ros::NodeHandle nh, ros::NodeHandle pnh, const NavaModemOptions& options)
    : nh_(nh), pnh_(pnh), options_(options), updater_(nh, pnh), guard_(updater_) {
  device_ = std::make_unique<nava_modem::AlsaDevice>(options_.alsa);
  link_ = std::make_unique<nava_modem::NavaLink>(options_.link, *device_);
  if (options_.link.profile == nava_modem::Profile::kNava) {
    ROS_INFO("nava_modem: ALSA device '%s' at %.0f Hz; profile nava: MARK %.0f Hz, SPACE %.0f Hz, %.0f bits/s; %s",
             options_.alsa.device.c_str(), options_.alsa.sample_rate, options_.link.modem.mark_hz,
             options_.link.modem.space_hz, options_.link.modem.baud,
             options_.link.mac.fixed_threshold_db ? "fixed carrier threshold" : "calibrating on silence");
  } else {
    ROS_INFO("nava_modem: ALSA device '%s' at %.0f Hz; profile %s: %.2f s a packet; %s", options_.alsa.device.c_str(),
             options_.alsa.sample_rate, nava_modem::ProfileName(options_.link.profile), link_->profile().Airtime(),
             options_.link.mac.fixed_threshold_db ? "fixed carrier threshold" : "calibrating on silence");
  }
  tx_sub_ = guard_.Subscribe<multirobot_audio::AudioPacket>(
      nh_, "audio/tx", 20,
      [format = link_->profile().Format()](const multirobot_audio::AudioPacket& m) {
        return PacketProblem(m, format.min_bytes, format.max_bytes);
      },
      [this](const multirobot_audio::AudioPacket::ConstPtr& m) { return OnTx(m); });
  rx_pub_ = nh_.advertise<multirobot_audio::AudioReception>("audio/rx", 50);
  carrier_pub_ = nh_.advertise<multirobot_audio::CarrierSense>("audio/carrier", 20);
  direction_pub_ = pnh_.advertise<visualization_msgs::Marker>("directions", 20);
  updater_.setHardwareID("alsa:" + options_.alsa.device);
  updater_.add("audio link", this, &NavaModemRos::Diagnose);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  if (options_.ranging_on) ranging_ = std::make_unique<RangingRos>(nh_, options_.ranging, guard_, options_.frame_id);
  audio_thread_ = std::thread(&NavaModemRos::AudioLoop, this);
}

NavaModemRos::~NavaModemRos() {
  running_ = false;
  if (audio_thread_.joinable()) audio_thread_.join();
  const nava_modem::LinkStatus& s = status_;
  const auto n = [](std::uint64_t v) { return static_cast<unsigned long>(v); };
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("nava_modem summary: sent %lu, heard %lu packets (%lu repaired) and noise %lu zero_byte, %lu one_byte, "
              "%lu bad_crc; queue drops %lu; capture overruns %lu, playback underruns %lu, "
              "packets cut %lu",
              n(s.sent), n(s.heard.packets), n(s.heard.repaired), n(s.heard.zero_byte), n(s.heard.one_byte),
              n(s.heard.bad_crc), n(s.queue_drops), n(s.overruns), n(s.underruns), n(s.packets_cut));
  std::printf("; capture catch-ups %lu; device faults %lu, reopens %lu, packets re-queued %lu%s; %s\n", n(s.catch_ups),
              n(s.device_faults), n(s.reopens), n(s.requeued), s.device_down ? " (the device is down)" : "",
              guard_.Summary().c_str());
  if (ranging_) std::printf("nava_modem %s\n", ranging_->Summary().c_str());
  std::fflush(stdout);
}

InputGuard::Verdict NavaModemRos::OnTx(const multirobot_audio::AudioPacket::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  // The audio thread empties the inbox every period; a flood faster than that must not grow it.
  if (inbox_.size() >= options_.link.mac.queue_capacity) {
    return InputGuard::Verdict::Drop("the transmit inbox is full (the audio thread has not caught up)");
  }
  inbox_.push_back(msg->data);
  return InputGuard::Verdict::Accept();
}

void NavaModemRos::AudioLoop() {
  std::vector<nava_modem::RxEvent> events;
  nava_modem::CarrierReports carrier_reports(1.0 / options_.carrier_rate);
  try {
    while (running_ && ros::ok()) {
      std::deque<std::vector<std::uint8_t>> to_send;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        to_send.swap(inbox_);
      }
      for (auto& data : to_send) {
        if (ranging_) ranging_->Announce(data);
        if (!link_->Send(std::move(data))) {
          ROS_WARN_THROTTLE(5.0, "nava_modem: transmit queue full, packet dropped (%lu dropped so far)",
                            static_cast<unsigned long>(link_->mac().dropped()));
        }
      }
      events.clear();
      if (!link_->Tick(events)) break;
      for (const nava_modem::OwnTiming& t : link_->TakeOwnTimings()) {
        if (!ranging_) break;
        const double ago = std::isfinite(t.arrival) ? std::max(0.0, link_->time() - t.arrival) : 0.0;
        ranging_->OwnTiming(t.data, t.arrival, ClockEpoch(), ros::Time::now() - ros::Duration(ago));
      }
      if (ranging_) ranging_->SetClock(link_->time(), link_->card_rate_error());
      for (const nava_modem::RxEvent& e : events) Publish(e, link_->time() - e.end);
      if (carrier_reports.Due(link_->carrier(), link_->time())) {
        multirobot_audio::CarrierSense msg;
        msg.header.stamp = ros::Time::now();
        msg.header.frame_id = options_.frame_id;
        msg.carrier = link_->carrier();
        msg.level_db = static_cast<float>(link_->level_db());
        carrier_pub_.publish(msg);
      }
      nava_modem::LinkStatus now = link_->status();
      nava_modem::LinkStatus before;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (now.device_faults != status_.device_faults) down_since_ = ros::WallTime::now();
        before = std::move(status_);
        status_ = now;
      }
      Report(before, now);
    }
  } catch (const std::exception& e) {
    ROS_FATAL("nava_modem: %s", e.what());
    std::fprintf(stderr, "nava_modem: %s\n", e.what());
    ros::requestShutdown();
  }
}

void NavaModemRos::Report(const nava_modem::LinkStatus& before, const nava_modem::LinkStatus& now) {
  const auto n = [](std::uint64_t v) { return static_cast<unsigned long>(v); };
  const char* device = options_.alsa.device.c_str();
  const nava_modem::ReopenOptions& r = options_.link.reopen;
  if (now.packets_cut != before.packets_cut || now.overruns != before.overruns) {
    // Said as it happens: a garbled packet on the air is then explained in the log.
    ROS_WARN_THROTTLE(1.0, "nava_modem: %s (capture overruns %lu, playback underruns %lu, packets cut %lu so far)",
                      now.packets_cut != before.packets_cut ? "playback underrun while sending: the packet went out with a gap"
                                                            : "capture overrun: audio was lost, a packet being heard may be lost",
                      n(now.overruns), n(now.underruns), n(now.packets_cut));
  }
  if (now.device_faults != before.device_faults) {
    ROS_ERROR("nava_modem: ALSA device '%s' failed: %s; %lu packets not played whole go back to the queue; reopening in "
              "%.2f s, the wait doubling up to %.1f s (device faults %lu so far)",
              device, now.device_error.c_str(), n(now.requeued - before.requeued), r.first_wait, r.max_wait, n(now.device_faults));
  }
  if (now.reopens != before.reopens || (now.device_down && now.failed_reopens != before.failed_reopens)) {
    ros::WallTime down_since;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      down_since = down_since_;
    }
    const double down_for = (ros::WallTime::now() - down_since).toSec();
    if (now.reopens != before.reopens) {
      ROS_WARN("nava_modem: ALSA device '%s' reopened after %.1f s (%d tries failed); sending again after %.1f s", device,
               down_for, now.failed_reopens, r.settle_time);
    } else {
      ROS_WARN_THROTTLE(10.0, "nava_modem: ALSA device '%s' still down after %.1f s (%d tries): %s", device, down_for,
                        now.failed_reopens, now.device_error.c_str());
    }
  }
  if (now.catch_ups != before.catch_ups) {
    ROS_WARN_THROTTLE(1.0, "nava_modem: capture fell more than %.2f s behind (a stalled process?): catching up without "
                      "playing silence, no send meanwhile (%lu catch-ups so far)",
                      options_.link.max_capture_lag, n(now.catch_ups));
  }
}

// The sender's clock as the receiver measured it, for ranging until the timings themselves tell
// it: the room profile's chirps measure it to some 30 ppm; nava's bit clock only to 0.1 %, worse
// than taking the sound cards as equal (they are within a few hundred ppm).
double NavaModemRos::RangingRateError(const nava_modem::RxEvent& e) const {
  return options_.link.profile == nava_modem::Profile::kRoom ? e.rate_error : 0.0;
}

void NavaModemRos::Publish(const nava_modem::RxEvent& e, double ago) {
  const ros::Time stamp = ros::Time::now() - ros::Duration(std::max(0.0, ago));
  multirobot_audio::AudioReception msg = ToAudioReception(e, options_.frame_id, stamp);
  if (ranging_ && e.kind == nava_modem::RxEvent::Kind::kPacket) {
    const RangingRos::Known known =
        ranging_->Heard(e.data, e.arrival, RangingRateError(e), e.direction, e.direction_confidence, ClockEpoch(), link_->time(),
                        ros::Time::now() - ros::Duration(std::isfinite(e.arrival) ? std::max(0.0, link_->time() - e.arrival) : ago));
    if (known.range) {
      msg.path_length = static_cast<float>(known.range->range);
      msg.path_length_std = static_cast<float>(known.range->range_std);
    }
  }
  rx_pub_.publish(msg);
  if (std::isfinite(e.direction)) {
    direction_pub_.publish(ToDirectionMarker(e.direction, e.direction_confidence, e.kind == nava_modem::RxEvent::Kind::kPacket,
                                             options_.frame_id, stamp, direction_id_++ % 100));
  }
}

void NavaModemRos::Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  const nava_modem::LinkStatus& s = status_;
  if (s.overruns > 0 || s.packets_cut > 0 || s.queue_drops > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "running; audio lost, packets cut or dropped");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
  }
  status.add("profile", nava_modem::ProfileName(options_.link.profile));
  status.add("state", nava_modem::MacStateName(s.state));
  status.add("carrier threshold (dB)", s.threshold_db);
  status.add("level (dB)", s.level_db);
  status.add("packets out", s.sent);
  status.add("packets in", s.heard.packets);
  status.add("packets repaired", s.heard.repaired);
  status.add("noise zero_byte", s.heard.zero_byte);
  status.add("noise one_byte", s.heard.one_byte);
  status.add("noise bad_crc", s.heard.bad_crc);
  status.add("capture overruns", s.overruns);
  status.add("playback underruns", s.underruns);
  status.add("packets cut by underruns", s.packets_cut);
  status.add("queue drops", s.queue_drops);
  DiagnoseDevice(status);
}

// Called with mutex_ held. A device that is down is an error (nothing is heard or sent), one
// that failed and came back a warning.
void NavaModemRos::DiagnoseDevice(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const nava_modem::LinkStatus& s = status_;
  if (s.device_down) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR,
                   "audio device down for " + std::to_string(static_cast<int>((ros::WallTime::now() - down_since_).toSec())) +
                       " s, reopening: " + s.device_error);
  } else if (s.device_faults > 0 && status.level == diagnostic_msgs::DiagnosticStatus::OK) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "running; the audio device failed and was reopened");
  }
  status.add("device", s.device_down ? "down, reopening" : "open");
  status.add("device faults", s.device_faults);
  status.add("device reopens", s.reopens);
  status.add("failed reopen tries", s.failed_reopens);
  status.add("packets re-queued after device faults", s.requeued);
  status.add("capture catch-ups", s.catch_ups);
  if (!s.device_error.empty()) status.add("last device error", s.device_error);
}

}  // namespace multirobot_audio
