#pragma once
// Registration of the subcommands. Each add_*_command defines its options on `app` and stores
// what to run in `commands`; main runs it after parsing, inside its one try/catch.
#include <CLI/CLI.hpp>
#include <functional>

namespace irad::apps {

struct Commands {
  std::function<int()> selected;
  int run() const { return selected ? selected() : 1; }
};

void add_render_command(CLI::App& app, Commands& commands);
void add_compare_command(CLI::App& app, Commands& commands);
void add_scene_command(CLI::App& app, Commands& commands);
void add_bench_command(CLI::App& app, Commands& commands);
void add_convert_command(CLI::App& app, Commands& commands);
void add_walkthrough_command(CLI::App& app, Commands& commands);
void add_merge_command(CLI::App& app, Commands& commands);

} // namespace irad::apps
