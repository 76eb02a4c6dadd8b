// Exact numbers and atomic output files: the primitives everything else relies on.
#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include "io/atomic_file.hpp"
#include "model/exact_trig.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>
#include <random>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace {

using hipair::Rational;

TEST(ExactDecimal, ValuesADoubleCannotHold) {
  // 2^53 + 1 is the first integer a double cannot represent.
  EXPECT_EQ(hipair::parse_rational("9007199254740993"), Rational("9007199254740993"));
  EXPECT_NE(hipair::parse_rational("9007199254740993"), Rational(9007199254740992.0));
  EXPECT_EQ(hipair::parse_rational("0.1"), Rational(1, 10));
  EXPECT_EQ(hipair::parse_rational("46.683"), Rational(46683, 1000));
  EXPECT_EQ(hipair::parse_rational("-2.4708"), Rational(-6177, 2500));  // canonical form of -24708/10000
  EXPECT_EQ(hipair::parse_rational("1e-30"), Rational(mpz_class(1), mpz_class("1" + std::string(30, '0'))));
  EXPECT_EQ(hipair::parse_rational("1/3") * 3, Rational(1));
  EXPECT_EQ(hipair::parse_rational("2.5E+2"), Rational(250));
}

TEST(ExactDecimal, RejectsNonNumbers) {
  for (const char* text : {"", "abc", "1/0", "nan", "inf", "1e", "--1", "1..2", "0x10"})
    EXPECT_THROW(hipair::parse_rational(text), hipair::NumericError) << text;
}

TEST(ExactDecimal, RoundTripsThroughExactText) {
  Rational value = hipair::parse_rational("46.683");
  EXPECT_EQ(hipair::to_exact_string(value), "46683/1000");
  EXPECT_EQ(hipair::parse_rational(hipair::to_exact_string(value)), value);
  EXPECT_EQ(hipair::to_decimal_string(value, 5), "46.683");
}

TEST(ExactDecimal, ToDoubleRoundsToNearest) {
  // 1/3 rounds down, 2/3 rounds up in binary: both must match the correctly rounded literal.
  EXPECT_EQ(hipair::to_double(Rational(1, 3)), 1.0 / 3.0);
  EXPECT_EQ(hipair::to_double(Rational(2, 3)), 2.0 / 3.0);
  EXPECT_EQ(hipair::to_double(hipair::parse_rational("0.1")), 0.1);
}

TEST(ExactTrig, UnitVectorsLieExactlyOnTheCircle) {
  std::vector<hipair::Rounding> roundings;
  for (int k = -12; k <= 12; ++k) {
    Rational multiple(k, 7);
    hipair::Point u = hipair::model_detail::exact_unit_vector_pi(multiple, "/x", "k pi/7", roundings);
    EXPECT_EQ(u.x * u.x + u.y * u.y, Rational(1)) << k;
    double angle = k * M_PI / 7;
    EXPECT_NEAR(hipair::to_double(u.x), std::cos(angle), 4e-12) << k;
    EXPECT_NEAR(hipair::to_double(u.y), std::sin(angle), 4e-12) << k;
  }
  // Multiples of pi/2 are exact and need no rounding.
  roundings.clear();
  hipair::Point up = hipair::model_detail::exact_unit_vector_pi(Rational(1, 2), "/y", "pi/2", roundings);
  EXPECT_EQ(up, (hipair::Point{Rational(0), Rational(1)}));
  EXPECT_TRUE(roundings.empty());
}

TEST(AtomicFile, FailureLeavesNoFileAndKeepsTheOldOne) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "hipair_atomic_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  hipair::io::write_file_atomically(dir / "a.txt", "first");
  EXPECT_EQ(hipair::io::read_file(dir / "a.txt"), "first");
  hipair::io::write_file_atomically(dir / "a.txt", "second");
  EXPECT_EQ(hipair::io::read_file(dir / "a.txt"), "second");
  EXPECT_THROW(hipair::io::write_file_atomically(dir / "missing" / "b.txt", "x"), hipair::IoError);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

