// nava_bench: how many packets nava_decode and minimodem each decode from the same noisy files.
//
//   nava_bench [--packets 60] [--seed 1] [--snr-min -12] [--snr-max 0] [--dir DIR]
//              [--minimodem minimodem|none] [modem options]
//
// Writes a WAV of N random packets for every full-band SNR (tone power over white-noise power
// across the whole band) from --snr-max down to --snr-min in 1 dB steps, decodes each file
// with nava_decode (beside this program) and with minimodem, as child processes, and prints a
// table: packets each decoded correctly, packets decoded wrong, and each decoder's CPU time.
// Ends with the speed of each decoder (seconds of audio per CPU second) and the targets.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spawn.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

#include "modem_args.h"
#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/wav_file.h"

extern char** environ;

namespace {

struct RunResult {
  std::string out;
  double cpu_s = 0.0;
  int status = -1;
};

// Runs a program, capturing its standard output; CPU time from the child's own usage.
RunResult Run(const std::vector<std::string>& argv) {
  RunResult r;
  int pipe_fd[2];
  if (pipe(pipe_fd) != 0) return r;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], 1);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fd[1]);
  if (spawned != 0) {
    close(pipe_fd[0]);
    return r;
  }
  char buffer[65536];
  ssize_t got;
  while ((got = read(pipe_fd[0], buffer, sizeof buffer)) > 0) r.out.append(buffer, static_cast<std::size_t>(got));
  close(pipe_fd[0]);
  struct rusage usage {};
  int status = 0;
  wait4(pid, &status, 0, &usage);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.cpu_s = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6 + usage.ru_stime.tv_sec + usage.ru_stime.tv_usec * 1e-6;
  return r;
}

struct Count {
  int right = 0, wrong = 0;
};

// Counts each sent packet at most once.
Count Score(const std::vector<std::string>& decoded_hex, const std::vector<std::string>& sent_hex) {
  std::map<std::string, int> left;
  for (const std::string& s : sent_hex) ++left[s];
  Count c;
  for (const std::string& d : decoded_hex) {
    auto it = left.find(d);
    if (it != left.end() && it->second > 0) {
      --it->second;
      ++c.right;
    } else if (it == left.end()) {
      ++c.wrong;
    }
  }
  return c;
}

std::vector<std::string> NavaPackets(const std::string& json_lines) {
  std::vector<std::string> out;
  std::istringstream in(json_lines);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("\"kind\": \"packet\"") == std::string::npos) continue;
    const auto at = line.find("\"data\": \"");
    if (at != std::string::npos) out.push_back(line.substr(at + 9, 8));
  }
  return out;
}

// minimodem prints the bytes it decodes; our packets are the runs of 7 that frame correctly.
std::vector<std::string> MinimodemPackets(const std::string& bytes, nava_modem::CrcVariant crc) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i + nava_modem::kFrameBytes <= bytes.size(); ++i) {
    nava_modem::Frame f;
    for (int k = 0; k < nava_modem::kFrameBytes; ++k) f[k] = static_cast<std::uint8_t>(bytes[i + k]);
    if (f[0] != nava_modem::kHeader || !nava_modem::CrcMatches(f, crc)) continue;
    out.push_back(nava_modem::tools::HexBytes({f[1], f[2], f[3], f[4]}));
    i += nava_modem::kFrameBytes - 1;
  }
  return out;
}

