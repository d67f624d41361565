// Makes the fuzz targets' binary seeds with the project's own modulators and writers:
//
//   fuzz_make_corpus fuzz/corpus
//
// writes fsk_receiver/, room_receiver/, frame/, wav_file/, map_file/ (the images; the YAML seeds
// are written by hand) and decode_table/ under the folder. The seeds are small (a packet at a
// low sample rate, a WAV of a few samples): libFuzzer mutates small inputs fastest.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "audio_propagation/decode_table.h"
#include "nava_modem/frame.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

void Write(const fs::path& path, const Bytes& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

Bytes ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The fuzzer's largest receiver input (scripts/fuzz.sh's -max_len for the receivers).
constexpr std::size_t kMaxReceiverInput = 65536;

// A packet between short silences, as receiver_input.h's samples: with faint white noise
// (`noise`, its RMS), or as a microphone in `room` hears it (room_channel.h: reverberation,
// tilt, noise, whine, the sender's clock off), cut to fit the fuzzer's largest input.
Bytes ReceiverSeed(nava_modem::Profile profile, double rate, std::uint8_t rate_index, bool floats,
                   const std::vector<std::uint8_t>& data, double noise,
                   const std::optional<nava_modem::RoomOptions>& room = std::nullopt) {
  nava_modem::ModemOptions modem;
  modem.sample_rate = rate;
  std::vector<float> samples(static_cast<std::size_t>(0.05 * rate), 0.0f);
  const std::vector<float> packet = nava_modem::MakeProfile(profile, modem)->ModulatePacket(data);
  samples.insert(samples.end(), packet.begin(), packet.end());
  samples.insert(samples.end(), static_cast<std::size_t>(0.05 * rate), 0.0f);
  if (room) {
    samples = nava_modem::RenderRoom(samples, rate, *room);
  } else {
    const std::vector<double> hiss = nava_modem::WhiteNoise(samples.size(), 7);
    for (std::size_t k = 0; k < samples.size(); ++k) samples[k] += static_cast<float>(noise * hiss[k]);
  }
  samples.resize(std::min(samples.size(), (kMaxReceiverInput - 3) / (floats ? 4 : 2)));
  Bytes out = {static_cast<std::uint8_t>(rate_index << 1 | (floats ? 1 : 0)), 20, 2 | 4};
  for (float s : samples) {
    if (floats) {
      std::uint8_t b[4];
      std::memcpy(b, &s, 4);
      out.insert(out.end(), b, b + 4);
    } else {
      const auto v = static_cast<std::int16_t>(std::lround(std::max(-1.0f, std::min(1.0f, s)) * 32767.0f));
      out.push_back(static_cast<std::uint8_t>(v & 0xff));
      out.push_back(static_cast<std::uint8_t>((v >> 8) & 0xff));
    }
  }
  return out;
}

// frame.cpp's input: options, a frame, and soft decisions on its bits (some flipped and unsure).
Bytes FrameSeed(nava_modem::CrcVariant crc, int max_fixed_bits, const std::vector<std::uint8_t>& data,
                const std::vector<int>& flipped) {
  const nava_modem::Frame frame = nava_modem::MakeFrame(data, crc);
  Bytes out = {static_cast<std::uint8_t>((crc == nava_modem::CrcVariant::kXmodem ? 1 : 0) | max_fixed_bits << 1)};
  out.insert(out.end(), frame.begin(), frame.end());
  for (int b = 0; b < nava_modem::kFrameBytes * 8; ++b) {
    float soft = ((frame[b / 8] >> (b % 8)) & 1) ? 2.5f : -2.5f;
    for (int f : flipped) {
      if (f == b) soft = -0.1f * soft;
    }
    std::uint8_t bytes[4];
    std::memcpy(bytes, &soft, 4);
    out.insert(out.end(), bytes, bytes + 4);
  }
  return out;
}