// Session 29 (hunt29): an output path that is a symbolic link, or a chain of them (relative and
// absolute, across directories), is written through: the links stay links and the final target
// gets the content; a path that is (or leads to) a FIFO without a reader is refused with IoError
// and stays a FIFO (before, the rename replaced the link, the FIFO, or as root a device such as
// /dev/full, with a regular file); a symlink loop is refused. Nothing else in the directories changes. Generated
// chains with a fixed seed.
TEST(AtomicFile, LinksAreWrittenThroughAndSpecialFilesRefused) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "hipair_atomic_links_test";
  fs::remove_all(dir);
  std::mt19937 random(29);
  auto listing = [&] {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) names.push_back(entry.path().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  for (int instance = 0; instance < 60; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    fs::create_directories(dir / "a" / "b");
    const fs::path dirs[] = {dir, dir / "a", dir / "a" / "b"};
    const bool fifo = instance % 3 == 2;
    fs::path end = dirs[random() % 3] / (fifo ? "end.fifo" : "end.txt");
    if (fifo)
      ASSERT_EQ(::mkfifo(end.c_str(), 0644), 0);
    else
      hipair::io::write_file_atomically(end, "old");
    // a chain of 0 to 4 links ending at `end`, each in a random directory, relative or absolute
    fs::path head = end;
    const int hops = static_cast<int>(random() % 5);
    for (int h = 0; h < hops; ++h) {
      fs::path link = dirs[random() % 3] / ("link" + std::to_string(h));
      fs::path to = random() % 2 ? head : fs::relative(head, link.parent_path());
      fs::create_symlink(to, link);
      head = link;
    }
    std::vector<std::string> before = listing();
    const std::string content = "content " + std::to_string(instance);
    if (fifo) {
      EXPECT_THROW(hipair::io::write_file_atomically(head, content), hipair::IoError);
      EXPECT_TRUE(fs::is_fifo(fs::symlink_status(end)));
    } else {
      hipair::io::write_file_atomically(head, content);
      EXPECT_EQ(hipair::io::read_file(end), content);
      EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(end)));
    }
    if (hops > 0) EXPECT_TRUE(fs::is_symlink(fs::symlink_status(head)));
    EXPECT_EQ(listing(), before);   // no temporary left, no link replaced
    fs::remove_all(dir);
  }
  fs::create_directories(dir);
  fs::create_symlink("loop-b", dir / "loop-a");
  fs::create_symlink("loop-a", dir / "loop-b");
  EXPECT_THROW(hipair::io::write_file_atomically(dir / "loop-a", "x"), hipair::IoError);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "loop-a")));
  fs::remove_all(dir);
}

