// input::parse_json: the document nlohmann's parser would build, plus a nesting limit enforced
// while parsing, duplicate keys refused, and every error naming its JSON pointer and line.

#include "input/json_read.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using nlohmann::json;

std::string json_error(const std::string& text, std::size_t depth = input::kMaxJsonDepth) {
  try {
    input::parse_json(text, depth);
  } catch (const input::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(JsonRead, BuildsTheSameDocumentAsNlohmann) {
  for (const char* text : {R"({"a": [1, 2.5, -3, "x", true, null, {"b": {}}], "c": [], "d": 18446744073709551615})",
                           "[]", "0", "\"s\"", R"([[[[{"k": [[]]}]]]])"})
    EXPECT_EQ(input::parse_json(text), json::parse(text)) << text;
}

TEST(JsonRead, NestingIsLimitedWhileParsing) {
  EXPECT_NO_THROW(input::parse_json(std::string(64, '[') + std::string(64, ']')));
  EXPECT_EQ(json_error(std::string(65, '[') + std::string(65, ']')),
            "/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...: nested deeper than 64 "
            "levels at line 1, column 65");
  // A million levels cost no more than 65: the parse stops there.
  EXPECT_NE(json_error(std::string(1000000, '[')).find("nested deeper than 64 levels"), std::string::npos);
  EXPECT_EQ(json_error(R"({"a": {"b": [[1]]}})", 3), "/a/b/0: nested deeper than 3 levels at line 1, column 14");
}

TEST(JsonRead, DuplicateKeysAreRefusedWithTheirPath) {
  EXPECT_EQ(json_error("{\"a\": 1,\n \"b\": {\"c\": 2, \"c\": 3}}"),
            "/b/c: duplicate key at line 2, column 18 (each key may appear only once in an object)");
  EXPECT_EQ(json_error(R"([{}, {"x": 1, "x": 1}])"),
            "/1/x: duplicate key at line 1, column 17 (each key may appear only once in an object)");
  EXPECT_NO_THROW(input::parse_json(R"([{"x": 1}, {"x": 1}])"));  // the same key in two objects
}

TEST(JsonRead, SyntaxErrorsNameThePointerAndLine) {
  EXPECT_EQ(json_error("[1, 2"),
            "/2: invalid JSON: parse error at line 1, column 6: syntax error while parsing array - unexpected end of "
            "input; expected ']'");
  EXPECT_EQ(json_error(""),
            "(root): invalid JSON: parse error at line 1, column 1: syntax error while parsing value - unexpected end "
            "of input; expected '[', '{', or a literal");
  EXPECT_EQ(json_error(R"({"a": [1, NaN]})"), "/a/1: must be a finite number, got NaN");
  EXPECT_EQ(json_error(R"({"a": -Infinity})"), "/a: must be a finite number, got -Infinity");
  EXPECT_EQ(json_error(R"({"a": 1e999})"), "/a: number \"1e999\" is beyond double range (magnitude at most 1.8e308) at "
                                         "line 1, column 7");
  EXPECT_EQ(json_error("{\"a\": 1} x"), "(root): invalid JSON: parse error at line 1, column 10: syntax error while "
                                      "parsing value - invalid literal; last read: '1} x'; expected end of input");
}

TEST(JsonRead, LongPointersAreCut) {
  const std::string key(500, 'k');
  const std::string got = json_error("{\"" + key + "\": 1, \"" + key + "\": 2}");
  EXPECT_EQ(got.rfind("/kkkk", 0), 0u) << got;
  EXPECT_LT(got.size(), 200u) << got;
}

}  // namespace
