// Reading a file without end (session 33): `hipair cspace /dev/zero` and `hipair-verify /dev/zero
// MODEL` read until memory ran out (a hang on a machine with swap). io::read_file stops after its
// limit (1 GiB by default) and read_model_file after 256 MiB, with an IoError naming the path;
// regular files of every size around the read block's come back byte for byte.
#include "io/atomic_file.hpp"
#include "core/model_equal.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>
#include <string>

namespace hipair {
namespace {

TEST(IoBoundedRead, DeviceWithoutEndIsRefusedAtTheLimit) {
  if (!std::filesystem::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero";
  try {
    io::read_file("/dev/zero", std::size_t{1} << 20);
    FAIL() << "read /dev/zero whole";
  } catch (const IoError& error) {
    EXPECT_NE(std::string(error.what()).find("'/dev/zero': it is larger than 1048576 bytes"), std::string::npos) << error.what();
  }
  try {
    read_model_file("/dev/zero");
    FAIL() << "read /dev/zero as a model";
  } catch (const IoError& error) {
    EXPECT_NE(std::string(error.what()).find("'/dev/zero': it is larger than 256 MiB"), std::string::npos) << error.what();
  }
}

TEST(IoBoundedRead, RegularFilesComeBackWhole) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("hipair-bounded-read-" + std::to_string(::getpid()));
  std::mt19937_64 random(33);
  for (std::size_t size : {std::size_t{0}, std::size_t{1}, std::size_t{65535}, std::size_t{65536}, std::size_t{65537},
                           std::size_t{200000}}) {
    std::string text(size, '\0');
    for (char& c : text) c = static_cast<char>(random() & 0xff);
    {
      std::ofstream out(path, std::ios::binary);
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
    }
    EXPECT_EQ(io::read_file(path), text) << size;
    if (size > 0) {
      EXPECT_EQ(io::read_file(path, size), text) << size;   // exactly at the limit
      EXPECT_THROW(io::read_file(path, size - 1), IoError) << size;
    }
  }
  std::filesystem::remove(path);
}

// read_model_file reads in blocks of 1 MiB that it does not zero first (session 58): a model
// file of every size around the block's (whitespace between the JSON values pads it; the model
// itself is small) reads as its text does, and a byte past the JSON's end is an error, not
// something left from an earlier block.
TEST(IoBoundedRead, ModelFilesAcrossReadBlocksReadAsTheirText) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("hipair-model-blocks-" + std::to_string(::getpid()));
  const std::string head = R"({ "hipair": 1, "name": "blocks", "parts": [ { "name": "a", "motion": { "translation": { "direction": [1, 0] } },
    "loops": [ { "start": [0, 0], "edges": [ { "line_to": [4, 0] }, { "line_to": [1, 3] }, { "line_to": [0, 0] } ] } ] },)";
  const std::string tail = R"( { "name": "b", "motion": "fixed",
    "loops": [ { "start": [10, 10], "edges": [ { "line_to": ["12", "10"] }, { "line_to": ["12", "25/2"] }, { "line_to": [10, 10] } ] } ] } ] })";
  const std::size_t block = std::size_t{1} << 20;
  for (std::size_t size : {block - 1, block, block + 1, 2 * block + 7, 3 * block}) {
    const std::string text = head + std::string(size - head.size() - tail.size(), ' ') + tail;
    ASSERT_EQ(text.size(), size);
    {
      std::ofstream out(path, std::ios::binary);
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
    }
    // (the reference reads the same text under the same name: a model keeps its source's
    // name and digest)
    EXPECT_TRUE(same_model(read_model_file(path), read_model(text, path.string()))) << size;
    {
      std::ofstream out(path, std::ios::binary | std::ios::app);
      out << 'x';   // one byte past the model, in the last block read
    }
    EXPECT_THROW(read_model_file(path), Error) << size;
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace hipair
