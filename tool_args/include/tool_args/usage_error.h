#pragma once

// How a command-line tool refuses its command line without leaving the process: the parsers
// throw, and only the tool's main turns that into output and an exit status. So a parser can be
// called by a test or a fuzzer, which would stop at an exit().
#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace multirobot_audio::tools {

// A command line (or a file it names) that the tool refuses. RunTool prints Message() on stderr
// and exits 1. Deliberately not a std::exception: the tools report run-time failures from their
// own `catch (const std::exception&)` blocks in their own words, and a usage error must pass
// those unchanged on its way to main.
class UsageError {
 public:
  // With no `usage`, the message is the problem alone (errors that are about a file, not the
  // command line's shape).
  UsageError(std::string program, std::string problem, std::string usage = "")
      : program_(std::move(program)), problem_(std::move(problem)), usage_(std::move(usage)) {}

  const std::string& problem() const { return problem_; }
  // "PROGRAM: PROBLEM" and, when there is a usage, "usage: USAGE" on a second line.
  std::string Message() const { return program_ + ": " + problem_ + (usage_.empty() ? "" : "\nusage: " + usage_); }

 private:
  std::string program_, problem_, usage_;
};

// -h or --help: RunTool prints the usage on stdout and exits 0.
class HelpRequested {
 public:
  explicit HelpRequested(std::string usage) : usage_(std::move(usage)) {}
  const std::string& usage() const { return usage_; }

 private:
  std::string usage_;
};

// A tool's name and usage, to refuse its command line in the parser's words after parsing
// (when a file it names turns out not to fit it).
struct ToolUsage {
  std::string program, usage;
  [[noreturn]] void Fail(const std::string& problem) const { throw UsageError(program, problem, usage); }
};

// The words of a command line, without the program's name.
inline std::vector<std::string> Words(int argc, char** argv) { return std::vector<std::string>(argv + 1, argv + argc); }

// Runs a tool's main body (a callable returning the exit status), turning a UsageError into its
// message on stderr and status 1, HelpRequested into the usage on stdout and status 0, and any
// other error the body lets through (say, no share folder to take a default map from) into its
// message and status 1 rather than an abort.
template <typename Body>
int RunTool(Body&& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    std::cerr << e.Message() << "\n";
    return 1;
  } catch (const HelpRequested& help) {
    std::cout << "usage: " << help.usage() << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}

}  // namespace multirobot_audio::tools
