#include "tool_args/shard.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

namespace multirobot_audio::tools {

namespace {

namespace fs = std::filesystem;

std::string Path(const std::string& dir, const char* file) { return (fs::path(dir) / file).string(); }

// A whole number of digits only (no sign, no spaces), below 2^63; nullopt otherwise.
std::optional<unsigned long long> Whole(const std::string& text) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stoull(text);
}

struct Manifest {
  std::string dir, tool;
  Shard shard;
  std::size_t trials = 0;
  std::vector<MergedShards::Option> options;
};

// "--seed 2", "--quick" or "no --seed": how an option shows in an error.
std::string Show(const std::vector<MergedShards::Option>& options, const std::string& flag) {
  for (const auto& [f, value] : options)
    if (f == flag) return value ? f + " " + *value : f;
  return "no " + flag;
}

// The first flag (in order) the two runs differ in, shown as each has it; empty when none.
std::pair<std::string, std::string> FirstDifference(const std::vector<MergedShards::Option>& a,
                                                    const std::vector<MergedShards::Option>& b) {
  std::set<std::string> flags;
  for (const auto& option : a) flags.insert(option.first);
  for (const auto& option : b) flags.insert(option.first);
  for (const std::string& flag : flags) {
    const std::string in_a = Show(a, flag), in_b = Show(b, flag);
    if (in_a != in_b) return {in_a, in_b};
  }
  return {};
}

Manifest ReadManifest(const std::string& dir) {
  const std::string path = Path(dir, kShardManifest);
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": expected a shard directory (written by --shard K/N), found no directory");
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error(dir + ": expected a shard directory with " + kShardManifest +
                             " (written last by --shard K/N), found none: not a shard, or one that did not finish");
  }
  Manifest m;
  m.dir = dir;
  bool has_shard = false, has_trials = false;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(number);
    const auto space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string rest = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "tool") {
      m.tool = rest;
    } else if (key == "shard") {
      const auto shard = ParseShard(rest);
      if (!shard) throw std::runtime_error(where + ": expected shard K/N, got '" + rest + "'");
      m.shard = *shard;
      has_shard = true;
    } else if (key == "trials") {
      const auto trials = Whole(rest);
      if (!trials) throw std::runtime_error(where + ": expected trials N, got '" + rest + "'");
      m.trials = *trials;
      has_trials = true;
    } else if (key == "option" && rest.rfind("--", 0) == 0) {
      const auto gap = rest.find(' ');
      if (gap == std::string::npos) m.options.push_back({rest, std::nullopt});
      else m.options.push_back({rest.substr(0, gap), rest.substr(gap + 1)});
    } else {
      throw std::runtime_error(where + ": expected tool, shard, trials or option --FLAG [VALUE], got '" + line + "'");
    }
  }
  if (m.tool.empty() || !has_shard || !has_trials)
    throw std::runtime_error(path + ": expected tool, shard and trials lines, found " +
                             (m.tool.empty() ? "no tool" : !has_shard ? "no shard" : "no trials"));
  return m;
}

// Reads one shard's records into `records` (the whole run's), which must be every trial the
// shard holds, each once.
void ReadRecords(const Manifest& m, std::vector<std::string>& records) {
  const std::string path = Path(m.dir, kShardRecords);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the shard's records");
  std::vector<bool> seen(records.size(), false);
  std::size_t count = 0;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string where = path + ":" + std::to_string(number);
    const auto space = line.find(' ');
    const auto trial = Whole(line.substr(0, space));
    if (!trial) throw std::runtime_error(where + ": expected a trial number and its record, got '" + line.substr(0, 40) + "'");
    if (*trial >= records.size())
      throw std::runtime_error(where + ": trial " + std::to_string(*trial) + ", expected one below " + std::to_string(records.size()));
    if (!m.shard.Holds(*trial)) {
      throw std::runtime_error(where + ": trial " + std::to_string(*trial) + " belongs to shard " +
                               Shard{static_cast<int>(*trial % m.shard.count) + 1, m.shard.count}.Name() +
                               ", expected only trials of shard " + m.shard.Name());
    }
    if (seen[*trial]) throw std::runtime_error(where + ": trial " + std::to_string(*trial) + " again");
    seen[*trial] = true;
    records[*trial] = space == std::string::npos ? "" : line.substr(space + 1);
    ++count;
  }
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (m.shard.Holds(i) && !seen[i]) {
      std::size_t expected = 0;
      for (std::size_t j = 0; j < records.size(); ++j) expected += m.shard.Holds(j);
      throw std::runtime_error(path + ": expected the " + std::to_string(expected) + " trials of shard " +
                               m.shard.Name() + ", found " + std::to_string(count) + " (trial " +
                               std::to_string(i) + " missing)");
    }
  }
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

