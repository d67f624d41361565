// The nava_modem node's parameters, read component by component: each reader fills one
// ROS-free options struct and has the component's own check judge it, once.
#include <string>
#include <vector>

#include "nava_modem/modem_profile.h"
#include "nava_modem_ros.h"
#include "params.h"

namespace multirobot_audio {
namespace {

nava_modem::AlsaOptions ReadAlsaParams(const ros::NodeHandle& pnh) {
  nava_modem::AlsaOptions o;
  o.device = StringParam(pnh, "device", o.device);
  o.sample_rate = NumberParam(pnh, "sample_rate", o.sample_rate);
  CheckOptionParams(pnh, {"sample_rate"}, [&] { nava_modem::ValidateSampleRate("sample rate", o.sample_rate); });
  o.latency = NumberParam(pnh, "latency", o.latency);
  o.capture_channels = IntParam(pnh, "channels", 1);
  CheckOptionParams(pnh, {"device", "latency", "channels"}, [&] { nava_modem::ValidateAlsaOptions(o); });
  return o;
}

// ~mic_positions: x, y (m) of each capture channel's microphone, required with more than one.
std::vector<nava_modem::Microphone2D> ReadMicrophoneParams(const ros::NodeHandle& pnh, int channels) {
  const std::string where = pnh.resolveName("mic_positions");
  if (!pnh.hasParam("mic_positions")) {
    if (channels > 1) {
      throw ParamError(where + ": required with ~channels " + std::to_string(channels) +
                       " (x, y in m of each microphone, in channel order)");
    }
    return {};
  }
  std::vector<double> xy;
  if (!pnh.getParam("mic_positions", xy)) throw ParamError(where + ": expected a list of numbers x1, y1, x2, y2, ... (m)");
  if (xy.size() != 2u * static_cast<std::size_t>(channels)) {
    throw ParamError(where + ": " + std::to_string(xy.size()) + " numbers, expected 2 x ~channels = " +
                     std::to_string(2 * channels) + " (x, y in m of each microphone, in channel order)");
  }
  std::string text;
  for (double v : xy) text += (text.empty() ? "" : ",") + std::to_string(v);
  try {
    return nava_modem::ParseMicPositions(text);
  } catch (const std::invalid_argument& e) {
    throw ParamError(where + ": " + e.what());
  }
}

nava_modem::Profile ReadProfileParam(const ros::NodeHandle& pnh) {
  const std::string profile = StringParam(pnh, "profile", "nava");
  const auto parsed = nava_modem::ParseProfile(profile);
  if (!parsed) throw ParamError(pnh.resolveName("profile") + ": expected " + nava_modem::kProfileNames + ", got '" + profile + "'");
  return *parsed;
}

nava_modem::ModemOptions ReadModemParams(const ros::NodeHandle& pnh, nava_modem::Profile profile, double sample_rate) {
  nava_modem::ModemOptions m;
  m.sample_rate = sample_rate;
  m.mark_hz = NumberParam(pnh, "mark", m.mark_hz, 1.0, 1e6);
  m.space_hz = NumberParam(pnh, "space", m.space_hz, 1.0, 1e6);
  m.baud = NumberParam(pnh, "baud", m.baud, 1.0, 1e6);
  m.amplitude = NumberParam(pnh, "amplitude", m.amplitude);
  const std::string crc = StringParam(pnh, "crc", "ccitt-false");
  const auto variant = nava_modem::ParseCrcVariant(crc);
  if (!variant) throw ParamError(pnh.resolveName("crc") + ": expected ccitt-false or xmodem, got '" + crc + "'");
  m.crc = *variant;
  CheckOptionParams(pnh, {"mark", "space", "amplitude"}, [&] {
    nava_modem::ValidateModemOptions(m);
    nava_modem::ValidateProfileOptions(profile, m);  // a rate the profile's band does not fit
  });
  return m;
}

nava_modem::MacOptions ReadMacParams(const ros::NodeHandle& pnh, nava_modem::Profile profile, const nava_modem::ModemOptions& m) {
  nava_modem::MacOptions mac;
  mac.calibration_time = NumberParam(pnh, "calibration_time", mac.calibration_time, 0.0, 3600.0);
  if (pnh.hasParam("threshold_db")) mac.fixed_threshold_db = NumberParam(pnh, "threshold_db", 0.0, -200.0, 20.0);
  mac.threshold_margin_db = NumberParam(pnh, "threshold_margin_db", mac.threshold_margin_db, 0.0, 100.0);
  mac.floor_window = NumberParam(pnh, "floor_window", mac.floor_window, 0.0, 3600.0);
  mac.floor_block = NumberParam(pnh, "floor_block", mac.floor_block, 0.01, 3600.0);
  mac.backoff_min_bits = NumberParam(pnh, "backoff_min_bits", mac.backoff_min_bits, 0.0, 1e6);
  mac.backoff_max_bits = NumberParam(pnh, "backoff_max_bits", mac.backoff_max_bits, 0.0, 1e6);
  mac.deaf_time = NumberParam(pnh, "deaf_time", mac.deaf_time, 0.0, 60.0);
  mac.queue_capacity = static_cast<std::size_t>(IntParam(pnh, "queue_size", static_cast<int>(mac.queue_capacity), 1, 100000));
  nava_modem::UseProfileTiming(profile, m, mac);
  CheckOptionParams(pnh, {"floor_window", "floor_block", "backoff_min_bits", "backoff_max_bits", "deaf_time", "queue_size"},
                    [&] { nava_modem::ValidateMacOptions(mac); });
  return mac;
}

nava_modem::ReceiverOptions ReadReceiverParams(const ros::NodeHandle& pnh, bool time_arrivals) {
  nava_modem::ReceiverOptions rx;
  rx.max_fixed_bits = IntParam(pnh, "max_fixed_bits", rx.max_fixed_bits);
  rx.detect_threshold = NumberParam(pnh, "detect_threshold", rx.detect_threshold);
  rx.time_arrivals = time_arrivals;
  CheckOptionParams(pnh, {"max_fixed_bits", "detect_threshold"}, [&] { nava_modem::ValidateReceiverOptions(rx); });
  return rx;
}

nava_modem::ReopenOptions ReadReopenParams(const ros::NodeHandle& pnh) {
  nava_modem::ReopenOptions reopen;
  reopen.first_wait = NumberParam(pnh, "reopen_backoff_min", reopen.first_wait, 0.001, 60.0);
  reopen.max_wait = NumberParam(pnh, "reopen_backoff_max", reopen.max_wait, reopen.first_wait, 600.0);
  reopen.settle_time = NumberParam(pnh, "reopen_settle_time", reopen.settle_time, 0.0, 60.0);
  CheckOptionParams(pnh, {"reopen_backoff_min", "reopen_backoff_max", "reopen_settle_time"},
                    [&] { nava_modem::ValidateReopenOptions(reopen); });
  return reopen;
}

}  // namespace

NavaModemOptions ReadNavaModemOptions(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  NavaModemOptions o;
  o.alsa = ReadAlsaParams(pnh);
  o.link.microphones = ReadMicrophoneParams(pnh, o.alsa.capture_channels);
  o.frame_id = StringParam(pnh, "frame_id", o.frame_id);
  o.carrier_rate = NumberParam(pnh, "carrier_rate", o.carrier_rate, 0.1, 1000.0);
  o.link.profile = ReadProfileParam(pnh);
  o.link.modem = ReadModemParams(pnh, o.link.profile, o.alsa.sample_rate);
  o.link.mac = ReadMacParams(pnh, o.link.profile, o.link.modem);
  // The rate step every frame goes at (nava_encode --list-rates names them).
  o.link.rate = IntParam(pnh, "rate", o.link.rate, 0, nava_modem::ProfileFormat(o.link.profile).rates - 1);
  o.ranging_on = BoolParam(pnh, "ranging", true);
  o.link.receiver = ReadReceiverParams(pnh, o.ranging_on);
  o.link.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", 1, 0, 2147483647));
  o.link.max_capture_lag = NumberParam(pnh, "max_capture_lag", o.link.max_capture_lag, 0.001, 10.0);
  // Its own sound comes back through both of the device's buffers and the sound server's.
  o.link.max_loop = NumberParam(pnh, "max_loop", std::max(o.link.max_loop, 4.0 * o.alsa.latency + 0.2), 0.01, 10.0);
  o.ranging = ReadRangingRosOptions(nh, pnh);
  o.link.reopen = ReadReopenParams(pnh);
  return o;
}

}  // namespace multirobot_audio
