// `dispcon`: the command line over .dcl files (cli.md) and FreeCAD documents (fcstd.cpp). Parsing
// arguments and printing only; all the work is the engine's. Each subcommand lives in its own file
// (commands.hpp).
#include <iostream>
#include <stdexcept>
#include <vector>

#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace dispcon::cli;
  // FreeCAD documents go to FreeCAD (fcstd.cpp).
  if (is_fcstd_call(argc, argv)) return run_fcstd(argc, argv);
  CLI::App app{
      "dispcon: mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"};
  app.require_subcommand(1);
  const std::vector<Subcommand> subcommands = {add_assemble(app), add_drag(app), add_animate(app),
                                               add_check(app), add_sweep(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }
  try {
    for (const Subcommand& s : subcommands) {
      if (s.app->parsed()) return s.run();
    }
  } catch (const CLI::ValidationError& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  }
  return kBadInput;
}
