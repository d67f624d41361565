#pragma once

// Speech as an interferer for the benches: made at run time by make_speech.sh (espeak-ng, so
// nothing is downloaded; found in the package's share folder), and a different stretch of it
// for each room or packet.
#include <cstddef>
#include <string>
#include <vector>

#include "tool_args/tool_args.h"

namespace bench_support {

// Makes 240 s of speech with `seed` as DIR/speech.wav (at espeak-ng's own rate; the benches read
// it at theirs with nava_modem::ReadAudioAt) and returns that path; exits with a message naming
// the script when it cannot.
std::string MakeSpeech(const std::string& dir, unsigned seed);

// The speech from sample `shift` (modulo its length) on, wrapping round to its start.
std::vector<float> SpeechFrom(const std::vector<float>& speech, std::size_t shift);

// The folder for a bench's files: `dir` when given (made if missing), else a new one in /tmp
// (refused through `usage`, naming --dir, when it cannot be made).
std::string TempDir(const multirobot_audio::tools::ToolUsage& usage, const std::string& dir);

}  // namespace bench_support
