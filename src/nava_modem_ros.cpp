#include "nava_modem_ros.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>

#include "conversions.h"
#include "input_checks.h"
#include "nava_modem/frame.h"
#include "params.h"

namespace multirobot_audio {

NavaModemOptions ReadNavaModemOptions(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  NavaModemOptions o;
  o.alsa.device = StringParam(pnh, "device", o.alsa.device);
  o.alsa.sample_rate = NumberParam(pnh, "sample_rate", o.alsa.sample_rate);
  CheckOptionParams(pnh, {"sample_rate"}, [&] { nava_modem::ValidateSampleRate("sample rate", o.alsa.sample_rate); });
  o.alsa.latency = NumberParam(pnh, "latency", o.alsa.latency);
  o.alsa.capture_channels = IntParam(pnh, "channels", 1);
  CheckOptionParams(pnh, {"device", "latency", "channels"}, [&] { nava_modem::ValidateAlsaOptions(o.alsa); });
  if (pnh.hasParam("mic_positions")) {
    std::vector<double> xy;
    if (!pnh.getParam("mic_positions", xy)) {
      throw ParamError(pnh.resolveName("mic_positions") + ": expected a list of numbers x1, y1, x2, y2, ... (m)");
    }
    if (xy.size() != 2u * static_cast<std::size_t>(o.alsa.capture_channels)) {
      throw ParamError(pnh.resolveName("mic_positions") + ": " + std::to_string(xy.size()) +
                       " numbers, expected 2 x ~channels = " + std::to_string(2 * o.alsa.capture_channels) +
                       " (x, y in m of each microphone, in channel order)");
    }
    std::string text;
    for (double v : xy) text += (text.empty() ? "" : ",") + std::to_string(v);
    try {
      o.link.microphones = nava_modem::ParseMicPositions(text);
    } catch (const std::invalid_argument& e) {
      throw ParamError(pnh.resolveName("mic_positions") + ": " + e.what());
    }
  } else if (o.alsa.capture_channels > 1) {
    throw ParamError(pnh.resolveName("mic_positions") + ": required with ~channels " +
                     std::to_string(o.alsa.capture_channels) + " (x, y in m of each microphone, in channel order)");
  }
  o.frame_id = StringParam(pnh, "frame_id", o.frame_id);
  o.carrier_rate = NumberParam(pnh, "carrier_rate", o.carrier_rate, 0.1, 1000.0);

  const std::string profile = StringParam(pnh, "profile", "nava");
  const auto parsed_profile = nava_modem::ParseProfile(profile);
  if (!parsed_profile) {
    throw ParamError(pnh.resolveName("profile") + ": expected " + nava_modem::kProfileNames + ", got '" + profile + "'");
  }
  o.link.profile = *parsed_profile;
  nava_modem::ModemOptions& m = o.link.modem;
  m.sample_rate = o.alsa.sample_rate;
  m.mark_hz = NumberParam(pnh, "mark", m.mark_hz, 1.0, 1e6);
  m.space_hz = NumberParam(pnh, "space", m.space_hz, 1.0, 1e6);
  m.baud = NumberParam(pnh, "baud", m.baud, 1.0, 1e6);
  m.amplitude = NumberParam(pnh, "amplitude", m.amplitude);
  const std::string crc = StringParam(pnh, "crc", "ccitt-false");
  const auto variant = nava_modem::ParseCrcVariant(crc);
  if (!variant) throw ParamError(pnh.resolveName("crc") + ": expected ccitt-false or xmodem, got '" + crc + "'");
  m.crc = *variant;

  nava_modem::MacOptions& mac = o.link.mac;
  mac.calibration_time = NumberParam(pnh, "calibration_time", mac.calibration_time, 0.0, 3600.0);
  if (pnh.hasParam("threshold_db")) mac.fixed_threshold_db = NumberParam(pnh, "threshold_db", 0.0, -200.0, 20.0);
  mac.threshold_margin_db = NumberParam(pnh, "threshold_margin_db", mac.threshold_margin_db, 0.0, 100.0);
  mac.backoff_min_bits = NumberParam(pnh, "backoff_min_bits", mac.backoff_min_bits, 0.0, 1e6);
  mac.backoff_max_bits = NumberParam(pnh, "backoff_max_bits", mac.backoff_max_bits, 0.0, 1e6);
  mac.deaf_time = NumberParam(pnh, "deaf_time", mac.deaf_time, 0.0, 60.0);
  mac.queue_capacity = static_cast<std::size_t>(IntParam(pnh, "queue_size", static_cast<int>(mac.queue_capacity), 1, 100000));
  nava_modem::UseProfileTiming(o.link.profile, m, mac);

  nava_modem::ReceiverOptions& rx = o.link.receiver;
  rx.max_fixed_bits = IntParam(pnh, "max_fixed_bits", rx.max_fixed_bits);
  rx.detect_threshold = NumberParam(pnh, "detect_threshold", rx.detect_threshold);
  CheckOptionParams(pnh, {"max_fixed_bits", "detect_threshold"}, [&] { nava_modem::ValidateReceiverOptions(rx); });
  o.link.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", 1, 0, 2147483647));
  o.link.max_capture_lag = NumberParam(pnh, "max_capture_lag", o.link.max_capture_lag, 0.001, 10.0);
  // Its own sound comes back through both of the device's buffers and the sound server's.
  o.link.max_loop = NumberParam(pnh, "max_loop", std::max(o.link.max_loop, 4.0 * o.alsa.latency + 0.2), 0.01, 10.0);
  o.ranging_on = BoolParam(pnh, "ranging", true);
  rx.time_arrivals = o.ranging_on;
  o.ranging = ReadRangingRosOptions(nh, pnh);
  nava_modem::ReopenOptions& reopen = o.link.reopen;
  reopen.first_wait = NumberParam(pnh, "reopen_backoff_min", reopen.first_wait, 0.001, 60.0);
  reopen.max_wait = NumberParam(pnh, "reopen_backoff_max", reopen.max_wait, reopen.first_wait, 600.0);
  reopen.settle_time = NumberParam(pnh, "reopen_settle_time", reopen.settle_time, 0.0, 60.0);
  CheckOptionParams(pnh, {"mark", "space", "amplitude"}, [&] {
    nava_modem::ValidateModemOptions(m);
    nava_modem::MakeProfile(o.link.profile, m);  // refuses a rate the profile's band does not fit
  });
  try {
    nava_modem::ValidateMacOptions(mac);
    nava_modem::ValidateReopenOptions(reopen);
  } catch (const std::invalid_argument& e) {
    throw ParamError(e.what());
  }
  return o;
}

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
      [](const multirobot_audio::AudioPacket& m) { return PacketProblem(m, nava_modem::kDataBytes); },
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
  const Counts& c = counts_;
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("nava_modem summary: sent %lu, heard %lu packets (%lu repaired) and noise %lu zero_byte, %lu one_byte, "
              "%lu bad_crc; queue drops %lu; capture overruns %lu, playback underruns %lu, "
              "packets cut %lu",
              static_cast<unsigned long>(c.sent), static_cast<unsigned long>(c.packets),
              static_cast<unsigned long>(c.repaired), static_cast<unsigned long>(c.zero_byte),
              static_cast<unsigned long>(c.one_byte), static_cast<unsigned long>(c.bad_crc),
              static_cast<unsigned long>(c.queue_drops), static_cast<unsigned long>(c.overruns),
              static_cast<unsigned long>(c.underruns), static_cast<unsigned long>(c.packets_cut));
  std::printf("; capture catch-ups %lu; device faults %lu, reopens %lu, packets re-queued %lu%s; %s\n",
              static_cast<unsigned long>(health_.catch_ups), static_cast<unsigned long>(health_.faults),
              static_cast<unsigned long>(health_.reopens), static_cast<unsigned long>(health_.requeued),
              health_.down ? " (the device is down)" : "", guard_.Summary().c_str());
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
  bool last_carrier = false;
  double last_carrier_sent = -1e9;
  const double carrier_period = 1.0 / options_.carrier_rate;
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
          std::lock_guard<std::mutex> lock(mutex_);
          counts_.queue_drops = link_->mac().dropped();
          ROS_WARN_THROTTLE(5.0, "nava_modem: transmit queue full, packet dropped (%lu dropped so far)",
                            static_cast<unsigned long>(counts_.queue_drops));
        }
      }
      events.clear();
      if (!link_->Tick(events)) break;
      ReportDevice();
      for (const nava_modem::OwnTiming& t : link_->TakeOwnTimings()) {
        if (!ranging_) break;
        const double ago = std::isfinite(t.arrival) ? std::max(0.0, link_->time() - t.arrival) : 0.0;
        ranging_->OwnTiming(t.data, t.arrival, ClockEpoch(), ros::Time::now() - ros::Duration(ago));
      }
      if (ranging_) ranging_->SetClock(link_->time(), link_->card_rate_error());
      for (const nava_modem::RxEvent& e : events) Publish(e, link_->time() - e.end);
      const bool carrier = link_->carrier();
      if (carrier != last_carrier || link_->time() - last_carrier_sent >= carrier_period) {
        multirobot_audio::CarrierSense msg;
        msg.header.stamp = ros::Time::now();
        msg.header.frame_id = options_.frame_id;
        msg.carrier = carrier;
        msg.level_db = static_cast<float>(link_->level_db());
        carrier_pub_.publish(msg);
        last_carrier = carrier;
        last_carrier_sent = link_->time();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      counts_.state = nava_modem::MacStateName(link_->mac().state());
      counts_.threshold_db = link_->mac().threshold_db();
      counts_.level_db = link_->level_db();
      counts_.sent = link_->packets_sent();
      if (link_->packets_cut() != counts_.packets_cut || link_->overruns() != counts_.overruns) {
        // Said as it happens: a garbled packet on the air is then explained in the log.
        ROS_WARN_THROTTLE(1.0, "nava_modem: %s (capture overruns %lu, playback underruns %lu, packets cut %lu so far)",
                          link_->packets_cut() != counts_.packets_cut
                              ? "playback underrun while sending: the packet went out with a gap"
                              : "capture overrun: audio was lost, a packet being heard may be lost",
                          static_cast<unsigned long>(link_->overruns()), static_cast<unsigned long>(link_->underruns()),
                          static_cast<unsigned long>(link_->packets_cut()));
      }
      counts_.overruns = link_->overruns();
      counts_.underruns = link_->underruns();
      counts_.packets_cut = link_->packets_cut();
      counts_.queue_drops = link_->mac().dropped();
      for (const nava_modem::RxEvent& e : events) {
        counts_.packets += e.kind == nava_modem::RxEvent::Kind::kPacket;
        counts_.repaired += e.kind == nava_modem::RxEvent::Kind::kPacket && e.fixed_bits > 0;
        counts_.zero_byte += e.noise == nava_modem::RxEvent::Noise::kZeroByte;
        counts_.one_byte += e.noise == nava_modem::RxEvent::Noise::kOneByte;
        counts_.bad_crc += e.noise == nava_modem::RxEvent::Noise::kBadCrc;
      }
    }
  } catch (const std::exception& e) {
    ROS_FATAL("nava_modem: %s", e.what());
    std::fprintf(stderr, "nava_modem: %s\n", e.what());
    ros::requestShutdown();
  }
}

