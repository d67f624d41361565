#pragma once
// Spreading a batch tool's trials over processes or machines, and gathering them back:
//
//   TOOL [options] --shard K/N [--out DIR]   runs trial i (0-based, in the whole run's order)
//       when i mod N = K - 1, with the seed it has in the whole run, and writes into DIR a record
//       per trial (shard_trials.txt) and then the manifest (shard.txt: tool, shard, trial count
//       and the options that say what is run), so a directory with a manifest holds a finished
//       shard.
//   TOOL --merge DIR... [--out DIR]   checks that the shards are of one run and hold every trial
//       once, and the tool makes the whole run's report from their records.
//
// A tool makes its report from records read back (tool_args/record.h) in a whole run too, so the
// merged report is the whole run's to the byte.
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tool_args/tool_args.h"

namespace multirobot_audio::tools {

// Trial i belongs to shard (i mod count) + 1: every shard gets a spread of the run's
// configurations and seeds, and so about the same work.
struct Shard {
  int index = 1;  // 1..count
  int count = 1;
  bool Holds(std::size_t trial) const { return static_cast<int>(trial % count) == index - 1; }
  std::string Name() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// "K/N" with whole numbers 1 <= K <= N; nullopt for anything else.
std::optional<Shard> ParseShard(const std::string& text);

inline constexpr const char* kShardManifest = "shard.txt";
inline constexpr const char* kShardRecords = "shard_trials.txt";

// Shard directories read and checked to be one whole run. Every problem throws
// std::runtime_error with one line naming the directory (or file and line) and what was expected.
class MergedShards {
 public:
  MergedShards(const std::vector<std::string>& dirs, const std::string& tool);

  // The words of the options the shards were run with (flags and values, as on a command line).
  std::vector<std::string> OptionWords() const;
  // Every trial's record in the whole run's order. `trials` is the count the tool makes of the
  // options: a different count (shards of another version of the tool) throws.
  const std::vector<std::string>& Records(std::size_t trials) const;
  // Where trial i's record came from, for errors in it: "DIR/shard_trials.txt: trial i".
  std::string Where(std::size_t trial) const;
  // Copies the files the shards wrote besides their manifests and records (configurations,
  // worlds) into `out`, refusing two different files of one name and an `out` that is a shard.
  void CopyFiles(const std::string& out) const;

  using Option = std::pair<std::string, std::optional<std::string>>;  // flag, value (none: a switch)

 private:
  std::vector<std::string> dirs_;
  std::vector<Option> options_;
  std::vector<std::string> records_;
};

// How a batch tool was asked to run: the whole run, one shard (--shard K/N), or the merge of
// shards (--merge DIR...; --merge is a switch and the directories are the positional arguments).
class BatchRun {
 public:
  // Reads --shard and --merge from `command`, refusing bad ones through command.Fail. `local`
  // names the tool's flags that say where results go or how fast they come (--out, --threads,
  // ...): shards may differ in them, they are left out of the manifest, and they are all that
  // --merge takes besides the directories.
  BatchRun(const ToolArgs& command, std::set<std::string> local);

  // The command it was read from (a copy), to refuse it later in the parser's words.
  const ToolArgs& command() const { return command_; }

  bool merging() const { return !dirs_.empty(); }
  bool sharded() const { return sharded_; }
  const Shard& shard() const { return shard_; }
  const std::vector<std::string>& dirs() const { return dirs_; }

  // The trials of an n-trial run that this process runs, in order: all, or its shard's.
  std::vector<std::size_t> Trials(std::size_t n) const;

  // A shard's files in `dir`: the records of its trials (records[i] for every i it holds; the
  // vector is the whole run's length) and then the manifest. Throws naming the file.
  void WriteShard(const std::string& dir, const std::vector<std::string>& records) const;

  // --merge: the shards read and checked, and the arguments the tool parses as a whole run's:
  // the shards' options with this command's local flags.
  MergedShards Merge() const;
  ToolArgs MergedArgs(const MergedShards& shards) const;

 private:
  ToolArgs command_;  // a copy: a parser returns the BatchRun, not the words it read
  std::set<std::string> local_;
  Shard shard_;
  bool sharded_ = false;
  std::vector<std::string> dirs_;
};

// A batch tool's command: a run (`run`: what the tool parsed for it), or the merge of shards
// (batch.merging(), no run: the merge parses the shards' options with the tool's own parser).
template <class Run>
struct BatchCommand {
  BatchRun batch;
  std::optional<Run> run;
};

// Reads a batch command from `args` (`local` as for BatchRun): `parse(args, batch)` gives the
// run, unless the command is a merge.
template <class Run, class Parse>
BatchCommand<Run> ParseBatchCommand(const ToolArgs& args, std::set<std::string> local, Parse parse) {
  BatchCommand<Run> command{BatchRun(args, std::move(local)), std::nullopt};
  if (!command.batch.merging()) command.run = parse(args, command.batch);
  return command;
}

}  // namespace multirobot_audio::tools
