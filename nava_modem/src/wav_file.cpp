#include "nava_modem/wav_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include <sndfile.h>

namespace nava_modem {
namespace {

// Closes a libsndfile handle however the function leaves.
struct SndFile {
  SNDFILE* handle = nullptr;
  ~SndFile() {
    if (handle) sf_close(handle);
  }
};

}  // namespace

Audio ReadAudioFile(const std::string& path) {
  const MultiAudio multi = ReadAudioChannels(path);
  Audio audio;
  audio.sample_rate = multi.sample_rate;
  audio.samples.assign(multi.channels[0].size(), 0.0f);
  const float share = 1.0f / static_cast<float>(multi.channels.size());
  for (const std::vector<float>& channel : multi.channels) {
    for (std::size_t k = 0; k < channel.size(); ++k) audio.samples[k] += share * channel[k];
  }
  return audio;
}

namespace {

void WriteMono(const std::string& path, const std::vector<float>& samples, double sample_rate, int subformat) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | subformat;
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file.handle) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  if (subformat == SF_FORMAT_PCM_16) sf_command(file.handle, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  if (sf_writef_float(file.handle, samples.data(), static_cast<sf_count_t>(samples.size())) !=
      static_cast<sf_count_t>(samples.size())) {
    throw std::runtime_error(path + ": write failed (" + sf_strerror(file.handle) + ")");
  }
}

}  // namespace

void WriteWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  WriteMono(path, samples, sample_rate, SF_FORMAT_PCM_16);
}

void WriteFloatWavFile(const std::string& path, const std::vector<float>& samples, double sample_rate) {
  WriteMono(path, samples, sample_rate, SF_FORMAT_FLOAT);
}

void WriteWavChannels(const std::string& path, const std::vector<std::vector<float>>& channels, double sample_rate) {
  if (channels.empty()) throw std::runtime_error(path + ": no channels to write");
  const std::size_t frames = channels[0].size();
  for (std::size_t c = 1; c < channels.size(); ++c) {
    if (channels[c].size() != frames) {
      throw std::runtime_error(path + ": channel " + std::to_string(c + 1) + " has " + std::to_string(channels[c].size()) +
                               " samples, channel 1 has " + std::to_string(frames) + ": expected the same length");
    }
  }
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate));
  info.channels = static_cast<int>(channels.size());
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file.handle) throw std::runtime_error(path + ": cannot write (" + sf_strerror(nullptr) + ")");
  sf_command(file.handle, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  std::vector<float> interleaved(frames * channels.size());
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t c = 0; c < channels.size(); ++c) interleaved[f * channels.size() + c] = channels[c][f];
  }
  if (sf_writef_float(file.handle, interleaved.data(), static_cast<sf_count_t>(frames)) != static_cast<sf_count_t>(frames)) {
    throw std::runtime_error(path + ": write failed (" + sf_strerror(file.handle) + ")");
  }
}

