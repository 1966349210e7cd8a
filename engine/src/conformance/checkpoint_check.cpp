// Checkpoint check: a model's save_state / load_state (or its NO_HISTORY claim) let a restored
// instance continue bit for bit, and load_state refuses a damaged or foreign blob with a reason.
// It drives the raw table (create, no begin after a load), as a restore does.
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "conformance/checks.hpp"
#include "conformance/test_body.hpp"

namespace tacta::conformance {

namespace {

constexpr int kStepsBeforeSave = 7;
constexpr int kStepsAfterSave = 12;

const tacta_model_api& api_of(const tacta_descriptor& model) {
  return *static_cast<const tacta_model_api*>(model.api);
}

// One instance on the raw table; throws when create() refuses the test body.
class RawModel {
 public:
  RawModel(const tacta_descriptor& model, const TestBody& body)
      : api_(api_of(model)), size_(model.api_size) {
    const tacta_model_setup setup = body.setup();
    char message[256] = {};
    if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(std::string("create() refused the test cube: ") + message);
  }
  ~RawModel() {
    if (instance_) api_.destroy(instance_);
  }
  RawModel(const RawModel&) = delete;
  RawModel& operator=(const RawModel&) = delete;

  void begin(const tacta_body_state& state, double dt) {
    if (api_.begin) api_.begin(instance_, &state, dt);
  }
  uint32_t step(tacta_body_state& state, double dt) { return api_.step(instance_, &state, dt); }
  std::vector<unsigned char> save() {
    std::vector<unsigned char> blob(api_.save_state(instance_, nullptr, 0));
    const size_t written = api_.save_state(instance_, blob.data(), blob.size());
    if (written != blob.size())
      throw std::runtime_error("save_state asked for " + std::to_string(blob.size()) +
                               " bytes, then wrote " + std::to_string(written));
    return blob;
  }
  // TACTA_OK, or the status with the plugin's reason in why.
  tacta_status load(const void* bytes, size_t size, std::string& why) {
    char message[256] = {};
    const tacta_status status = api_.load_state(instance_, bytes, size, message, sizeof message);
    why = message;
    return status;
  }
  std::vector<double> counters() {
    std::vector<double> values;
    if (size_ < offsetof(tacta_model_api, counters) + sizeof(void*) || !api_.counters)
      return values;
    std::vector<tacta_model_counter> all(api_.counters(instance_, nullptr, 0));
    all.resize(api_.counters(instance_, all.data(), static_cast<uint32_t>(all.size())));
    for (const tacta_model_counter& c : all) values.push_back(c.value);
    return values;
  }

 private:
  const tacta_model_api& api_;
  uint32_t size_;
  void* instance_ = nullptr;
};

// A clamped cube under gravity and a smoothly varying load on its free corner, so the solvers,
// warm starts and integrator histories all carry something from step to step (a smooth load
// keeps extrapolated warm starts in use rather than rejected).
struct LoadedRun {
  const TestBody& body;
  NodeState state;
  double time = 0;
  LoadedRun(const TestBody& b, const NodeState& s) : body(b), state(s) {}
  void steps(RawModel& model, int count) {
    const size_t corner = 3 * (body.mesh.node_count() - 1);
    for (int k = 0; k < count; ++k, time += body.dt) {
      for (size_t i = 2; i < state.f.size(); i += 3) state.f[i] = -9.81 * body.masses[i / 3];
      state.f[corner] = 0.02 * body.force_scale() * (1.0 + std::sin(40.0 * time));  // 6 Hz
      tacta_body_state view = state.view(time);
      model.step(view, body.dt);
    }
  }
};

size_t differing(const std::vector<double>& a, const std::vector<double>& b) {
  size_t count = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    count += std::memcmp(&a[i], &b[i], sizeof(double)) != 0;
  return count;
}

// load_state of damaged blobs: each must be refused with a reason. Empty when all were.
std::string refusals(RawModel& model, const std::vector<unsigned char>& blob) {
  std::vector<unsigned char> foreign(blob.size(), 0x5A);  // not any model's header
  const std::pair<const char*, std::vector<unsigned char>> bad[] = {
      {"a blob cut by one byte", {blob.begin(), blob.end() - (blob.empty() ? 0 : 1)}},
      {"half a blob", {blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(blob.size() / 2)}},
      {"a blob of foreign bytes", foreign},
  };
  for (const auto& [what, bytes] : bad) {
    std::string why;
    if (model.load(bytes.data(), bytes.size(), why) == TACTA_OK)
      return std::string("load_state accepted ") + what;
    if (why.empty()) return std::string("load_state refused ") + what + " without a reason";
  }
  return {};
}

}  // namespace

CheckResult check_checkpoint(const tacta_descriptor& model) {
  const char* name = "checkpoint";
  const tacta_model_api& api = api_of(model);
  const bool entries = tacta_model_has_state_entries(&api, model.api_size);
  const bool no_history = claims_of(model) & TACTA_MODEL_CLAIM_NO_HISTORY;
  if (!entries && !no_history)
    return {name,
            "not checkpointable: neither save_state/load_state entries nor the "
            "TACTA_MODEL_CLAIM_NO_HISTORY claim",
            Verdict::Fail};
  const auto body = make_test_body(model, true);
  RawModel original(model, *body);
  LoadedRun run(*body, NodeState(body->mesh.positions));
  original.begin(run.state.view(), body->dt);
  run.steps(original, kStepsBeforeSave);
  const LoadedRun at_save = run;
  std::vector<unsigned char> blob;
  if (entries) blob = original.save();
  run.steps(original, kStepsAfterSave);

  RawModel restored(model, *body);
  LoadedRun again = at_save;
  std::string how = "a fresh instance, no begin() (NO_HISTORY)";
  if (entries) {
    std::string why;
    if (restored.load(blob.data(), blob.size(), why) != TACTA_OK)
      return {name, "load_state refused its own blob: " + why, Verdict::Fail};
    how = "a fresh instance, load_state of a " + std::to_string(blob.size()) + "-byte blob";
  }
  again.steps(restored, kStepsAfterSave);
  const size_t diff = differing(run.state.x, again.state.x) + differing(run.state.v, again.state.v);
  std::string text = how + ", " + std::to_string(kStepsAfterSave) +
                     " steps: " + std::to_string(diff) +
                     " position/velocity doubles differ, limit 0";
  bool pass = diff == 0;
  // A fresh NO_HISTORY instance counts from zero; a loaded one continues the original's counts.
  if (entries && original.counters() != restored.counters()) {
    text += "; counters() differ from the original's";
    pass = false;
  }
  if (entries) {
    const std::string refused = refusals(restored, blob);
    if (refused.empty()) {
      text += "; cut, halved and foreign blobs refused";
    } else {
      text += "; " + refused;
      pass = false;
    }
  }
  return {name, text, pass ? Verdict::Pass : Verdict::Fail};
}

}  // namespace tacta::conformance
