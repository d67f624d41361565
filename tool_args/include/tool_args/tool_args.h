#pragma once

// Command-line parsing shared by the command-line tools: --flag value pairs and positional
// arguments, with errors that name the flag. Errors throw UsageError and -h/--help throws
// HelpRequested (usage_error.h); the tool's main (RunTool) prints them and exits 1 or 0.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tool_args/usage_error.h"

namespace multirobot_audio::tools {

class ToolArgs {
 public:
  // `switches` are flags that take no value (e.g. --quick); every other flag takes one.
  ToolArgs(const std::string& program, const std::string& usage, int argc, char** argv,
           const std::set<std::string>& switches = {})
      : ToolArgs(program, usage, std::vector<std::string>(argv + 1, argv + argc), switches) {}

  // The same from words given without the program name (e.g. the options a shard was run with).
  ToolArgs(const std::string& program, const std::string& usage, const std::vector<std::string>& words,
           const std::set<std::string>& switches = {})
      : program_(program), usage_(usage), switches_(switches) {
    const int argc = static_cast<int>(words.size());
    for (int i = 0; i < argc; ++i) {
      const std::string flag = words[i];
      if (flag == "-h" || flag == "--help") throw HelpRequested(usage_);
      if (flag.rfind("--", 0) != 0 || flag == "--") {
        positional_.push_back(flag);
        continue;
      }
      if (switches.count(flag)) {
        values_[flag] = "";
        continue;
      }
      if (i + 1 >= argc) Fail(flag + ": expected --flag VALUE");
      values_[flag] = words[++i];
    }
  }

  [[noreturn]] void Fail(const std::string& problem) const { throw UsageError(program_, problem, usage_); }

  std::string String(const std::string& flag, const std::string& fallback) const {
    const auto it = values_.find(flag);
    used_[flag] = true;
    return it == values_.end() ? fallback : it->second;
  }

  // Whether a switch was given.
  bool Switch(const std::string& flag) const {
    used_[flag] = true;
    return values_.count(flag) > 0;
  }

  std::string Required(const std::string& flag) const {
    if (!values_.count(flag)) Fail(flag + " is required");
    return String(flag, "");
  }

  long Int(const std::string& flag, long fallback, long lo, long hi) const {
    const std::string v = String(flag, std::to_string(fallback));
    char* end = nullptr;
    const long x = std::strtol(v.c_str(), &end, 10);
    if (*end || x < lo || x > hi) {
      Fail(flag + ": expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + v);
    }
    return x;
  }

  double Double(const std::string& flag, double fallback, double lo, double hi) const {
    const std::string v = String(flag, "");
    if (v.empty()) return fallback;
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    if (*end || !std::isfinite(x) || x < lo || x > hi) {
      Fail(flag + ": expected a number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + v);
    }
    return x;
  }

  // A comma-separated list of ascending numbers from `lo` to `hi` (`what` names them for the
  // error); empty when the flag is not given.
  std::vector<double> AscendingList(const std::string& flag, double lo, double hi, const std::string& what) const {
    const std::string list = String(flag, "");
    std::vector<double> out;
    if (list.empty()) return out;
    std::size_t at = 0;
    while (at <= list.size()) {
      const std::size_t comma = std::min(list.find(',', at), list.size());
      const std::string item = list.substr(at, comma - at);
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || *end || !std::isfinite(v) || v < lo || v > hi || (!out.empty() && v <= out.back())) {
        Fail(flag + ": expected ascending " + what + " separated by commas, got " + list);
      }
      out.push_back(v);
      at = comma + 1;
    }
    return out;
  }

  // Arguments that are not --flag VALUE pairs, in order.
  const std::vector<std::string>& positional() const {
    positional_read_ = true;
    return positional_;
  }

  // Every flag given, with its value ("" for a switch), whether read or not.
  const std::map<std::string, std::string>& given() const { return values_; }
  const std::set<std::string>& switches() const { return switches_; }
  const std::string& program() const { return program_; }
  const std::string& usage() const { return usage_; }
  ToolUsage tool_usage() const { return {program_, usage_}; }

  // Rejects flags the tool does not know, once all have been read.
  void CheckAllUsed() const {
    for (const auto& [flag, value] : values_) {
      if (!used_.count(flag)) Fail("unknown option " + flag);
    }
    if (!positional_read_ && !positional_.empty()) Fail("unexpected argument " + positional_.front());
  }

 private:
  std::string program_, usage_;
  std::set<std::string> switches_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
  mutable bool positional_read_ = false;
  mutable std::map<std::string, bool> used_;
};

}  // namespace multirobot_audio::tools
