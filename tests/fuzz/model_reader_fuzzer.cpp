// libFuzzer target: any byte string given to the model reader either yields a model or a
// hipair::Error. Anything else escaping (another exception, a crash, undefined behaviour,
// a leak, a hang) is a bug. Built and run by run_fuzz.sh.
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    hipair::Model model = hipair::read_model(text, "<fuzz>");
    // Touch the result so the reader's invariants are exercised.
    for (const hipair::Part& part : model.parts)
      for (const hipair::Loop& loop : part.loops)
        for (std::size_t i = 0; i < loop.edges.size(); ++i)
          if (!(loop.edges[i].target == loop.edges[(i + 1) % loop.edges.size()].source)) __builtin_trap();
  } catch (const hipair::Error&) {
  }
  return 0;
}