namespace {

// libsndfile 1.2 can loop for hours in sf_open on a RIFF file one of whose chunks claims more
// bytes than the file holds (its LIST/INFO parser; upstream libsndfile issue 1118). Such a file
// is refused before libsndfile sees it. The data chunk alone may run past the end (a recording
// cut short, or a stream's unknown length), as libsndfile reads what there is. `read(offset,
// n, out)` reads n bytes of the file at offset, false past its end.
template <typename Read>
void CheckRiffChunks(std::uint64_t length, Read read, const std::string& name) {
  unsigned char header[12];
  if (!read(0, 12, header)) return;
  const bool little = std::memcmp(header, "RIFF", 4) == 0, big = std::memcmp(header, "RIFX", 4) == 0;
  if (!(little || big) || std::memcmp(header + 8, "WAVE", 4) != 0) return;
  std::uint64_t at = 12;
  unsigned char chunk[8];
  while (at + 8 <= length && read(at, 8, chunk)) {
    const std::uint32_t size = little ? chunk[4] | chunk[5] << 8 | chunk[6] << 16 | static_cast<std::uint32_t>(chunk[7]) << 24
                                      : static_cast<std::uint32_t>(chunk[4]) << 24 | chunk[5] << 16 | chunk[6] << 8 | chunk[7];
    if (std::memcmp(chunk, "data", 4) == 0) return;
    if (size > length - at - 8) {
      std::string id;
      for (int k = 0; k < 4; ++k) id += std::isprint(chunk[k]) ? static_cast<char>(chunk[k]) : '?';
      throw std::runtime_error(name + ": not a readable audio file (chunk '" + id + "' at byte " + std::to_string(at) +
                               " claims " + std::to_string(size) + " bytes, more than the file's " +
                               std::to_string(length) + ")");
    }
    at += 8 + size + (size & 1);  // chunks are padded to an even length
  }
}

// Every channel of an opened file, `name` naming it in errors.
MultiAudio ReadOpened(SndFile& file, const SF_INFO& info, const std::string& name) {
  if (info.channels < 1 || info.samplerate <= 0) {
    throw std::runtime_error(name + ": no audio channels or no sample rate");
  }
  const std::size_t channels = static_cast<std::size_t>(info.channels);
  // Block by block (of about 64 K samples over all channels) until the end: the header's frame
  // count is the file's claim, not a size to allocate (a few hundred bytes can claim terabytes).
  const std::size_t block = std::max<std::size_t>(1, (std::size_t{1} << 16) / channels);
  std::vector<float> interleaved;
  std::size_t got = 0;
  while (true) {
    interleaved.resize((got + block) * channels);
    const sf_count_t n = sf_readf_float(file.handle, interleaved.data() + got * channels, static_cast<sf_count_t>(block));
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  MultiAudio audio;
  audio.sample_rate = info.samplerate;
  audio.channels.assign(channels, std::vector<float>(got));
  for (std::size_t f = 0; f < got; ++f) {
    for (std::size_t c = 0; c < channels; ++c) audio.channels[c][f] = interleaved[f * channels + c];
  }
  return audio;
}

// A file's bytes in memory, read through libsndfile's virtual I/O.
struct MemoryFile {
  const unsigned char* data;
  sf_count_t size;
  sf_count_t at = 0;

  static MemoryFile& Of(void* user) { return *static_cast<MemoryFile*>(user); }
  static sf_count_t Length(void* user) { return Of(user).size; }
  static sf_count_t Seek(sf_count_t offset, int whence, void* user) {
    MemoryFile& m = Of(user);
    const sf_count_t base = whence == SEEK_CUR ? m.at : whence == SEEK_END ? m.size : 0;
    // Past the end reads nothing; before the start is refused, as by a file.
    if (offset < -base || offset > std::numeric_limits<sf_count_t>::max() - base) return -1;
    m.at = base + offset;
    return m.at;
  }
  static sf_count_t Read(void* out, sf_count_t count, void* user) {
    MemoryFile& m = Of(user);
    const sf_count_t n = std::max<sf_count_t>(0, std::min(count, m.size - m.at));
    if (n > 0) std::memcpy(out, m.data + m.at, static_cast<std::size_t>(n));
    m.at += n;
    return n;
  }
  static sf_count_t Write(const void*, sf_count_t, void*) { return 0; }
  static sf_count_t Tell(void* user) { return Of(user).at; }
};

}  // namespace

MultiAudio ReadAudioChannelsFromMemory(const void* data, std::size_t size, const std::string& name) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  CheckRiffChunks(size, [&](std::uint64_t offset, std::size_t n, unsigned char* out) {
    if (offset + n > size) return false;
    std::memcpy(out, bytes + offset, n);
    return true;
  }, name);
  MemoryFile memory{bytes, static_cast<sf_count_t>(size)};
  SF_VIRTUAL_IO io{&MemoryFile::Length, &MemoryFile::Seek, &MemoryFile::Read, &MemoryFile::Write, &MemoryFile::Tell};
  SF_INFO info{};
  SndFile file;
  file.handle = sf_open_virtual(&io, SFM_READ, &info, &memory);
  if (!file.handle) {
    throw std::runtime_error(name + ": not readable audio (" + sf_strerror(nullptr) + ")");
  }
  return ReadOpened(file, info, name);
}

MultiAudio ReadAudioChannels(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (in) {
    const auto length = static_cast<std::uint64_t>(in.tellg());
    CheckRiffChunks(length, [&](std::uint64_t offset, std::size_t n, unsigned char* out) {
      in.seekg(static_cast<std::streamoff>(offset));
      return static_cast<bool>(in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n)));
    }, path);
  }
  SF_INFO info{};
  SndFile file;
  file.handle = sf_open(path.c_str(), SFM_READ, &info);
  if (!file.handle) {
    throw std::runtime_error(path + ": not a readable audio file (" + sf_strerror(nullptr) + ")");
  }
  return ReadOpened(file, info, path);
}

}  // namespace nava_modem