std::vector<float> Tone(std::size_t n, double rate, double hz) {
  std::vector<float> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<float>(0.5 * std::sin(2.0 * M_PI * hz * k / rate));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_corpus CORPUS_DIR\n";
    return 1;
  }
  const fs::path corpus = argv[1];
  using nava_modem::Profile;
  // fsk_receiver's rates: 16000, 44100, 48000, 8000 (receiver_input.h picks by index).
  Write(corpus / "fsk_receiver" / "packet_16k_int16", ReceiverSeed(Profile::kNava, 16000.0, 0, false, {1, 2, 3, 4}, 0.01));
  Write(corpus / "fsk_receiver" / "packet_8k_float", ReceiverSeed(Profile::kNava, 8000.0, 3, true, {0xa0, 0x55, 0xff, 0}, 0.05));
  // room_receiver's rates: 12000, 16000, 48000.
  Write(corpus / "room_receiver" / "packet_12k_int16", ReceiverSeed(Profile::kRoom, 12000.0, 0, false, {9, 8, 7, 6}, 0.01));
  // As a robot's microphone hears it: reverberation louder than the direct sound, pink noise, a
  // motor whine, a speaker weak in the highs, the sender's clock 0.3 % fast.
  nava_modem::RoomOptions office;
  office.rt60 = 0.5;
  office.drr_db = -5.0;
  office.tilt_db = -6.0;
  office.clock_offset = 0.003;
  office.noise = nava_modem::RoomOptions::Noise::kPink;
  office.snr_db = 15.0;
  office.whine_hz = 1800.0;
  office.whine_sir_db = 10.0;
  Write(corpus / "room_receiver" / "office_12k_int16",
        ReceiverSeed(Profile::kRoom, 12000.0, 0, false, {0x31, 0x41, 0x59, 0x26}, 0.0, office));
  // The nava FSK profile in a milder room (it has no defence against strong echoes).
  nava_modem::RoomOptions small_room = office;
  small_room.rt60 = 0.3;
  small_room.drr_db = 5.0;
  small_room.snr_db = 25.0;
  Write(corpus / "fsk_receiver" / "small_room_16k_int16",
        ReceiverSeed(Profile::kNava, 16000.0, 0, false, {0x27, 0x18, 0x28, 0x18}, 0.0, small_room));

  using nava_modem::CrcVariant;
  Write(corpus / "frame" / "clean", FrameSeed(CrcVariant::kCcittFalse, 2, {1, 2, 3, 4}, {}));
  Write(corpus / "frame" / "one_flipped", FrameSeed(CrcVariant::kCcittFalse, 1, {0x55, 0xaa, 0, 0xff}, {13}));
  Write(corpus / "frame" / "two_flipped_xmodem", FrameSeed(CrcVariant::kXmodem, 2, {7, 7, 7, 7}, {3, 40}));

  const fs::path scratch = fs::temp_directory_path() / "fuzz_make_corpus.wav";
  nava_modem::WriteWavFile(scratch.string(), Tone(64, 8000.0, 1000.0), 8000.0);
  Write(corpus / "wav_file" / "pcm16_mono.wav", ReadBytes(scratch));
  nava_modem::WriteFloatWavFile(scratch.string(), Tone(32, 48000.0, 2300.0), 48000.0);
  Write(corpus / "wav_file" / "float_mono.wav", ReadBytes(scratch));
  nava_modem::WriteWavChannels(scratch.string(), {Tone(24, 16000.0, 440.0), Tone(24, 16000.0, 880.0)}, 16000.0);
  Write(corpus / "wav_file" / "pcm16_stereo.wav", ReadBytes(scratch));
  fs::remove(scratch);

  // map_file's image seeds: byte 0 odd, then a small room walled round (PGM and PNG, grey and
  // colour with alpha), unknown cells in a corner.
  cv::Mat grey(12, 16, CV_8UC1, cv::Scalar(254));
  grey.row(0).setTo(0);
  grey.row(11).setTo(0);
  grey.col(0).setTo(0);
  grey.col(15).setTo(0);
  grey(cv::Rect(12, 8, 3, 3)).setTo(205);
  std::vector<std::uint8_t> encoded;
  cv::imencode(".pgm", grey, encoded);
  encoded.insert(encoded.begin(), 1);
  Write(corpus / "map_file" / "image_pgm", encoded);
  cv::imencode(".png", grey, encoded);
  encoded.insert(encoded.begin(), 3);
  Write(corpus / "map_file" / "image_png_negated", encoded);
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>{grey, grey, grey, cv::Mat(grey.size(), CV_8UC1, cv::Scalar(255))}, colour);
  cv::imencode(".png", colour, encoded);
  encoded.insert(encoded.begin(), 1);
  Write(corpus / "map_file" / "image_png_rgba", encoded);

  // A small table: every kind, two SNRs, one DRR, one RT60.
  fs::create_directories(corpus / "decode_table");
  audio_propagation::DecodeTable table;
  table.profile = "nava";
  table.packets = 4;
  table.whine_hz = 3000.0;
  table.band_low_hz = 2150.0;
  table.band_high_hz = 3850.0;
  table.command = "fuzz_make_corpus";
  table.snr_db = {-10.0, 0.0};
  table.drr_db = {0.0};
  table.rt60 = {0.5};
  table.Resize();
  for (std::size_t c = 0; c < table.cells.size(); ++c) {
    table.cells[c] = c % 2 ? audio_propagation::DecodeOutcome{1.0, 0.0, 0.0, 0.0}
                           : audio_propagation::DecodeOutcome{0.25, 0.25, 0.25, 0.0};
  }
  audio_propagation::SaveDecodeTable((corpus / "decode_table" / "small.yaml").string(), table);
  table.profile = "room";
  table.snr_db = {-20.0, -5.0, 10.0};
  table.drr_db = {-6.0, 6.0};
  table.rt60 = {0.3, 1.2};
  table.Resize();
  for (std::size_t c = 0; c < table.cells.size(); ++c) table.cells[c] = {0.75, 0.0, 0.125, 0.125};
  audio_propagation::SaveDecodeTable((corpus / "decode_table" / "room.yaml").string(), table);
  std::cout << "seeds written under " << corpus.string() << "\n";
  return 0;
}
