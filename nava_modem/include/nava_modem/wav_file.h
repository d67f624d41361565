#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace nava_modem {

// Mono audio as floats in [-1, 1].
struct Audio {
  std::vector<float> samples;
  double sample_rate = 0.0;
};

// Reads any audio file libsndfile knows (WAV, FLAC, ...); several channels are mixed to one.
// Throws std::runtime_error naming the file when it cannot be read or is not audio.
Audio ReadAudioFile(const std::string& path);

// Writes 16-bit PCM WAV, clipping to full scale. Throws std::runtime_error naming the file.
void WriteWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate);

// Writes 32-bit float WAV, unclipped: for renderings whose levels are absolute (the scene
// renderer's) and may pass full scale. Throws std::runtime_error naming the file.
void WriteFloatWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate);

// Writes several channels (channels[c] is channel c) as one interleaved 16-bit PCM WAV, clipping
// to full scale. Throws std::runtime_error naming the file when there are no channels, when
// they differ in length, or when it cannot be written.
void WriteWavChannels(const std::string& path, const std::vector<std::vector<float>>& channels, double sample_rate);

// Every channel of an audio file, apart: channels[c][k] is channel c's sample k (floats in
// [-1, 1]), for a microphone array's recording.
struct MultiAudio {
  std::vector<std::vector<float>> channels;
  double sample_rate = 0.0;
};

// Reads any audio file libsndfile knows, keeping its channels. Throws std::runtime_error naming
// the file when it cannot be read or is not audio.
MultiAudio ReadAudioChannels(const std::string& path);

// The same from a file's bytes in memory (through libsndfile's virtual I/O), for audio that
// arrives other than as a file, and for the fuzzer; `name` names it in errors.
MultiAudio ReadAudioChannelsFromMemory(const void* data, std::size_t size, const std::string& name);

}  // namespace nava_modem