// Session 29 (integrator): an existing node that is no regular file is written to, not replaced:
// /dev/null takes the content, /dev/full fails with IoError (no space) and stays a device, a FIFO
// with a reader receives the content whole (the same for 0 to 3 links in front of it), and a
// producer that throws writes nothing to the node.
TEST(AtomicFile, DevicesAndFifosWithAReaderAreWrittenToNotReplaced) {
  namespace fs = std::filesystem;
  if (fs::is_character_file(fs::status("/dev/null"))) {
    EXPECT_NO_THROW(hipair::io::write_file_atomically("/dev/null", "discarded"));
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status("/dev/null")));
  }
  if (fs::is_character_file(fs::status("/dev/full"))) {
    EXPECT_THROW(hipair::io::write_file_atomically("/dev/full", std::string(1 << 16, 'x')), hipair::IoError);
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status("/dev/full")));
  }
  fs::path dir = fs::temp_directory_path() / "hipair_atomic_fifo_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::mt19937 random(2929);
  for (int instance = 0; instance < 12; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    fs::path fifo = dir / ("f" + std::to_string(instance));
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    fs::path head = fifo;
    for (int h = 0, hops = static_cast<int>(random() % 4); h < hops; ++h) {
      fs::path link = dir / ("l" + std::to_string(instance) + "_" + std::to_string(h));
      fs::create_symlink(head.filename(), link);
      head = link;
    }
    // content up to 256 KB: beyond a pipe's buffer, so the writer must wait for the reader
    std::string content(static_cast<std::size_t>(random() % (1 << 18)) + 1, 'a');
    for (char& c : content) c = static_cast<char>('a' + random() % 26);
    std::string received;
    std::thread reader([&] {
      std::ifstream in(fifo, std::ios::binary);   // blocks until the writer opens
      std::ostringstream all;
      all << in.rdbuf();
      received = all.str();
    });
    // the writer's non-blocking open fails while the reader has not opened yet: retry briefly
    bool written = false;
    for (int attempt = 0; attempt < 2000 && !written; ++attempt) {
      try {
        hipair::io::write_file_atomically(head, content);
        written = true;
      } catch (const hipair::IoError&) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    if (!written) {   // unblock the reader before failing
      std::ofstream unblock(fifo);
    }
    reader.join();
    ASSERT_TRUE(written);
    EXPECT_EQ(received, content);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  }
  // a regular file open on a descriptor, written through /dev/fd/N or /proc/self/fd/N (as
  // `--out /dev/stdout > log` does): appended to, the same file (inode) afterwards
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (!fs::exists(prefix)) continue;
    fs::path log = dir / "log.txt";
    fs::remove(log);
    int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, "head ", 5), 5);
    struct stat before {};
    ASSERT_EQ(::stat(log.c_str(), &before), 0);
    hipair::io::write_file_atomically(std::string(prefix) + std::to_string(fd), "tail");
    ASSERT_EQ(::write(fd, " more", 5), 5);
    ::close(fd);
    struct stat after {};
    ASSERT_EQ(::stat(log.c_str(), &after), 0);
    EXPECT_EQ(before.st_ino, after.st_ino) << prefix;
    EXPECT_EQ(hipair::io::read_file(log), "head tail more") << prefix;
  }
  // a producer that throws leaves the node untouched (nothing opened: no reader needed)
  fs::path fifo = dir / "thrown";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_THROW(hipair::io::write_file_atomically(fifo, [](std::ostream&) { throw hipair::IoError("producer"); }),
               hipair::IoError);
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  fs::remove_all(dir);
}

}  // namespace

namespace {

TEST(ExactTrig, SimplestRationalBetween) {
  using hipair::model_detail::simplest_rational_between;
  EXPECT_EQ(simplest_rational_between(Rational(333, 1000), Rational(334, 1000)), Rational(1, 3));
  EXPECT_EQ(simplest_rational_between(hipair::parse_rational("3.14159"), hipair::parse_rational("3.1416")),
            Rational(355, 113));
  EXPECT_EQ(simplest_rational_between(Rational(-1, 2), Rational(1, 3)), Rational(0));
  EXPECT_EQ(simplest_rational_between(hipair::parse_rational("-3.1416"), hipair::parse_rational("-3.14159")),
            Rational(-355, 113));
  EXPECT_EQ(simplest_rational_between(Rational(7, 2), Rational(7, 2)), Rational(7, 2));
  EXPECT_EQ(simplest_rational_between(Rational(5, 2), Rational(4)), Rational(3));
}

TEST(ExactTrig, HalfTangentsStayWithinTheGridBoundWithFewDigits) {
  // tan(pi/8) = sqrt(2) - 1: the simplest rational within 5e-13 has a denominator near 10^6,
  // where the grid value has 10^12.
  Rational near_tangent = hipair::parse_rational("0.41421356237309504880168872");
  Rational t = hipair::model_detail::round_half_tangent(near_tangent);
  Rational error = t - near_tangent;
  EXPECT_LE(abs(error), Rational(mpz_class(1), mpz_class("2000000000000")));
  EXPECT_LT(mpz_sizeinbase(t.get_den_mpz_t(), 10), 9u);
}

}  // namespace
