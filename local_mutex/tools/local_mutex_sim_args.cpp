#include "local_mutex_sim_args.h"

#include <string>

namespace local_mutex::tools {
namespace {

using multirobot_audio::tools::BatchRun;
using multirobot_audio::tools::ToolArgs;

const std::string kUsage =
    std::string("local_mutex_sim --scenario single|three [--timeline out.png] | --trials N [--robots 2..6] [--noise P] "
    "[--loss Q] | --sweep N | --bound N [--robots 2..8] [--rho 0.001]; timers --grab --request --request-sd --lock "
    "--lock-sd; trials --radius --want-spread --hold-min --hold-max --cycles --liveness-bound; --seed S; channel ") +
    audio_propagation::tools::kExperimentChannelUsage + "; --shard K/N --out DIR | --merge DIR...";

void ParseRange(const ToolArgs& args, const std::string& text, int& lo, int& hi) {
  const auto dots = text.find("..");
  try {
    if (dots == std::string::npos) {
      lo = hi = std::stoi(text);
    } else {
      lo = std::stoi(text.substr(0, dots));
      hi = std::stoi(text.substr(dots + 2));
    }
  } catch (const std::exception&) {
    args.Fail("--robots: expected a count or a range like 2..8, got " + text);
  }
  if (lo < 1 || hi < lo || hi > 64) args.Fail("--robots: expected 1 <= min <= max <= 64, got " + text);
}

}  // namespace

SimRequest ParseSimRequest(const ToolArgs& args, const BatchRun& batch) {
  SimRequest r;
  r.scenario = args.String("--scenario", "");
  r.timeline = args.String("--timeline", "");
  r.out = args.String("--out", "");
  r.trial_count = static_cast<int>(args.Int("--trials", 0, 0, 100000000));
  r.sweep = static_cast<int>(args.Int("--sweep", 0, 0, 100000000));
  r.bound = static_cast<int>(args.Int("--bound", 0, 0, 100000000));
  r.rho = args.Double("--rho", r.rho, 1e-300, 1.0);
  TeamSimOptions& options = r.options;
  options.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  options.noise = args.Double("--noise", 0.0, 0.0, 1.0);
  options.loss = args.Double("--loss", 0.0, 0.0, 1.0);
  MutexOptions& m = options.mutex;
  m.grab_time = args.Double("--grab", m.grab_time, 1e-3, 1e6);
  m.request_mean = args.Double("--request", m.request_mean, 1e-3, 1e6);
  m.request_sd = args.Double("--request-sd", m.request_sd, 0.0, 1e6);
  m.lock_mean = args.Double("--lock", m.lock_mean, 1e-3, 1e6);
  m.lock_sd = args.Double("--lock-sd", m.lock_sd, 0.0, 1e6);
  TrialOptions& trials = r.trials;
  // The bound's cells are team sizes, r robots in earshot: 2..8 as the thesis's trials.
  ParseRange(args, args.String("--robots", r.bound > 0 ? "2..8" : "2..6"), trials.min_robots, trials.max_robots);
  trials.radius = args.Double("--radius", trials.radius, 0.0, 9.0);
  trials.want_spread = args.Double("--want-spread", trials.want_spread, 0.0, 1e6);
  trials.hold_min = args.Double("--hold-min", trials.hold_min, 0.0, 1e6);
  trials.hold_max = args.Double("--hold-max", trials.hold_max, trials.hold_min, 1e6);
  trials.cycles = static_cast<int>(args.Int("--cycles", trials.cycles, 1, 1000));
  trials.liveness_bound = args.Double("--liveness-bound", 0.0, 0.0, 1e9);
  r.channel = audio_propagation::tools::ParseExperimentChannel(args, options.channel);
  args.CheckAllUsed();
  if ((r.scenario.empty() ? 0 : 1) + (r.trial_count > 0) + (r.sweep > 0) + (r.bound > 0) != 1) {
    args.Fail("give exactly one of --scenario, --trials N, --sweep N, --bound N");
  }
  if (!(r.rho < 1.0)) args.Fail("--rho: expected a failure rate in (0, 1), got " + std::to_string(r.rho));
  if (r.bound > 0 && trials.min_robots < 2) args.Fail("--bound: a team needs at least 2 robots to lose a request, got --robots " + std::to_string(trials.min_robots) + "..");
  if (batch.sharded() && !r.scenario.empty()) args.Fail("--shard: for --trials N, --sweep N and --bound N, not --scenario");
  if (batch.sharded() && r.out.empty()) args.Fail("--shard: give --out DIR for the shard's files");
  if (!batch.sharded() && !r.out.empty()) args.Fail("--out: for --shard only (the report is printed)");
  if (batch.sharded() && !r.timeline.empty()) args.Fail("--timeline draws one trial: give it without --shard");
  return r;
}

SimCommand ParseSimArgs(const std::vector<std::string>& words) {
  const ToolArgs args("local_mutex_sim", kUsage, words, {"--merge", audio_propagation::tools::kLinkFateSwitch});
  return multirobot_audio::tools::ParseBatchCommand<SimRequest>(args, {"--out"}, ParseSimRequest);
}

}  // namespace local_mutex::tools
