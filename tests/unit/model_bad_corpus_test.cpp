// Every model in tests/data/bad is rejected with exactly the JSON pointer and a message
// fragment listed in tests/data/bad/EXPECTED.txt (regenerate with make_bad_models.py).
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "test_paths.hpp"

namespace {

namespace fs = std::filesystem;

struct BadCase {
  std::string file;
  std::string pointer;
  std::string fragment;
};

const fs::path bad_directory = fs::path(HIPAIR_TEST_DATA) / "bad";

std::vector<BadCase> load_cases() {
  std::vector<BadCase> cases;
  std::ifstream in(bad_directory / "EXPECTED.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    BadCase c;
    std::getline(fields, c.file, '\t');
    std::getline(fields, c.pointer, '\t');
    std::getline(fields, c.fragment, '\t');
    if (c.pointer == "-") c.pointer.clear();
    cases.push_back(c);
  }
  return cases;
}

class BadModel : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadModel, IsRejectedWithItsPointerAndReason) {
  const BadCase& c = GetParam();
  try {
    hipair::read_model_file(bad_directory / c.file);
    ADD_FAILURE() << c.file << " was accepted";
  } catch (const hipair::ModelError& error) {
    std::string message = error.what();
    EXPECT_EQ(error.pointer(), c.pointer) << message;
    EXPECT_NE(message.find(c.fragment), std::string::npos) << "message: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "the message must be one line";
    if (!c.pointer.empty()) {
      EXPECT_EQ(message.rfind(c.pointer + ": ", 0), 0u) << message;
    }
  }
}

std::string case_name(const ::testing::TestParamInfo<BadCase>& info) {
  std::string name = info.param.file.substr(0, info.param.file.find('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadModel, ::testing::ValuesIn(load_cases()), case_name);

TEST(BadModelCorpus, EveryFileIsListedAndTheCorpusIsLarge) {
  std::set<std::string> listed;
  for (const BadCase& c : load_cases()) listed.insert(c.file);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(bad_directory)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " has no expectation";
  }
  EXPECT_EQ(files, listed.size());
  EXPECT_GE(files, 35u);
}

TEST(GoodModelCorpus, EveryGoodModelAndExampleIsAccepted) {
  std::size_t read = 0;
  for (const fs::path& directory : {fs::path(HIPAIR_TEST_DATA) / "good", fs::path(HIPAIR_EXAMPLES)}) {
    if (!fs::exists(directory)) continue;
    for (const auto& entry : fs::directory_iterator(directory)) {
      if (entry.path().extension() != ".json") continue;
      try {
        hipair::read_model_file(entry.path());
      } catch (const hipair::Error& error) {
        ADD_FAILURE() << entry.path() << ": " << error.what();
      }
      ++read;
    }
  }
  EXPECT_GE(read, 5u);
}

}  // namespace