std::string SelfDir() {
  char path[4096];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return ".";
  const std::string p(path, static_cast<std::size_t>(n));
  return p.substr(0, p.rfind('/'));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nava_modem;
  const std::string usage = std::string("nava_bench [--packets 60] [--seed 1] [--snr-min -12] [--snr-max 0] [--dir DIR] "
                                        "[--minimodem minimodem|none] ") + tools::kModemUsage;
  const multirobot_audio::tools::ToolArgs args("nava_bench", usage, argc, argv);
  const int packets = static_cast<int>(args.Int("--packets", 60, 1, 100000));
  const unsigned seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  const int snr_min = static_cast<int>(args.Int("--snr-min", -12, -60, 60));
  const int snr_max = static_cast<int>(args.Int("--snr-max", 0, -60, 60));
  std::string dir = args.String("--dir", "");
  const std::string minimodem = args.String("--minimodem", "minimodem");
  const ModemOptions options = tools::ModemArgs(args);
  args.CheckAllUsed();
  if (snr_min > snr_max) args.Fail("--snr-min must not be above --snr-max");
  if (dir.empty()) {
    char tmpl[] = "/tmp/nava_bench.XXXXXX";
    if (!mkdtemp(tmpl)) args.Fail("cannot make a folder in /tmp");
    dir = tmpl;
  }

  // The clean signal: packets of random data with gaps, tone power amplitude^2 / 2.
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  const FskModulator modulator(options);
  const std::size_t gap = static_cast<std::size_t>(0.3 * options.sample_rate);
  std::vector<float> clean(gap, 0.0f);
  std::vector<std::string> sent;
  for (int p = 0; p < packets; ++p) {
    std::vector<std::uint8_t> data(kDataBytes);
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    sent.push_back(tools::HexBytes(data));
    const std::vector<float> burst = modulator.ModulatePacket(data);
    clean.insert(clean.end(), burst.begin(), burst.end());
    clean.insert(clean.end(), gap, 0.0f);
  }
  const double seconds = clean.size() / options.sample_rate;
  const double tone_power = options.amplitude * options.amplitude / 2.0;

  const std::vector<std::string> flags = {"--mark", std::to_string(options.mark_hz), "--space", std::to_string(options.space_hz),
                                          "--baud", std::to_string(options.baud), "--crc", CrcVariantName(options.crc)};
  const std::string decoder = SelfDir() + "/nava_decode";
  const bool with_minimodem = minimodem != "none";
  std::printf("nava_bench: %d packets, %.0f s of audio per file at %.0f Hz, files in %s\n", packets, seconds,
              options.sample_rate, dir.c_str());
  std::printf("%8s %10s %10s %10s %10s %10s %10s\n", "snr_db", "nava", "nava_bad", "nava_cpu_s", "minimodem",
              "mm_bad", "mm_cpu_s");
  std::normal_distribution<double> gauss(0.0, 1.0);
  double nava_cpu = 0.0, mm_cpu = 0.0;
  int files = 0;
  std::map<int, Count> nava_at, mm_at;
  for (int snr = snr_max; snr >= snr_min; --snr) {
    const double sigma = std::sqrt(tone_power / std::pow(10.0, snr / 10.0));
    // Scale the mix so that the noise stays clear of full scale in a 16-bit file.
    const double scale = 0.9 / (4.0 * std::max(sigma, options.amplitude));
    std::vector<float> noisy(clean.size());
    for (std::size_t k = 0; k < clean.size(); ++k) noisy[k] = static_cast<float>(scale * (clean[k] + sigma * gauss(rng)));
    const std::string file = dir + "/snr_" + std::to_string(snr) + ".wav";
    WriteWavFile(file, noisy, options.sample_rate);
    ++files;

    std::vector<std::string> nava_argv = {decoder};
    nava_argv.insert(nava_argv.end(), flags.begin(), flags.end());
    nava_argv.push_back(file);
    const RunResult nava = Run(nava_argv);
    if (nava.status != 0) {
      std::cerr << "nava_bench: " << decoder << " failed on " << file << "\n";
      return 1;
    }
    const Count n = Score(NavaPackets(nava.out), sent);
    nava_at[snr] = n;
    nava_cpu += nava.cpu_s;
    Count m;
    double m_cpu = 0.0;
    if (with_minimodem) {
      const RunResult mm = Run({minimodem, "--rx", "-q", "-f", file, "--mark", std::to_string(options.mark_hz), "--space",
                                std::to_string(options.space_hz), std::to_string(options.baud)});
      if (mm.status < 0) {
        std::cerr << "nava_bench: could not run " << minimodem << " (use --minimodem none to skip it)\n";
        return 1;
      }
      m = Score(MinimodemPackets(mm.out, options.crc), sent);
      m_cpu = mm.cpu_s;
      mm_cpu += mm.cpu_s;
      mm_at[snr] = m;
    }
    std::printf("%8d %10d %10d %10.3f %10d %10d %10.3f\n", snr, n.right, n.wrong, nava.cpu_s, m.right, m.wrong, m_cpu);
    std::fflush(stdout);
  }
  const double audio_total = seconds * files;
  std::printf("speed: nava_decode %.0fx real time", audio_total / std::max(nava_cpu, 1e-9));
  if (with_minimodem) std::printf(", minimodem %.0fx real time", audio_total / std::max(mm_cpu, 1e-9));
  std::printf(" (seconds of audio per CPU second)\n");
  auto share = [&](int snr) { return nava_at.count(snr) ? 100.0 * nava_at[snr].right / packets : -1.0; };
  bool never_worse = true;
  for (const auto& [snr, m] : mm_at) never_worse = never_worse && nava_at[snr].right >= m.right;
  std::printf("targets: -9 dB %.0f%% (>= 90), -10 dB %.0f%% (>= 50), never fewer than minimodem: %s, speed >= 500x: %s\n",
              share(-9), share(-10), with_minimodem ? (never_worse ? "yes" : "NO") : "not run",
              audio_total / std::max(nava_cpu, 1e-9) >= 500.0 ? "yes" : "NO");
  return 0;
}