void NavaModemRos::ReportDevice() {
  std::lock_guard<std::mutex> lock(mutex_);
  DeviceHealth& h = health_;
  const char* device = options_.alsa.device.c_str();
  const nava_modem::ReopenOptions& r = options_.link.reopen;
  if (link_->device_faults() != h.faults) {
    ROS_ERROR("nava_modem: ALSA device '%s' failed: %s; %lu packets not played whole go back to the queue; reopening in "
              "%.2f s, the wait doubling up to %.1f s (device faults %lu so far)",
              device, link_->device_error().c_str(), static_cast<unsigned long>(link_->packets_requeued() - h.requeued),
              r.first_wait, r.max_wait, static_cast<unsigned long>(link_->device_faults()));
    h.down_since = ros::WallTime::now();
  }
  if (link_->reopens() != h.reopens) {
    ROS_WARN("nava_modem: ALSA device '%s' reopened after %.1f s (%d tries failed); sending again after %.1f s",
             device, (ros::WallTime::now() - h.down_since).toSec(), link_->failed_reopens(), r.settle_time);
  } else if (link_->device_down() && link_->failed_reopens() != h.failed_reopens) {
    ROS_WARN_THROTTLE(10.0, "nava_modem: ALSA device '%s' still down after %.1f s (%d tries): %s", device,
                      (ros::WallTime::now() - h.down_since).toSec(), link_->failed_reopens(), link_->device_error().c_str());
  }
  if (link_->catch_ups() != h.catch_ups) {
    ROS_WARN_THROTTLE(1.0, "nava_modem: capture fell more than %.2f s behind (a stalled process?): catching up without "
                      "playing silence, no send meanwhile (%lu catch-ups so far)",
                      options_.link.max_capture_lag, static_cast<unsigned long>(link_->catch_ups()));
  }
  h.catch_ups = link_->catch_ups();
  h.down = link_->device_down();
  h.error = link_->device_error();
  h.faults = link_->device_faults();
  h.reopens = link_->reopens();
  h.requeued = link_->packets_requeued();
  h.failed_reopens = link_->failed_reopens();
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
  const Counts& c = counts_;
  if (c.overruns > 0 || c.packets_cut > 0 || c.queue_drops > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "running; audio lost, packets cut or dropped");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
  }
  status.add("profile", nava_modem::ProfileName(options_.link.profile));
  status.add("state", c.state);
  status.add("carrier threshold (dB)", c.threshold_db);
  status.add("level (dB)", c.level_db);
  status.add("packets out", c.sent);
  status.add("packets in", c.packets);
  status.add("packets repaired", c.repaired);
  status.add("noise zero_byte", c.zero_byte);
  status.add("noise one_byte", c.one_byte);
  status.add("noise bad_crc", c.bad_crc);
  status.add("capture overruns", c.overruns);
  status.add("playback underruns", c.underruns);
  status.add("packets cut by underruns", c.packets_cut);
  status.add("queue drops", c.queue_drops);
  DiagnoseDevice(status);
}

// Called with mutex_ held. A device that is down is an error (nothing is heard or sent), one
// that failed and came back a warning.
void NavaModemRos::DiagnoseDevice(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const DeviceHealth& h = health_;
  if (h.down) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR,
                   "audio device down for " + std::to_string(static_cast<int>((ros::WallTime::now() - h.down_since).toSec())) +
                       " s, reopening: " + h.error);
  } else if (h.faults > 0 && status.level == diagnostic_msgs::DiagnosticStatus::OK) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "running; the audio device failed and was reopened");
  }
  status.add("device", h.down ? "down, reopening" : "open");
  status.add("device faults", h.faults);
  status.add("device reopens", h.reopens);
  status.add("failed reopen tries", h.failed_reopens);
  status.add("packets re-queued after device faults", h.requeued);
  status.add("capture catch-ups", h.catch_ups);
  if (!h.error.empty()) status.add("last device error", h.error);
}

}  // namespace multirobot_audio
