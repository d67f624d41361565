#include "nava_modem/wav_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace nava_modem {
namespace {

// Found by fuzz/wav_file.cpp: 107 bytes whose LIST chunk claims 4 GB made libsndfile's sf_open
// loop for hours (its chunk parser; upstream libsndfile issue 1118). The file must be refused
// with std::runtime_error; the read runs in a child stopped by an alarm, so a hang fails the
// test in seconds instead of hanging it.
const std::vector<unsigned char> kHugeListChunk = {
    'R', 'I', 'F', 'F', 0xc8, 0x00, 'U', 0x00, 'W', 'A', 'V', 'E', 'L', 'I', 'S', 'T', 0x1f, 0xff, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xfa, 0xbf, 0xff, 0xff, 0xff, 0x0c, 0x05, 'i', 0xe9, 0x00, 0xff, 0xfa};

// Exits 0 when `read` throws std::runtime_error, 1 when it returns; SIGALRM after 5 s.
template <typename Read>
void RefusedWithin5Seconds(Read read) {
  alarm(5);
  try {
    read();
  } catch (const std::runtime_error&) {
    std::exit(0);
  }
  std::exit(1);
}

TEST(WavFileDeathTest, ChunkLongerThanTheFileIsRefusedNotHungOn) {
  ASSERT_EQ(kHugeListChunk.size(), 107u);
  EXPECT_EXIT(RefusedWithin5Seconds([] { ReadAudioChannelsFromMemory(kHugeListChunk.data(), kHugeListChunk.size(), "m.wav"); }),
              ::testing::ExitedWithCode(0), "");
  const std::string path = (std::filesystem::temp_directory_path() / ("wav_file_test_" + std::to_string(getpid()) + ".wav")).string();
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(kHugeListChunk.data()), kHugeListChunk.size());
  EXPECT_EXIT(RefusedWithin5Seconds([&] { ReadAudioChannels(path); }), ::testing::ExitedWithCode(0), "");
  std::filesystem::remove(path);
}

TEST(WavFile, MemoryReadsWhatTheFileReads) {
  const std::string path = (std::filesystem::temp_directory_path() / ("wav_file_test_ok_" + std::to_string(getpid()) + ".wav")).string();
  WriteWavChannels(path, {{0.5f, -0.25f, 0.0f}, {0.125f, 0.0f, -0.5f}}, 16000.0);
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const MultiAudio from_file = ReadAudioChannels(path), from_memory = ReadAudioChannelsFromMemory(bytes.data(), bytes.size(), "m.wav");
  std::filesystem::remove(path);
  EXPECT_EQ(from_memory.sample_rate, 16000.0);
  EXPECT_EQ(from_memory.channels, from_file.channels);
  ASSERT_EQ(from_memory.channels.size(), 2u);
  EXPECT_FLOAT_EQ(from_memory.channels[1][2], -0.5f);
}

}  // namespace
}  // namespace nava_modem
