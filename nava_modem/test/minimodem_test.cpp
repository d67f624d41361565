// Interoperability with minimodem, an independent FSK modem (Debian package minimodem):
// with --mark 2300 --space 3700 300 it reads and writes 8N1 bytes the way Nava does.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

std::string Capture(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  std::size_t got;
  while ((got = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, got);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return out;
}

std::string TempPath(const std::string& name) {
  return "/tmp/nava_minimodem_" + std::to_string(getpid()) + "_" + name;
}

TEST(Minimodem, ReadsThePacketsWeSend) {
  ModemOptions o;
  const FskModulator mod(o);
  std::vector<float> audio(static_cast<std::size_t>(0.3 * o.sample_rate), 0.0f);
  for (const std::vector<std::uint8_t>& data : {std::vector<std::uint8_t>{1, 2, 3, 4}, {0xDE, 0xAD, 0xBE, 0xEF}}) {
    const std::vector<float> burst = mod.ModulatePacket(data);
    audio.insert(audio.end(), burst.begin(), burst.end());
    audio.insert(audio.end(), static_cast<std::size_t>(0.3 * o.sample_rate), 0.0f);
  }
  const std::string wav = TempPath("ours.wav");
  WriteWavFile(wav, audio, o.sample_rate);
  const std::string bytes = Capture("minimodem --rx -q -f " + wav + " --mark 2300 --space 3700 300");
  std::remove(wav.c_str());
  // Each frame, header to CRC, in order (minimodem cannot frame the break, so it may print
  // something for it, or not).
  const Frame a = MakeFrame({1, 2, 3, 4}, o.crc), b = MakeFrame({0xDE, 0xAD, 0xBE, 0xEF}, o.crc);
  const std::string expected_a(a.begin(), a.end()), expected_b(b.begin(), b.end());
  const auto at_a = bytes.find(expected_a);
  ASSERT_NE(at_a, std::string::npos) << "minimodem printed " << bytes.size() << " bytes";
  EXPECT_NE(bytes.find(expected_b, at_a + expected_a.size()), std::string::npos);
}

TEST(Minimodem, WeDecodeWhatItSends) {
  // minimodem sends bytes back to back, so the break is approximated by characters: 0x00 0x00
  // (mostly SPACE) then 0xFF 0xFF (mostly MARK), then the frame.
  const Frame frame = MakeFrame({0x10, 0x20, 0x30, 0x40}, CrcVariant::kCcittFalse);
  std::string bytes = "\\000\\000\\377\\377";  // octal: POSIX printf has no \x
  char octal[8];
  for (std::uint8_t b : frame) {
    std::snprintf(octal, sizeof octal, "\\%03o", b);
    bytes += octal;
  }
  const std::string wav = TempPath("theirs.wav");
  Capture("printf '" + bytes + "' | minimodem --tx -f " + wav + " --mark 2300 --space 3700 -R 48000 300");
  const std::string json = Capture(std::string(NAVA_DECODE_PATH) + " " + wav);
  std::remove(wav.c_str());
  EXPECT_NE(json.find("\"kind\": \"packet\", \"noise\": \"none\", \"data\": \"10203040\""), std::string::npos) << json;
}

}  // namespace
}  // namespace nava_modem
