// A downstream program: reads a model through the installed HIPAIR package.
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  try {
    hipair::Model model = hipair::read_model_file(argv[1]);
    std::cout << "model: " << model.name << "\nparts: " << model.parts.size() << "\n";
    return 0;
  } catch (const hipair::Error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
