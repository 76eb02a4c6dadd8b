#include "cli/commands.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <utility>
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
  // The subcommands in the order of the top level's help. When the first argument is exactly a
  // subcommand's name, only that subcommand is registered: CLI11's registration of every
  // subcommand's options was ≈ 1.4 M instructions per process (docs/performance.md, session 59),
  // more than a small pair's whole C-space build, and a subcommand's parse, help and errors read
  // nothing of its siblings (the top level takes one subcommand: a sibling's name after it is an
  // argument of its own either way). `hipair --version` alone registers none (the flag answers
  // before any subcommand is looked for). Anything else first (an option, --help, an unknown or
  // misspelt name, nothing) registers every subcommand, so the top level's help and its errors
  // list them all.
  using Register = void (*)(CLI::App&, hipair::cli::Action&);
  static constexpr std::pair<const char*, Register> subcommands[] = {
      {"validate", hipair::cli::register_validate}, {"show", hipair::cli::register_show},
      {"analyze", hipair::cli::register_analyze},   {"certify", hipair::cli::register_certify},
      {"cspace", hipair::cli::register_cspace},     {"tolerance", hipair::cli::register_tolerance},
      {"simulate", hipair::cli::register_simulate}};
  Register named = nullptr;
  if (argc > 1)
    for (const auto& [name, add] : subcommands)
      if (std::string_view(argv[1]) == name) named = add;
  if (named)
    named(app, action);
  else if (!(argc == 2 && std::string_view(argv[1]) == "--version"))
    for (const auto& [name, add] : subcommands) add(app, action);
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
