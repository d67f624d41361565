// Every command-line tool's argument parser. Byte 0 picks the tool (mod the count, in the order
// of kParsers); the rest is its words, separated by NUL bytes, as argv would hold them. A parser
// may only return options, refuse with UsageError or answer -h with HelpRequested: any other
// exception, an exit or a sanitizer report is a finding.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "audio_propagation_args.h"
#include "charging_experiment_args.h"
#include "decode_table_bench_args.h"
#include "local_mutex_sim_args.h"
#include "nava_bench_args.h"
#include "nava_decode_args.h"
#include "nava_encode_args.h"
#include "nava_room_args.h"
#include "sounds_good_experiment_args.h"
#include "tool_args/usage_error.h"
#include "world_sim_bench_args.h"

namespace {

using Words = std::vector<std::string>;

const std::vector<std::function<void(const Words&)>> kParsers = {
    [](const Words& w) { nava_modem::tools::ParseNavaEncodeArgs(w); },              // 0
    [](const Words& w) { nava_modem::tools::ParseNavaDecodeArgs(w); },              // 1
    [](const Words& w) { nava_modem::tools::ParseNavaRoomArgs(w); },                // 2
    [](const Words& w) { nava_modem::tools::ParseNavaBenchArgs(w); },               // 3
    [](const Words& w) { audio_propagation::tools::ParseQueryArgs(w); },            // 4
    [](const Words& w) { audio_propagation::tools::ParseBenchArgs(w); },            // 5
    [](const Words& w) { audio_propagation::tools::ParseSceneRenderArgs(w); },      // 6
    [](const Words& w) { audio_propagation::tools::ParseValidateArgs(w); },         // 7
    [](const Words& w) { local_mutex::tools::ParseSimArgs(w); },                    // 8
    [](const Words& w) { sounds_good_explorer::tools::ParseExperimentArgs(w); },    // 9
    [](const Words& w) { charging_demo::tools::ParseExperimentArgs(w); },           // 10
    [](const Words& w) { world_sim::tools::ParseWorldSimBenchArgs(w); },            // 11
    [](const Words& w) { audio_propagation::tools::ParseDecodeTableBenchArgs(w); },  // 12
    [](const Words& w) { audio_propagation::tools::ParseRangingBenchArgs(w); },     // 13
    [](const Words& w) { audio_propagation::tools::ParsePredictArgs(w); },          // 14
    [](const Words& w) { audio_propagation::tools::ParseSurveyArgs(w); },           // 15
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto& parse = kParsers[data[0] % kParsers.size()];
  Words words;
  if (size > 1) {
    words.emplace_back();
    for (std::size_t k = 1; k < size; ++k) {
      if (data[k] == 0) {
        words.emplace_back();
      } else {
        words.back() += static_cast<char>(data[k]);
      }
    }
  }
  try {
    parse(words);
  } catch (const multirobot_audio::tools::UsageError&) {
  } catch (const multirobot_audio::tools::HelpRequested&) {
  }
  return 0;
}
