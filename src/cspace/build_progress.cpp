// A C-space build's progress reports (include/hipair/cspace.hpp: CSpaceBuildProgress): the
// text of each report and the terminal's reporter `hipair` passes when stderr is a terminal.
#include <hipair/cspace.hpp>

#include "core/console_text.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <string>

namespace hipair {

std::string CSpaceBuildProgress::text() const {
  // names over 200 bytes cut as on every console line (core/console_text.hpp): a 1 MB part name
  // was redrawn whole on every report
  const std::string pair = "hipair: " + console::shown_name(std::string(first_part)) + ":" +
                           console::shown_name(std::string(second_part)) + " ";
  switch (stage) {
    case Stage::chart:
      return pair + (tiles ? "tile " : "chart ") + std::to_string(chart) + "/" + std::to_string(charts);
    case Stage::classification:
      return pair + "classifying chart " + std::to_string(chart) + "/" + std::to_string(charts) + ": " +
             std::to_string(100 * done / std::max<std::size_t>(total, 1)) + "%" +
             (coefficient_bits > 300 ? " (exact signs, coefficients of up to " + std::to_string(coefficient_bits) +
                                           " bits)"
                                     : "");
    case Stage::done:
      break;
  }
  return {};
}

CSpaceProgress stderr_progress() {
  using Clock = std::chrono::steady_clock;
  struct State {
    Clock::time_point last_shown = Clock::now() - std::chrono::seconds(1);
    std::size_t shown = 0;   // the width of the last classification line shown
  };
  auto state = std::make_shared<State>();
  return [state](const CSpaceBuildProgress& report) {
    switch (report.stage) {
      case CSpaceBuildProgress::Stage::chart:
        std::cerr << "\r" << report.text() << std::flush;
        if (report.chart == report.charts) std::cerr << "\n";
        return;
      case CSpaceBuildProgress::Stage::classification: {
        if (Clock::now() - state->last_shown < std::chrono::milliseconds(250)) return;
        state->last_shown = Clock::now();
        const std::string line = report.text();
        std::cerr << "\r" << line << std::string(state->shown > line.size() ? state->shown - line.size() : 0, ' ')
                  << std::flush;
        state->shown = std::max(state->shown, line.size());
        return;
      }
      case CSpaceBuildProgress::Stage::done:
        // the classification line is wiped; the next build starts afresh
        if (state->shown) std::cerr << "\r" << std::string(state->shown, ' ') << "\r" << std::flush;
        *state = State{};
        return;
    }
  };
}

}  // namespace hipair
