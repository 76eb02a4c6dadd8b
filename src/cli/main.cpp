#include "cli/commands.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  // out of memory inside GMP (and MPFR, CGAL) becomes std::bad_alloc: exit 4, not an abort
  hipair::use_throwing_gmp_allocation();
  CLI::App app{
      "HIPAIR: exact contact analysis of planar mechanisms from configuration spaces.\n"
      "Models are JSON files (see docs/model-format.md)."};
  app.set_version_flag("--version", "hipair 0.1.0");
  app.require_subcommand(1);
  hipair::cli::Action action;
  hipair::cli::register_validate(app, action);
  hipair::cli::register_show(app, action);
  hipair::cli::register_analyze(app, action);
  hipair::cli::register_certify(app, action);
  hipair::cli::register_cspace(app, action);
  hipair::cli::register_tolerance(app, action);
  hipair::cli::register_simulate(app, action);
  // a usage error is one line, like every other error: "hipair: error: <CLI11's message> (see
  // 'hipair SUBCOMMAND --help')" (CLI11's default adds a second line, "Run with --help ...")
  // an argument before the subcommand that nothing takes (`hipair --bogus validate M`) is the
  // top level's: its help is 'hipair --help', not the subcommand's (session 44)
  bool top_level_extra = false;
  app.failure_message([&top_level_extra](const CLI::App* top, const CLI::Error& e) {
    std::string command = "hipair";
    if (!top_level_extra)
      for (const CLI::App* sub : top->get_subcommands()) command += " " + sub->get_name();
    return "hipair: error: " + std::string(e.what()) + " (see '" + command + " --help')\n";
  });
  // a parse error's message with its overlong words cut (a 100 000-digit value is not echoed)
  auto exit_with = [&app](const CLI::ParseError& e) {
    const std::string message = hipair::cli::shortened_message(e.what());
    if (e.get_exit_code() == 0 || e.get_name() == "RuntimeError" || message == e.what()) return app.exit(e);
    return app.exit(CLI::ParseError(message, e.get_exit_code()));
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::RequiredError& e) {
    // CLI11 checks "a subcommand is required" before the unparsed arguments: `hipair --bogus`
    // and `hipair bogus` said "A subcommand is required" and named neither (session 43)
    const std::vector<std::string> unknown = app.remaining();
    if (!app.get_subcommands().empty() && !unknown.empty()) {
      // `hipair --bogus show M` (no --svg): the argument before the subcommand first, with the
      // top level's help, as without the subcommand's missing option (session 44)
      top_level_extra = true;
      std::string list;
      for (const std::string& word : unknown) list += " " + word;
      return exit_with(CLI::ExtrasError(std::string("The following argument") + (unknown.size() > 1 ? "s were" : " was") +
                                            " not expected:" + list,
                                        CLI::ExitCodes::ExtrasError));
    }
    if (!app.get_subcommands().empty() || unknown.empty()) return exit_with(e);
    if (unknown.front().rfind("-", 0) == 0)
      return exit_with(CLI::ExtrasError("The following argument was not expected: " + unknown.front(),
                                        CLI::ExitCodes::ExtrasError));
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    return exit_with(CLI::ExtrasError("unknown subcommand '" + unknown.front() + "' (the subcommands: " + names + ")",
                                      CLI::ExitCodes::ExtrasError));
  } catch (const CLI::ExtrasError& e) {
    top_level_extra = !app.remaining(false).empty();   // CLI11 checks the top level's extras first
    return exit_with(e);
  } catch (const CLI::ParseError& e) {
    return exit_with(e);
  }
  try {
    return action ? action() : 0;
  } catch (const CLI::ParseError& e) {   // a usage error found once the options are read (OnceEach)
    return exit_with(e);
  } catch (const hipair::ModelError& e) {
    std::cerr << "hipair: error: " << hipair::cli::shortened_message(e.what()) << "\n";
    return 2;
  } catch (const hipair::Error& e) {
    std::cerr << "hipair: error: " << hipair::cli::shortened_message(e.what()) << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "hipair: error: out of memory (the computation needs more memory than the process may use)\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "hipair: internal error: " << e.what() << "\n";
    return 5;
  }
}
