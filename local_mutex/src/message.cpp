#include "local_mutex/message.h"

#include <cstdio>

namespace local_mutex {

const char* MessageTypeName(MessageType t) {
  switch (t) {
    case MessageType::kRequest:
      return "request";
    case MessageType::kLock:
      return "lock";
  }
  return "?";
}

bool LamportAfter(LamportTime a, LamportTime b) {
  return static_cast<std::int16_t>(static_cast<LamportTime>(a - b)) > 0;
}

std::vector<std::uint8_t> Encode(const Message& m) {
  return {m.robot_id, static_cast<std::uint8_t>(m.type), static_cast<std::uint8_t>(m.time >> 8),
          static_cast<std::uint8_t>(m.time & 0xff)};
}

std::optional<Message> Decode(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() != kMessageBytes) return std::nullopt;
  const auto type = static_cast<MessageType>(bytes[1]);
  if (type != MessageType::kRequest && type != MessageType::kLock) return std::nullopt;
  Message m;
  m.robot_id = bytes[0];
  m.type = type;
  m.time = static_cast<LamportTime>((bytes[2] << 8) | bytes[3]);
  return m;
}

std::string Describe(const Message& m) {
  char text[32];
  std::snprintf(text, sizeof text, "(%c, %u, %u)", static_cast<char>(m.type), m.time, m.robot_id);
  return text;
}

bool Precedes(const RequestTuple& a, const RequestTuple& b) {
  if (a.time != b.time) return LamportAfter(b.time, a.time);
  return a.robot_id < b.robot_id;
}

}  // namespace local_mutex
