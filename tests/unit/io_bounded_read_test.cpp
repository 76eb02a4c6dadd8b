// Reading a file without end (session 33): `hipair cspace /dev/zero` and `hipair-verify /dev/zero
// MODEL` read until memory ran out (a hang on a machine with swap). io::read_file stops after its
// limit (1 GiB by default) and read_model_file after 256 MiB, with an IoError naming the path;
// regular files of every size around the read block's come back byte for byte.
#include "io/atomic_file.hpp"

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

}  // namespace
}  // namespace hipair
