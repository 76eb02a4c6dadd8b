// Where the unit tests find the project's files (the examples, the test data, the source tree).
//
// The paths are defined in one generated translation unit (test_paths.cpp.in, configured into the
// build directory), not as compile definitions of every test: a checkout in another directory
// then changes that one unit only, and the test units' objects stay shareable through ccache.
#pragma once

namespace hipair::test {

// The source tree's root (the directory holding CMakeLists.txt, docs/, examples/).
const char* source_dir();
// tests/data of the source tree.
const char* test_data_dir();
// examples/models of the source tree.
const char* examples_dir();

}  // namespace hipair::test

// The names the tests have always used; each is a `const char*` naming a directory.
#define HIPAIR_SOURCE_DIR (::hipair::test::source_dir())
#define HIPAIR_TEST_DATA (::hipair::test::test_data_dir())
#define HIPAIR_EXAMPLES (::hipair::test::examples_dir())
