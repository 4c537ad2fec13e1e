// irad: instant radiosity from the command line. Each subcommand lives in its own file; errors
// from anywhere arrive here as exceptions, are printed on one line, and exit with code 1.
#include "apps/commands.h"
#include "core/error.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  CLI::App app{"irad: diffuse global illumination with Keller's Instant Radiosity"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "irad 0.1");
  irad::apps::Commands commands;
  irad::apps::add_render_command(app, commands);
  irad::apps::add_compare_command(app, commands);
  irad::apps::add_scene_command(app, commands);
  irad::apps::add_bench_command(app, commands);
  irad::apps::add_convert_command(app, commands);
  irad::apps::add_walkthrough_command(app, commands);
  try {
    app.parse(argc, argv);
    return commands.run();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "irad: error: %s (see irad --help)\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irad: error: %s\n", e.what());
    return 1;
  }
}
