// The reader's JSON layer: numbers keep their text, duplicate keys are errors, pointers are
// RFC 6901, malformed input names its line and column; and the content hash is SHA-256.
#include "core/sha256.hpp"
#include "io/atomic_file.hpp"
#include "model/json_document.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace {

using hipair::model_detail::JsonValue;
using hipair::model_detail::parse_json;

std::string error_of(const std::string& text, std::string* pointer = nullptr) {
  try {
    parse_json(text);
  } catch (const hipair::ModelError& error) {
    if (pointer) *pointer = error.pointer();
    return error.what();
  }
  ADD_FAILURE() << "parsed: " << text;
  return "";
}

TEST(JsonDocument, NumbersKeepTheirTextBeyondDoublePrecision) {
  JsonValue root = parse_json(R"({"a": [9007199254740993, 0.1, 46.683, 1e-30, -0, 123456789012345678901234567890, -5]})");
  const JsonValue& a = *root.find("a");
  ASSERT_EQ(a.items.size(), 7u);
  EXPECT_EQ(a.items[0].text, "9007199254740993");
  EXPECT_EQ(a.items[1].text, "0.1");
  EXPECT_EQ(a.items[2].text, "46.683");
  EXPECT_EQ(a.items[3].text, "1e-30");
  EXPECT_EQ(a.items[5].text, "123456789012345678901234567890");
  EXPECT_EQ(a.items[6].text, "-5");
  EXPECT_EQ(hipair::parse_rational(a.items[4].text), 0);
}

TEST(JsonDocument, PointersFollowRfc6901) {
  JsonValue root = parse_json(R"({"parts": [{"a/b": {"c~d": true}}]})");
  const JsonValue& inner = *root.find("parts")->items[0].find("a/b")->find("c~d");
  EXPECT_EQ(inner.pointer, "/parts/0/a~1b/c~0d");
  EXPECT_TRUE(inner.is_boolean());
  EXPECT_EQ(root.pointer, "");
}

TEST(JsonDocument, MembersKeepFileOrder) {
  JsonValue root = parse_json(R"({"z": 1, "a": 2, "m": 3})");
  ASSERT_EQ(root.members.size(), 3u);
  EXPECT_EQ(root.members[0].key, "z");
  EXPECT_EQ(root.members[2].key, "m");
}

TEST(JsonDocument, DuplicateKeysAreErrors) {
  std::string pointer;
  std::string message = error_of(R"({"parts": [{"name": "a", "name": "b"}]})", &pointer);
  EXPECT_EQ(pointer, "/parts/0/name");
  EXPECT_NE(message.find("duplicate key 'name'"), std::string::npos);
}

TEST(JsonDocument, MalformedInputNamesLineAndColumn) {
  EXPECT_NE(error_of("{\n  \"a\": 1,\n  \"b\": ]\n}").find("line 3, column 8"), std::string::npos);
  EXPECT_NE(error_of("{\"a\": [1, 2").find("unexpected end of file"), std::string::npos);
  EXPECT_NE(error_of("").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"a\": NaN}").find("malformed JSON"), std::string::npos);
  // beyond double range is no error (read exactly from its text); beyond the format's limit is,
  // named by the value's pointer
  std::string pointer;
  EXPECT_NE(error_of("{\"a\": 1e5000}", &pointer).find("out of range"), std::string::npos);
  EXPECT_EQ(pointer, "/a");
  EXPECT_NE(error_of("{} {}").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"a\": \"\xff\"}").find("malformed JSON"), std::string::npos);
  EXPECT_EQ(error_of("{\"a\": \"\xff\"}").find('\xff'), std::string::npos) << "raw bytes in the message";
  std::string deep(200, '[');
  EXPECT_NE(error_of(deep).find("nested too deeply"), std::string::npos);
}

// Session 29 (hunt29): the parser's lexer took a NUL byte for the end of the input, so a whole
// document followed by a NUL and anything at all (a model, or a certificate for hipair-verify)
// was accepted. Every example model and every certificate of the corpus, with a NUL inserted at
// a random offset or appended before random bytes, is malformed JSON naming the offset.
TEST(JsonDocument, ANulByteAnywhereIsMalformed) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const fs::path& dir : {fs::path(HIPAIR_EXAMPLES), fs::path(HIPAIR_TEST_DATA) / "certificates"})
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 60u);
  std::mt19937_64 random(29);
  const std::string tails[] = {"", "x", "{}", "\n{\"hipair\": 1}", "]]]", std::string(1, '\0')};
  std::size_t cases = 0;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::string text = hipair::io::read_file(file);
    ASSERT_NO_THROW(parse_json(text));
    for (int k = 0; k < 4; ++k) {
      std::string changed = text;
      std::size_t at = k < 2 ? text.size() : static_cast<std::size_t>(random() % (text.size() + 1));
      changed.insert(at, 1, '\0');
      if (k == 1) changed += tails[random() % std::size(tails)];
      EXPECT_NE(error_of(changed).find("NUL byte at offset " + std::to_string(at)), std::string::npos);
      ++cases;
    }
  }
  EXPECT_GE(cases, 240u);
}

TEST(Sha256, KnownVectors) {
  using hipair::detail::sha256_hex;
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // 55, 56 and 64 bytes: the padding boundaries.
  EXPECT_EQ(sha256_hex(std::string(55, 'x')), "d5e285683cd4efc02d021a5c62014694958901005d6f71e89e0989fac77e4072");
  EXPECT_EQ(sha256_hex(std::string(56, 'x')), "04c26261370ee7541549d16dee320c723e3fd14671e66a099afe0a377c16888e");
  EXPECT_EQ(sha256_hex(std::string(64, 'x')), "7ce100971f64e7001e8fe5a51973ecdfe1ced42befe7ee8d5fd6219506b5393c");
}

}  // namespace
