#include "bench_support/speech.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "bench_support/child_process.h"
#include "package_data/package_data.h"

namespace bench_support {

std::string MakeSpeech(const std::string& dir, unsigned seed) {
  const std::string file = dir + "/speech.wav";
  std::string script = "make_speech.sh";
  try {
    script = package_data::DataFile("make_speech.sh");
  } catch (const package_data::PackageDataError& e) {
    std::cerr << e.what() << "\n";
    std::exit(1);
  }
  const RunResult r = Run({"bash", script, file, "240", std::to_string(seed)});
  if (r.status != 0) {
    std::cerr << script << " could not make speech (are espeak-ng and sox installed?)\n";
    std::exit(1);
  }
  return file;
}

std::vector<float> SpeechFrom(const std::vector<float>& speech, std::size_t shift) {
  shift %= speech.size();
  std::vector<float> talk(speech.begin() + static_cast<std::ptrdiff_t>(shift), speech.end());
  talk.insert(talk.end(), speech.begin(), speech.begin() + static_cast<std::ptrdiff_t>(shift));
  return talk;
}

std::string TempDir(const multirobot_audio::tools::ToolUsage& usage, const std::string& dir) {
  if (!dir.empty()) {
    // Made when missing, so that the speech and the files written into it have a place.
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error || !std::filesystem::is_directory(dir)) usage.Fail("--dir " + dir + ": expected a folder that exists or can be made");
    return dir;
  }
  char tmpl[] = "/tmp/nava_bench.XXXXXX";
  if (!mkdtemp(tmpl)) usage.Fail("cannot make a folder in /tmp");
  return tmpl;
}

}  // namespace bench_support
