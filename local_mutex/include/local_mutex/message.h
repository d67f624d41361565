#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace local_mutex {

// The two messages of the thesis's Figure 7.1. The wire values are ASCII letters so that a hex
// dump of the air reads naturally, and so that other 4-byte traffic (a wanderer's 'W' beacon)
// is recognised as foreign and treated as noise.
enum class MessageType : std::uint8_t { kRequest = 'R', kLock = 'L' };
const char* MessageTypeName(MessageType t);

// Lamport times travel as 16 bits; they wrap, and are compared with serial-number arithmetic
// (RFC 1982), which is right as long as two robots that hear each other are within 32767 events
// of each other.
using LamportTime = std::uint16_t;

// True when `a` is later than `b` on the wrapping 16-bit clock.
bool LamportAfter(LamportTime a, LamportTime b);

// One 4-byte packet: robot id, type, Lamport time (high byte first).
struct Message {
  std::uint8_t robot_id = 0;
  MessageType type = MessageType::kRequest;
  LamportTime time = 0;

  bool operator==(const Message& o) const {
    return robot_id == o.robot_id && type == o.type && time == o.time;
  }
};
constexpr std::size_t kMessageBytes = 4;

std::vector<std::uint8_t> Encode(const Message& m);
// nullopt for anything that is not one of our packets: a wrong length or an unknown type.
std::optional<Message> Decode(const std::vector<std::uint8_t>& bytes);
// "(R, 0, 11)": type letter, time, robot id, as the thesis's figures label messages.
std::string Describe(const Message& m);

// A request's place in the total order: earlier time first, then the smaller robot id.
struct RequestTuple {
  LamportTime time = 0;
  std::uint8_t robot_id = 0;
};
// True when `a` comes before `b` (has priority over it).
bool Precedes(const RequestTuple& a, const RequestTuple& b);

}  // namespace local_mutex
