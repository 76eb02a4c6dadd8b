// Reads a model and prints its parts, their motions and any value the reader had to round.
//   example_print_model examples/models/geneva.json
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: example_print_model MODEL.json\n";
    return 64;
  }
  try {
    const hipair::Model model = hipair::read_model_file(argv[1]);
    std::cout << model.name << ": " << model.parts.size() << " parts, "
              << model.parameters.size() << " parameters\n";
    for (const hipair::Part& part : model.parts) {
      std::size_t edges = 0;
      for (const hipair::Loop& loop : part.loops) edges += loop.edges.size();
      std::cout << "  " << part.name << ": " << part.loops.size() << " loops, " << edges
                << " edges, " << part.motion.degrees_of_freedom() << " degree(s) of freedom\n";
    }
    for (const hipair::Rounding& rounding : model.roundings)
      std::cout << "  rounded " << rounding.pointer << " (" << rounding.expression << ") to "
                << hipair::to_decimal_string(rounding.value) << ", error <= "
                << hipair::to_decimal_string(rounding.bound, 3) << "\n";
    return 0;
  } catch (const hipair::Error& error) {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
}
