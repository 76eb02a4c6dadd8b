// Where the benchmark programs find the examples and the `hipair` program.
//
// The paths are defined in one generated translation unit (tests/perf/CMakeLists.txt writes it into
// the build directory), not as compile definitions of every benchmark unit: until session 75 each
// unit had the checkout's path compiled in (-DHIPAIR_EXAMPLES="/.../examples/models"), so ccache
// missed all of them in every fresh clone (CI's test job compiled the 12 units cold, ~89 s CPU;
// docs/performance.md "Session 74 (ci74)" and "Session 75 (ci75)"). As tests/unit/test_paths.hpp.
#pragma once

namespace hipair::bench {

// examples/models of the source tree.
const char* examples_dir();
// The `hipair` program of this build.
const char* cli_path();

}  // namespace hipair::bench

// The names the benchmarks have always used; each is a `const char*`.
#define HIPAIR_EXAMPLES (::hipair::bench::examples_dir())
#define HIPAIR_CLI (::hipair::bench::cli_path())
