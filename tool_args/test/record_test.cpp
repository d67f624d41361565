#include "tool_args/record.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace multirobot_audio::tools {
namespace {

// A double's bits: "the same value" for a report means the same bits.
std::uint64_t Bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

TEST(RecordTest, DoublesReadBackBitForBit) {
  std::vector<double> values = {0.0, -0.0, 0.1, 1.0 / 3.0, 1e308, -2.5e-308,
                                std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity()};
  std::mt19937_64 rng(7);
  while (values.size() < 10000) {
    const std::uint64_t bits = rng();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (std::isfinite(value)) values.push_back(value);
  }
  RecordWriter writer;
  writer.PutList(values).Put(std::nan(""));
  RecordReader reader(writer.text(), "test");
  const std::vector<double> back = reader.GetList<double>();
  ASSERT_EQ(back.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(Bits(back[i]), Bits(values[i])) << values[i];
  EXPECT_TRUE(std::isnan(reader.Get<double>()));
  reader.End();
}

TEST(RecordTest, WholeNumbersAndFlagsReadBack) {
  RecordWriter writer;
  writer.Put(std::numeric_limits<std::uint64_t>::max())
      .Put(std::numeric_limits<long long>::min())
      .Put(true)
      .Put(false)
      .Put(-3)
      .Put(std::uint32_t{4294967295u});
  RecordReader reader(writer.text(), "test");
  EXPECT_EQ(reader.Get<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(reader.Get<long long>(), std::numeric_limits<long long>::min());
  EXPECT_TRUE(reader.Get<bool>());
  EXPECT_FALSE(reader.Get<bool>());
  EXPECT_EQ(reader.Get<int>(), -3);
  reader.Expect<std::uint32_t>(4294967295u, "seed");
  reader.End();
}

// The message of what `read` throws, or "" when it does not throw.
template <class Read>
std::string Error(const std::string& text, Read read) {
  try {
    RecordReader reader(text, "dir/shard_trials.txt:3");
    read(reader);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RecordTest, DamagedRecordsNameTheWordAndWhatWasExpected) {
  EXPECT_EQ(Error("1 x", [](RecordReader& r) { r.Get<int>(), r.Get<double>(); }),
            "dir/shard_trials.txt:3: word 2: expected a number, got 'x'");
  EXPECT_EQ(Error("300", [](RecordReader& r) { r.Get<std::uint8_t>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number from 0 to 255, got '300'");
  EXPECT_EQ(Error("-1", [](RecordReader& r) { r.Get<unsigned>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number from 0 to 4294967295, got '-1'");
  EXPECT_EQ(Error("2", [](RecordReader& r) { r.Get<bool>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number from 0 to 1, got '2'");
  EXPECT_EQ(Error("1.5", [](RecordReader& r) { r.Get<int>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number from -2147483648 to 2147483647, got '1.5'");
  EXPECT_EQ(Error("1", [](RecordReader& r) { r.Get<int>(), r.Get<int>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number, got the end of the record");
  EXPECT_EQ(Error("1 2", [](RecordReader& r) { r.Get<int>(), r.End(); }),
            "dir/shard_trials.txt:3: word 2: expected the end of the record, got '2'");
  EXPECT_EQ(Error("7", [](RecordReader& r) { r.Expect<int>(8, "seed"); }),
            "dir/shard_trials.txt:3: word 1: expected seed 8, got 7");
  // A list cannot claim more values than the record has words.
  EXPECT_EQ(Error("1000000 1", [](RecordReader& r) { r.GetList<double>(); }),
            "dir/shard_trials.txt:3: word 1: expected a whole number from 0 to 1, got '1000000'");
}

}  // namespace
}  // namespace multirobot_audio::tools
