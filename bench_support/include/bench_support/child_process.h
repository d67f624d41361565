#pragma once

// Running a program as a child process, as the benches run the decoders and make_speech.sh.
#include <string>
#include <vector>

namespace bench_support {

struct RunResult {
  std::string out;    // what it printed on standard output
  double cpu_s = 0.0;  // its own CPU time, user and system
  int status = -1;     // its exit status; -1 when it could not start or did not exit
};

// Runs argv[0] (looked up on PATH) with standard error to /dev/null, capturing its output.
RunResult Run(const std::vector<std::string>& argv);

// CPU seconds this process has used, all threads.
double CpuNow();

}  // namespace bench_support