std::optional<Shard> ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) return std::nullopt;
  const auto k = Whole(text.substr(0, slash)), n = Whole(text.substr(slash + 1));
  if (!k || !n || *k < 1 || *k > *n || *n > 1000000) return std::nullopt;
  return Shard{static_cast<int>(*k), static_cast<int>(*n)};
}

MergedShards::MergedShards(const std::vector<std::string>& dirs, const std::string& tool) {
  std::vector<Manifest> manifests;
  for (const std::string& dir : dirs) manifests.push_back(ReadManifest(dir));
  const Manifest& first = manifests.front();
  std::vector<const Manifest*> by_shard(first.shard.count, nullptr);
  for (const Manifest& m : manifests) {
    if (m.tool != tool) throw std::runtime_error(m.dir + ": a shard of " + m.tool + ", expected one of " + tool);
    if (m.shard.count != first.shard.count) {
      throw std::runtime_error(m.dir + ": shard " + m.shard.Name() + ", but " + first.dir + " is shard " +
                               first.shard.Name() + ": expected shards of one split into " +
                               std::to_string(first.shard.count));
    }
    const auto [in_first, in_this] = FirstDifference(first.options, m.options);
    if (!in_first.empty() || m.trials != first.trials) {
      throw std::runtime_error(m.dir + ": run with " + (in_first.empty() ? std::to_string(m.trials) + " trials" : in_this) +
                               ", but " + first.dir + " with " +
                               (in_first.empty() ? std::to_string(first.trials) + " trials" : in_first) +
                               ": expected shards of one run (the same options but --shard)");
    }
    const Manifest*& slot = by_shard[m.shard.index - 1];
    if (slot) throw std::runtime_error(m.dir + ": shard " + m.shard.Name() + " again (" + slot->dir + " is shard " + m.shard.Name() + " too)");
    slot = &m;
  }
  for (int k = 0; k < first.shard.count; ++k) {
    if (!by_shard[k]) {
      throw std::runtime_error("--merge: shard " + Shard{k + 1, first.shard.count}.Name() +
                               " missing: expected one directory for each shard 1/" +
                               std::to_string(first.shard.count) + " to " + std::to_string(first.shard.count) +
                               "/" + std::to_string(first.shard.count) + ", got " + std::to_string(dirs.size()) +
                               (dirs.size() == 1 ? " directory" : " directories"));
    }
  }
  options_ = first.options;
  records_.assign(first.trials, "");
  for (const Manifest* m : by_shard) {
    ReadRecords(*m, records_);
    dirs_.push_back(m->dir);
  }
}

std::vector<std::string> MergedShards::OptionWords() const {
  std::vector<std::string> words;
  for (const auto& [flag, value] : options_) {
    words.push_back(flag);
    if (value) words.push_back(*value);
  }
  return words;
}

const std::vector<std::string>& MergedShards::Records(std::size_t trials) const {
  if (trials != records_.size()) {
    throw std::runtime_error(dirs_.front() + ": the shards hold " + std::to_string(records_.size()) +
                             " trials, but their options make " + std::to_string(trials) +
                             ": expected shards written by this version of the tool");
  }
  return records_;
}

std::string MergedShards::Where(std::size_t trial) const {
  return Path(dirs_[trial % dirs_.size()], kShardRecords) + ": trial " + std::to_string(trial);
}

