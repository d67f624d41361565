#include "local_mutex/message.h"

#include <gtest/gtest.h>

namespace local_mutex {
namespace {

TEST(Message, EncodesIdTypeAndTimeHighByteFirst) {
  const Message m{11, MessageType::kRequest, 0x0102};
  EXPECT_EQ(Encode(m), std::vector<std::uint8_t>({11, 'R', 0x01, 0x02}));
  EXPECT_EQ(Encode({212, MessageType::kLock, 7}), std::vector<std::uint8_t>({212, 'L', 0, 7}));
}

TEST(Message, DecodesWhatItEncodes) {
  for (const Message m : {Message{1, MessageType::kRequest, 0}, Message{255, MessageType::kLock, 65535},
                          Message{30, MessageType::kRequest, 300}}) {
    const auto back = Decode(Encode(m));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, m);
  }
}

TEST(Message, RejectsWrongLengthsAndUnknownTypes) {
  EXPECT_FALSE(Decode({}));
  EXPECT_FALSE(Decode({11, 'R', 0}));
  EXPECT_FALSE(Decode({11, 'R', 0, 0, 0}));
  EXPECT_FALSE(Decode({11, 'W', 0, 0}));  // a wanderer's beacon
  EXPECT_FALSE(Decode({11, 0, 0, 0}));
}

TEST(Message, DescribesLikeTheThesisFigures) {
  EXPECT_EQ(Describe({11, MessageType::kRequest, 0}), "(R, 0, 11)");
  EXPECT_EQ(Describe({30, MessageType::kLock, 12}), "(L, 12, 30)");
}

TEST(Lamport, LaterOnAWrappingClock) {
  EXPECT_TRUE(LamportAfter(5, 4));
  EXPECT_FALSE(LamportAfter(4, 5));
  EXPECT_FALSE(LamportAfter(4, 4));
  EXPECT_TRUE(LamportAfter(2, 65534));  // across the wrap
  EXPECT_FALSE(LamportAfter(65534, 2));
}

TEST(RequestTuple, OrdersByTimeThenId) {
  EXPECT_TRUE(Precedes({0, 11}, {0, 30}));
  EXPECT_FALSE(Precedes({0, 30}, {0, 11}));
  EXPECT_TRUE(Precedes({0, 30}, {2, 11}));
  EXPECT_TRUE(Precedes({0, 30}, {2, 212}));
  EXPECT_FALSE(Precedes({2, 212}, {0, 30}));
  EXPECT_FALSE(Precedes({3, 7}, {3, 7}));  // strict
  EXPECT_TRUE(Precedes({65535, 200}, {0, 1}));  // 0 comes after 65535
}

}  // namespace
}  // namespace local_mutex
