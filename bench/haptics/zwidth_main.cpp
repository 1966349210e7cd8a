// zwidth: the largest stable coupling stiffness at 1 kHz for each model (the Z-width table of
// docs/BENCHMARKS.md). For every model, hand, coupling damping and passivity setting it bisects
// devices.*.coupling.stiffness over the Z-width scene and prints one Markdown table row per
// model and hand; --csv also writes every case with its verdict numbers.
//   zwidth [--scene scenes/bench/zwidth.yaml] [--models corotational_fem,tensor_mass,...]
//          [--hands firm,light] [--dampings 0,1] [--csv FILE]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "zwidth_run.hpp"

namespace {

using tacta::bench::ZwidthCase;
using tacta::bench::ZwidthResult;

// Model label -> the scene's `model:` value: the same block and material for all of them.
const std::map<std::string, std::string> kModels = {
    {"corotational_fem", "corotational_fem"},
    {"tensor_mass", "{name: tensor_mass, integrator: implicit_euler}"},
    {"mass_spring", "{name: mass_spring, integrator: implicit_euler}"},
    {"fd_debunne", "fd_debunne"},
    {"bullet_softbody", "bullet_softbody"},
    {"vbd", "vbd"},
    {"vbd_neo_hookean", "{name: vbd, energy: neo_hookean}"},
};
// Hand label -> sim_stylus overrides. firm: the plugin's defaults (critically damped);
// light: the same hand with a tenth of the damping, a loose grip.
const std::map<std::string, std::vector<std::string>> kHands = {
    {"firm", {"devices.*.params.hand_damping=11"}},
    {"light", {"devices.*.params.hand_damping=1"}},
};
constexpr double kOmniUsableStiffness = 1000.0;  // N/m at 1 kHz (docs/REFERENCES.md)

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

std::string cell(const ZwidthResult& r, const tacta::bench::ZwidthSearch& search,
                 bool stable_at_omni) {
  char text[96];
  if (r.smallest_unstable == 0.0)
    std::snprintf(text, sizeof text, "≥ %.0f", search.k_max);
  else if (r.largest_stable == 0.0)
    std::snprintf(text, sizeof text, "< %.0f", search.k_min);
  else
    std::snprintf(text, sizeof text, "%.0f", r.largest_stable);
  return std::string(text) + (stable_at_omni ? " ✓" : " ✗");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Largest stable coupling stiffness at 1 kHz per model (Z-width table)"};
  std::string scene = std::string(TACTA_SOURCE_DIR) + "/scenes/bench/zwidth.yaml";
  std::string models = "corotational_fem,tensor_mass,mass_spring,fd_debunne,bullet_softbody,vbd";
  std::string hands = "firm,light", dampings = "0,1", csv_path;
  std::string work = std::string(TACTA_BINARY_DIR) + "/zwidth_runs";
  tacta::bench::ZwidthSearch search;
  app.add_option("--scene", scene, "Z-width scene")->check(CLI::ExistingFile);
  app.add_option("--models", models, "comma-separated models");
  app.add_option("--hands", hands, "comma-separated hands: firm, light");
  app.add_option("--dampings", dampings, "comma-separated coupling dampings, N s/m");
  app.add_option("--k-min", search.k_min, "lowest stiffness tried, N/m");
  app.add_option("--k-max", search.k_max, "highest stiffness tried, N/m");
  app.add_option("--resolution", search.resolution, "bisection stops at this ratio");
  app.add_option("--csv", csv_path, "write every case here");
  app.add_option("--work", work, "folder for the runs' traces");
  CLI11_PARSE(app, argc, argv);

  try {
    tacta::bench::ZwidthRunner runner(scene, work, TACTA_PLUGIN_DIR);
    std::ofstream csv;
    if (!csv_path.empty()) {
      csv.open(csv_path);
      csv << "model,hand,coupling_damping_Ns_per_m,passivity,largest_stable_N_per_m,smallest_"
             "unstable_N_per_m,"
             "unstable_reason,mean_force_N,rendered_stiffness_N_per_m,oscillation_rms_N,min_port_"
             "energy_J,stable_at_1000_N_per_m,runs\n";
    }
    std::printf("| model | hand |");
    for (const std::string& b : split(dampings))
      std::printf(" b = %s, off | b = %s, on |", b.c_str(), b.c_str());
    std::printf("\n|---|---|");
    for (size_t i = 0; i < split(dampings).size(); ++i) std::printf("---|---|");
    std::printf("\n");
    for (const std::string& model : split(models)) {
      if (!kModels.count(model)) throw std::runtime_error("unknown model " + model);
      for (const std::string& hand : split(hands)) {
        if (!kHands.count(hand)) throw std::runtime_error("unknown hand " + hand);
        std::printf("| %s | %s |", model.c_str(), hand.c_str());
        for (const std::string& b : split(dampings)) {
          for (bool passivity : {false, true}) {
            ZwidthCase c{kModels.at(model), std::stod(b), passivity, kHands.at(hand)};
            const ZwidthResult r = runner.largest_stable(c, search);
            const tacta::bench::StabilityVerdict omni = runner.run(c, kOmniUsableStiffness);
            std::printf(" %s |", cell(r, search, omni.stable).c_str());
            std::fflush(stdout);
            if (csv.is_open())
              csv << model << ',' << hand << ',' << b << ',' << passivity << ',' << r.largest_stable
                  << ',' << r.smallest_unstable << ',' << r.unstable_reason << ','
                  << r.at_largest_stable.mean_force << ',' << r.at_largest_stable.rendered_stiffness
                  << ',' << r.at_largest_stable.oscillation_rms << ','
                  << r.at_largest_stable.min_port_energy << ',' << omni.stable << ',' << r.runs + 1
                  << '\n'
                  << std::flush;
          }
        }
        std::printf("\n");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zwidth: %s\n", e.what());
    return 2;
  }
  return 0;
}
