#include "core/console_text.hpp"

#include <string_view>

namespace hipair::console {

std::string shown_name(const std::string& name) {
  constexpr std::size_t limit = 200;
  if (name.size() <= limit) return name;
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;   // not inside a UTF-8 sequence
  return name.substr(0, cut) + "... (" + std::to_string(name.size()) + " characters)";
}

std::string shortened_message(const std::string& message) {
  std::string out;
  std::size_t start = 0;
  while (start <= message.size()) {
    std::size_t end = message.find_first_of(" \n", start);
    if (end == std::string::npos) end = message.size();
    const std::string_view word = std::string_view(message).substr(start, end - start);
    if (word.size() > 200) {
      std::size_t cut = 60;
      while (cut > 0 && (static_cast<unsigned char>(word[cut]) & 0xC0) == 0x80) --cut;
      out += std::string(word.substr(0, cut)) + "... (" + std::to_string(word.size()) + " characters)";
    } else {
      out += word;
    }
    if (end < message.size()) out += message[end];
    start = end + 1;
  }
  return out;
}

}  // namespace hipair::console