void MergedShards::CopyFiles(const std::string& out) const {
  for (const std::string& dir : dirs_) {
    if (fs::exists(out) && fs::equivalent(dir, out))
      throw std::runtime_error("--out " + out + ": " + dir + " is a shard; expected another directory for the merged report");
  }
  std::map<fs::path, fs::path> copied;  // relative path -> the file it came from
  for (const std::string& dir : dirs_) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      const fs::path relative = entry.path().lexically_relative(dir);
      if (relative == kShardManifest || relative == kShardRecords) continue;
      const auto [it, added] = copied.emplace(relative, entry.path());
      if (!added) {
        if (ReadAll(it->second) != ReadAll(entry.path())) {
          throw std::runtime_error(entry.path().string() + ": differs from " + it->second.string() +
                                   ": expected the shards to write the same file (the same map and world files, "
                                   "at the same paths)");
        }
        continue;
      }
      fs::create_directories((fs::path(out) / relative).parent_path());
      fs::copy_file(entry.path(), fs::path(out) / relative, fs::copy_options::overwrite_existing);
    }
  }
}

BatchRun::BatchRun(const ToolArgs& command, std::set<std::string> local)
    : command_(command), local_(std::move(local)) {
  if (!command.switches().count("--merge"))
    throw std::logic_error(command.program() + ": --merge must be one of the tool's switches");
  const bool merge = command.Switch("--merge");
  const std::string shard = command.String("--shard", "");
  if (command.given().count("--shard")) {
    if (merge) command.Fail("--shard and --merge: give one of them (--shard runs a share of the trials, --merge gathers the shards)");
    const auto parsed = ParseShard(shard);
    if (!parsed) command.Fail("--shard: expected K/N with whole numbers 1 <= K <= N, got '" + shard + "'");
    shard_ = *parsed;
    sharded_ = true;
    for (const auto& [flag, value] : command.given())
      if (value.find('\n') != std::string::npos) command.Fail(flag + ": a value with a line break cannot go into a shard's manifest");
  }
  if (merge) {
    dirs_ = command.positional();
    if (dirs_.empty()) command.Fail("--merge: expected the shard directories after it");
    for (const auto& [flag, value] : command.given()) {
      if (flag != "--merge" && !local_.count(flag))
        command.Fail("--merge takes the options from the shards' manifests: drop " + flag);
    }
  }
}

std::vector<std::size_t> BatchRun::Trials(std::size_t n) const {
  std::vector<std::size_t> trials;
  for (std::size_t i = 0; i < n; ++i)
    if (shard_.Holds(i)) trials.push_back(i);
  return trials;
}

void BatchRun::WriteShard(const std::string& dir, const std::vector<std::string>& records) const {
  fs::create_directories(dir);
  const std::string manifest_path = Path(dir, kShardManifest), records_path = Path(dir, kShardRecords);
  // The manifest goes last and only beside the records it describes: a shard that stops
  // half-way leaves a directory that --merge refuses.
  fs::remove(manifest_path);
  std::ofstream out(records_path);
  std::size_t written = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (!shard_.Holds(i)) continue;
    out << i << ' ' << records[i] << '\n';
    ++written;
  }
  out.close();
  if (!out) throw std::runtime_error(records_path + ": cannot write");
  std::ofstream manifest(manifest_path);
  manifest << "# A shard of a batch run (tool_args/shard.h): written after " << kShardRecords
           << ",\n# so a directory with this file holds a finished shard. Merge with --merge.\n"
           << "tool " << command_.program() << "\nshard " << shard_.Name() << "\ntrials " << records.size() << '\n';
  for (const auto& [flag, value] : command_.given()) {
    if (flag == "--shard" || local_.count(flag)) continue;
    manifest << "option " << flag;
    if (!command_.switches().count(flag)) manifest << ' ' << value;
    manifest << '\n';
  }
  manifest.close();
  if (!manifest) throw std::runtime_error(manifest_path + ": cannot write");
  std::printf("shard %s: %zu of %zu trials in %s (gather the shards with --merge)\n", shard_.Name().c_str(), written,
              records.size(), dir.c_str());
}

MergedShards BatchRun::Merge() const { return MergedShards(dirs_, command_.program()); }

ToolArgs BatchRun::MergedArgs(const MergedShards& shards) const {
  std::vector<std::string> words = shards.OptionWords();
  for (const auto& [flag, value] : command_.given()) {
    if (!local_.count(flag)) continue;
    words.push_back(flag);
    if (!command_.switches().count(flag)) words.push_back(value);
  }
  return ToolArgs(command_.program(), command_.usage(), words, command_.switches());
}

}  // namespace multirobot_audio::tools
