// tacta-view SCENE: the interactive window. Runs the scene in realtime on a worker thread and
// draws it with the shared renderer; a Dear ImGui panel
// plays, pauses and steps it, swaps the model of any body and edits its parameters, drives the
// stylus with the mouse (--mouse; C held cuts with a blade) and plots force and tick time.
// Exit 0 ok, 1 a run-time failure, 2 bad input.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "tacta/error.hpp"
#include "tacta/log.hpp"
#include "viewer.hpp"

int main(int argc, char** argv) {
  CLI::App app{"tacta-view: interactive window for Tacta scenes"};
  tacta::view::ViewerOptions options;
  std::string size = "1280x800";
  app.add_option("scene", options.scene, "Scene file (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("--set", options.overrides,
                 "Override a scene key: key.path=value (bodies.*.model=tensor_mass)");
  app.add_flag("--mouse", options.mouse,
               "Replace the scene's devices by the mouse (plugin 'mouse'), keeping their tools");
  app.add_flag("--paused", options.paused,
               "Start paused, showing the state before the first tick");
  app.add_option("--quit-after", options.quit_after_s,
                 "Close after this many seconds of wall time (0: never)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--seconds", options.quit_after_s, "Same as --quit-after")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--screenshot", options.screenshot,
                 "Write the last frame shown to this PNG on exit");
  app.add_option("--status", options.status,
                 "Write a JSON summary (frames, swaps, force, mouse) on exit");
  app.add_option(
      "--script", options.script,
      "Scripted actions 'FRAME:VERB ARGS; ...' (swap BODY MODEL, set BODY PARAM VALUE, play, "
      "pause, step, quit, mark, drag DX DY FRAMES, press DEPTH FRAMES, release, wheel NOTCHES, "
      "keydown KEY, keyup KEY)");
  app.add_option("--size", size, "Window size in pixels, WIDTHxHEIGHT");
  app.footer(
      "Mouse: left drag moves the stylus target on the view plane, the wheel moves it in depth. "
      "When a mouse device's tool carries a blade, hold C to cut (it holds the blade's button): "
      "the realtime run makes each cut off the haptic tick.");
  CLI11_PARSE(app, argc, argv);
  if (std::sscanf(size.c_str(), "%dx%d", &options.width, &options.height) != 2 ||
      options.width < 64 || options.height < 64) {
    tacta::log_error("--size: expected WIDTHxHEIGHT of at least 64x64, found '" + size + "'");
    return 2;
  }
  try {
    tacta::view::Viewer viewer(options);
    return viewer.run();
  } catch (const tacta::InputError& e) {
    tacta::log_error(e.what());
    return 2;
  } catch (const std::invalid_argument& e) {  // --script
    tacta::log_error(e.what());
    return 2;
  } catch (const std::exception& e) {
    tacta::log_error(e.what());
    return 1;
  }
}
