// input/message.h: error text that stays on one short line whatever the input holds.

#include "input/message.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using nlohmann::json;

TEST(Message, BriefShowsValuesAsWrittenAndCutsLongOnes) {
  EXPECT_EQ(input::brief(json(-1)), "-1");
  EXPECT_EQ(input::brief(json(0.0)), "0.0");
  EXPECT_EQ(input::brief(json("big")), "\"big\"");
  EXPECT_EQ(input::brief(json::parse(R"([1,{"a":[true,null]}])")), R"([1,{"a":[true,null]}])");
  json long_array = json::array();
  for (int i = 0; i < 1000000; ++i) long_array.push_back(i);
  EXPECT_EQ(input::brief(long_array), "[0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,...");
  EXPECT_EQ(input::brief(json(std::string(100000, 'x')), 10), "\"xxxxxx...");
  // Deep values are not recursed into past a few levels.
  json deep = json::array();
  for (int i = 0; i < 1000; ++i) deep = json::array({deep});
  EXPECT_EQ(input::brief(deep), "[[[[[[[[[...]]]]]]]]]");
  // Invalid UTF-8 (a string built in memory) is replaced, not thrown.
  EXPECT_NO_THROW(input::brief(json(std::string("\xff\xfe"))));
}

TEST(Message, OneLineCutsAtACharacterBoundary) {
  EXPECT_EQ(input::one_line("a\nb\rc\td"), "a b c d");
  const std::string long_text(300, 'y');
  const std::string cut = input::one_line(long_text);
  EXPECT_EQ(cut.size(), input::kMaxMessageChars);
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  // "é" is two bytes: never cut between them.
  std::string accents;
  for (int i = 0; i < 150; ++i) accents += "\xc3\xa9";
  const std::string a = input::one_line(accents);
  EXPECT_LE(a.size(), input::kMaxMessageChars);
  EXPECT_EQ((a.size() - 3) % 2, 0u);
}

TEST(Message, PointerTokensAreEscaped) { EXPECT_EQ(input::pointer_token("a/b~c"), "a~1b~0c"); }

}  // namespace
