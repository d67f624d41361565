#include "tool_args/shard.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace multirobot_audio::tools {
namespace {

namespace fs = std::filesystem;

TEST(ShardTest, ParsesOnlyKOfN) {
  const auto shard = ParseShard("2/8");
  ASSERT_TRUE(shard);
  EXPECT_EQ(shard->index, 2);
  EXPECT_EQ(shard->count, 8);
  EXPECT_EQ(shard->Name(), "2/8");
  for (const char* bad : {"0/2", "3/2", "a/b", "1/", "/2", "2", "-1/2", "1/2/3", " 1/2", "1/0", ""})
    EXPECT_FALSE(ParseShard(bad)) << bad;
}

TEST(ShardTest, EveryTrialBelongsToOneShard) {
  for (int n = 1; n <= 7; ++n)
    for (std::size_t trial = 0; trial < 50; ++trial) {
      int holders = 0;
      for (int k = 1; k <= n; ++k) holders += Shard{k, n}.Holds(trial);
      EXPECT_EQ(holders, 1) << trial << " of " << n;
      EXPECT_TRUE((Shard{static_cast<int>(trial % n) + 1, n}.Holds(trial)));
    }
}

class ShardFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("shard_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string Dir(const std::string& name) const { return (root_ / name).string(); }

  // Runs "tool OPTIONS --shard K/N --out DIR" over `trials` trials whose records are "r<i>", and
  // writes `extra` (a file every shard writes) into the shard too.
  void WriteShard(const std::string& name, const std::string& shard, std::vector<std::string> options,
                  std::size_t trials = 5, const std::string& extra = "same") {
    options.insert(options.end(), {"--shard", shard, "--out", Dir(name), "--threads", name});
    const ToolArgs args("tool", "tool [--seed S]", options, {"--merge"});
    const BatchRun run(args, {"--out", "--threads"});
    std::vector<std::string> records(trials);
    for (std::size_t i : run.Trials(trials)) records[i] = "r" + std::to_string(i);
    run.WriteShard(Dir(name), records);
    std::ofstream(root_ / name / "shared.txt") << extra;
  }

  // The error of merging `names`, or "" when it works.
  std::string MergeError(const std::vector<std::string>& names, std::size_t trials = 5) const {
    std::vector<std::string> dirs;
    for (const std::string& name : names) dirs.push_back(Dir(name));
    try {
      MergedShards(dirs, "tool").Records(trials);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path root_;
};

TEST_F(ShardFilesTest, MergeGivesEveryRecordInOrderAndTheRunsOptions) {
  WriteShard("b", "2/2", {"--seed", "3"});
  WriteShard("a", "1/2", {"--seed", "3"});
  const std::vector<std::string> words = {"--merge", Dir("b"), Dir("a"), "--out", Dir("m")};
  const ToolArgs command("tool", "tool [--seed S]", words, {"--merge"});
  const BatchRun run(command, {"--out", "--threads"});
  ASSERT_TRUE(run.merging());
  const MergedShards merged = run.Merge();
  EXPECT_EQ(merged.Records(5), (std::vector<std::string>{"r0", "r1", "r2", "r3", "r4"}));
  // --threads and --out were the shards' own; the merge's --out comes with the options.
  EXPECT_EQ(merged.OptionWords(), (std::vector<std::string>{"--seed", "3"}));
  const ToolArgs args = run.MergedArgs(merged);
  EXPECT_EQ(args.String("--seed", ""), "3");
  EXPECT_EQ(args.String("--out", ""), Dir("m"));
  merged.CopyFiles(Dir("m"));
  std::ifstream copied(root_ / "m" / "shared.txt");
  std::string text;
  copied >> text;
  EXPECT_EQ(text, "same");
  EXPECT_FALSE(fs::exists(root_ / "m" / kShardManifest));
  EXPECT_THROW(merged.Records(6), std::runtime_error);
}

TEST_F(ShardFilesTest, RefusesShardsThatAreNotOneWholeRun) {
  WriteShard("a", "1/2", {"--seed", "3"});
  WriteShard("b", "2/2", {"--seed", "3"});
  WriteShard("c", "2/2", {"--seed", "4"});
  WriteShard("d", "1/3", {"--seed", "3"});
  WriteShard("e", "2/2", {"--seed", "3", "--extra", "x"});
  WriteShard("f", "2/2", {"--seed", "3"}, 6);
  EXPECT_EQ(MergeError({"a", "b"}), "");
  EXPECT_EQ(MergeError({"a"}), "--merge: shard 2/2 missing: expected one directory for each shard 1/2 to 2/2, got 1 directory");
  EXPECT_EQ(MergeError({"a", "b", "b"}), Dir("b") + ": shard 2/2 again (" + Dir("b") + " is shard 2/2 too)");
  EXPECT_EQ(MergeError({"a", "c"}), Dir("c") + ": run with --seed 4, but " + Dir("a") +
                                        " with --seed 3: expected shards of one run (the same options but --shard)");
  EXPECT_EQ(MergeError({"a", "e"}), Dir("e") + ": run with --extra x, but " + Dir("a") +
                                        " with no --extra: expected shards of one run (the same options but --shard)");
  EXPECT_EQ(MergeError({"a", "f"}), Dir("f") + ": run with 6 trials, but " + Dir("a") +
                                        " with 5 trials: expected shards of one run (the same options but --shard)");
  EXPECT_EQ(MergeError({"a", "d"}),
            Dir("d") + ": shard 1/3, but " + Dir("a") + " is shard 1/2: expected shards of one split into 2");
  EXPECT_EQ(MergeError({"a", "nothing"}), Dir("nothing") + ": expected a shard directory (written by --shard K/N), found no directory");
  fs::create_directories(root_ / "empty");
  EXPECT_NE(MergeError({"a", "empty"}).find("empty: expected a shard directory with shard.txt"), std::string::npos);
}

TEST_F(ShardFilesTest, RefusesADroppedOrStrayRecord) {
  WriteShard("a", "1/2", {});
  WriteShard("b", "2/2", {});
  const fs::path records = root_ / "a" / kShardRecords;
  std::ofstream(records) << "0 r0\n4 r4\n";  // trial 2 dropped
  EXPECT_EQ(MergeError({"a", "b"}), records.string() + ": expected the 3 trials of shard 1/2, found 2 (trial 2 missing)");
  std::ofstream(records) << "0 r0\n2 r2\n4 r4\n1 r1\n";
  EXPECT_EQ(MergeError({"a", "b"}), records.string() + ":4: trial 1 belongs to shard 2/2, expected only trials of shard 1/2");
  std::ofstream(records) << "0 r0\n2 r2\n2 r2\n4 r4\n";
  EXPECT_EQ(MergeError({"a", "b"}), records.string() + ":3: trial 2 again");
  std::ofstream(records) << "0 r0\n2 r2\n4 r4\n6 r6\n";
  EXPECT_EQ(MergeError({"a", "b"}), records.string() + ":4: trial 6, expected one below 5");
}

TEST_F(ShardFilesTest, CopyRefusesDifferentFilesOfOneName) {
  WriteShard("a", "1/2", {});
  WriteShard("b", "2/2", {}, 5, "other");
  const MergedShards merged({Dir("a"), Dir("b")}, "tool");
  try {
    merged.CopyFiles(Dir("m"));
    FAIL() << "copied";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (root_ / "b" / "shared.txt").string() + ": differs from " +
                                         (root_ / "a" / "shared.txt").string() +
                                         ": expected the shards to write the same file (the same map and world "
                                         "files, at the same paths)");
  }
  EXPECT_THROW(merged.CopyFiles(Dir("a")), std::runtime_error);
}

}  // namespace
}  // namespace multirobot_audio::tools
