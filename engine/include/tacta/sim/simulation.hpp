// A scene loaded and running: builds the world from a validated scene (bodies, models, devices,
// interactions) and advances it on one persistent clock, either a tick at a time from the caller
// (step, advance_to: lockstep, on the calling thread) or in a batch on the chosen clock (run:
// lockstep or realtime). Between steps the caller reads and writes node state and loads, swaps
// models and changes parameters, and reads the report so far. Outputs (report.json, trace.csv,
// trajectory.csv, energy.csv, plots, frames) cover everything run since open. The public face of
// the engine for apps, the viewer, Python and tests.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tacta/mesh.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene.hpp"
#include "tacta/sim/cut.hpp"
#include "tacta/sim/handle.hpp"
#include "tacta/sim/run_status.hpp"
#include "tacta/sim/scheduler.hpp"
#include "tacta/sim/snapshot.hpp"

namespace tacta {

struct RunOptions {
  std::string out_dir;               // empty: write nothing
  std::optional<double> duration_s;  // overrides the scene's clock.duration_s
  std::optional<bool> realtime;      // overrides the scene's clock.mode
  bool progress = false;             // a progress bar on stderr
  std::string record_log;            // write the first device's session log here
  bool frames = false;               // force PNG frames on
  // Called with every snapshot the render task takes (frames, VTK, a window). Not owned.
  std::vector<FrameObserver*> observers;
};

struct BodyResult {
  std::string name, model;
  size_t nodes = 0, elements = 0, fixed_nodes = 0;
  double max_displacement_m = 0, kinetic_energy_J = 0, elastic_energy_J = 0;
  double initial_energy_J = 0;  // kinetic + elastic at t = 0
  bool frozen = false;
  std::string fault;
  std::string mesh;  // what the mesh source became (describe_body_mesh)
  std::vector<std::string>
      mesh_warnings;  // the mesh loader's warnings (surface not closed, pieces, ...)
  // A body with step_thread: own (its steps ran on a worker thread at step_rate_hz).
  bool own_thread = false;
  double step_rate_hz = 0;  // 0: stepped every haptic tick
  uint64_t worker_steps = 0;
  TickSummary worker_step_ms;    // wall time of each step on the worker
  uint64_t late_boundaries = 0;  // realtime: boundaries where the step was not finished
  double max_lateness_s = 0;     // realtime: longest time a step was collected past its boundary
  // Bodies that came or went while the scene ran (-1: in the scene from the start / never removed);
  // pending: requested or scheduled, not taken in yet.
  double added_s = -1, removed_s = -1;
  bool pending = false;
  // The final model's own counters (solver fallbacks, Newton iterations), in its order.
  std::vector<std::pair<std::string, double>> model_counters;
};

struct DeviceResult {
  std::string name, plugin;
  int32_t state = 0;  // tacta_device_state at the end of the run
  double max_force_N = 0;
  uint64_t contact_ticks = 0, reconnections = 0;
  std::vector<std::pair<std::string, double>> counters;  // the plugin's (device_api.h `counters`)
  uint64_t tool_changes = 0;                             // tools changed while the scene ran
};

struct RunResult {
  std::string scene, mode;
  ScheduleResult schedule;
  double sim_time_s = 0;
  std::string state_hash;  // FNV-1a 64 of every body's final node positions, hex
  std::vector<BodyResult> bodies;
  std::vector<DeviceResult> devices;
  size_t faults = 0;
  std::vector<std::string> fault_messages;  // one per fault: who, when (s), why
  std::vector<std::string> outputs;         // files written
  RunStatus status;   // status bits seen, collision roles (docs/REPORT.md `status`)
  int exit_code = 0;  // 0 ok, 1 runtime fault or error bit
};

// One body's node arrays, borrowed from the engine: valid until the Simulation is destroyed
// (bodies are never re-allocated after load). A cut gives the body new arrays: those taken before
// it stay readable, holding the state at the cut, but no longer follow the body; ask again after
// a cut. Write positions and velocities only between steps.
struct BodyArrays {
  size_t nodes = 0;
  double* positions = nullptr;             // 3 per node, m
  double* velocities = nullptr;            // 3 per node, m/s
  const double* rest_positions = nullptr;  // 3 per node, m
  const uint8_t* fixed = nullptr;          // 1 per node: held at rest
  const double* masses = nullptr;          // 1 per node, kg (lumped)
};

// A device's last sample and the force it was last sent, read between steps.
struct DeviceReading {
  double position[3] = {};  // m
  double proxy[3] = {};     // m, the god-object position on the surface
  double force[3] = {};     // N, last sent (zero after a fault)
  int32_t state = 0;        // tacta_device_state
  bool in_contact = false;
};

// The public face of a loaded scene, grouped: lifetime and run control, bodies, devices,
// outputs. Bodies and devices are named by handles (tacta/sim/handle.hpp): a stale handle (its
// body removed), a default one or one from another Simulation throws InputError naming it.
class Simulation {
 public:
  // ---- Lifetime and run control -------------------------------------------------------------

  // Builds everything the scene names; throws InputError, never leaves a half-built world.
  Simulation(const SceneDesc& scene, const PluginRegistry& plugins);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Runs `options.duration_s` (default: the scene's) more on the scene's clock (or the one
  // asked for), from the current time: on a fresh Simulation, the scene from t = 0. Outputs
  // written to options.out_dir cover everything since open.
  RunResult run(const RunOptions& options);
  // Ends run() after the current tick. The request is consumed when that run() returns, so a
  // later run() runs again (how the viewer pauses and plays on).
  void request_stop() noexcept;
  // Stepping (lockstep, on the calling thread, never while run() is running). step(n) advances n
  // haptic ticks and returns how many ran (fewer when the run must end: every device finished)
  // with what they raised (model, collision and device bits OR-ed, and whether one is an error,
  // e.g. a body faulted and froze); report() has the counts.
  StepResult step(uint64_t ticks = 1);
  // Steps whole ticks until time() reaches `time_s` (to within half a tick); as step().
  StepResult advance_to(double time_s);
  double time() const noexcept;    // s, simulated: tick() * dt()
  uint64_t tick() const noexcept;  // haptic ticks run since open
  double dt() const noexcept;      // s, one haptic tick
  const SceneDesc& scene() const;
  // What the scene asks for that is legal but likely a mistake (a body with every node fixed),
  // each naming the file, line and key; the caller prints them as warnings.
  std::vector<std::string> load_warnings() const;

  // ---- Bodies ------------------------------------------------------------------------------
  // Lookup. body(name) throws InputError (with a did-you-mean) for a name no body has; bodies()
  // lists the live handles (pending or present, not removed) in the order the bodies came.
  BodyHandle body(const std::string& name) const;
  std::vector<BodyHandle> bodies() const;
  bool body_alive(BodyHandle body) const noexcept;  // false once removal was requested
  const std::string& body_name(BodyHandle body) const;
  const std::string& body_model(BodyHandle body) const;  // the model asked for last
  const ParamSet& body_params(BodyHandle body) const;    // the model's parameters as last asked for

  // Adding and removing bodies while the scene runs, from any one thread at a time (the caller
  // between steps, or another thread during run()). add_body builds the body here (mesh, model:
  // allocates; InputError for a bad description, a name in use, step_thread: own, or no free slot
  // of the scene's capacity.bodies) and it enters at the next tick boundary, on the thread that
  // runs the tick; bodies() lists it from the call. remove_body takes the body out at the next
  // boundary (it stops stepping, colliding and being touched: a device touching it gets zero
  // force from that tick) and keeps it in the report; its handles are stale from the call.
  // Outside run() (before the first step or between steps) add_body also builds the body's
  // collision surface and render entries here, so from the boundary it enters at it collides,
  // is touched by devices and is in snapshots, frames and VTK, as a body the scene's `events`
  // add is from its time on. A body added from another thread during run() is stepped and
  // reported but not collided with, touched or drawn.
  BodyHandle add_body(const BodyDesc& desc);
  // The same from YAML text: one body as a scene lists it under `bodies` (paths relative to the
  // scene's folder).
  BodyHandle add_body(const std::string& yaml);
  void remove_body(BodyHandle body);

  // State between steps.
  BodyArrays body_arrays(BodyHandle body);
  // Tells the model that positions or velocities were written through body_arrays (its history,
  // e.g. the previous position of central differences, restarts from them).
  void state_written(BodyHandle body);
  const VolumeMesh& body_mesh(BodyHandle body) const;  // rest mesh: tets, triangles, quads
  // The triangles the body is drawn and touched through (its embedded surface, else the boundary)
  // and their current vertex positions (3 per vertex, m).
  const std::vector<uint32_t>& surface_triangles(BodyHandle body) const;
  std::vector<double> surface_positions(BodyHandle body) const;
  double kinetic_energy(BodyHandle body) const;  // J
  double elastic_energy(BodyHandle body) const;  // J

  // Loads: a force (N) on `nodes`, added to gravity and contact for every step until cleared or
  // replaced.
  void set_applied_forces(BodyHandle body, const std::vector<uint32_t>& nodes,
                          const std::vector<double>& forces);
  void clear_applied_forces(BodyHandle body);

  // Models and parameters. set_param changes one numeric parameter between steps: live when the
  // schema marks it so (the model's live_params) and its set_param takes it (returns true), else
  // by a swap to the same model with the new value (returns false; applied at the next tick).
  bool set_param(BodyHandle body, const std::string& name, double value);
  // From any thread but the haptic one, before or during run(): the body takes model `model`
  // with `params` (validated against its schema; empty = the defaults) at the start of the next
  // tick, positions and velocities carried over. The instance is built here, so this may
  // allocate and throws InputError when the model refuses the body; the haptic thread only
  // switches pointers. Also how the viewer changes a parameter (same model, new values).
  void request_model_swap(BodyHandle body, const std::string& model, const ParamSet& params);

  // Cutting (docs/ARCHITECTURE.md "Cutting"), between steps only (never during run()): a blade's
  // swept surface, `triangles` (9 doubles each: three corners, m, world frame), cuts `body` as it
  // stands now. Removal takes out the tets it passes through; separation opens the faces it
  // crosses. Everything derived from the mesh follows at once (masses, the model, fixed nodes,
  // probes, the embedded surface, collision, snapshots, VTK). InputError for a model that does not
  // take topology edits (tacta plugins lists which do), a body stepping on its own thread, a
  // removal that would leave no tet, or a triangle count not a multiple of 9 doubles.
  CutSummary cut(BodyHandle body, std::span<const double> triangles, CutMode mode);
  uint32_t body_revision(BodyHandle body) const;  // cuts that changed the body so far

  // ---- Devices -----------------------------------------------------------------------------
  // Lookup, as for bodies. Devices are fixed for a Simulation's life; their handles still carry
  // the Simulation's salt, so one from another Simulation is refused.
  DeviceHandle device(const std::string& name) const;
  std::vector<DeviceHandle> devices() const;  // in scene order
  const std::string& device_name(DeviceHandle device) const;
  const std::string& device_plugin(DeviceHandle device) const;  // the plugin's name, e.g. "mouse"
  // The last sample and the force last sent, read between steps.
  DeviceReading device_reading(DeviceHandle device) const;
  // From any thread, before or during run(): hands `values` to the device's input entry (the
  // mouse device: a target x, y, z in m). Lock-free in the plugin; false when the device takes
  // no input.
  bool device_input(DeviceHandle device, const double* values, uint32_t count);
  // The device's tool becomes `tool` at the next tick boundary (any one thread at a time, like
  // add_body): the collision shape the tool carries and the haptic proxy's radius change, and
  // the proxy starts afresh at the device's position. Builds the shape here (allocates;
  // InputError for a bad shape or a change still waiting).
  void change_tool(DeviceHandle device, const ShapeDesc& tool);
  // The same from YAML text: a shape as a device's `tool` gives it ({sphere: {radius: 0.004}}).
  void change_tool(DeviceHandle device, const std::string& yaml);

  // ---- Outputs -----------------------------------------------------------------------------
  // The state now, as the render task would draw it (positions, embedded surfaces, stress,
  // devices), and what does not change: for a picture between steps or after run() (`tacta
  // snapshot`, Python's Simulation.snapshot). Allocates; nothing is recorded.
  Snapshot snapshot();
  const SceneStatic& scene_static();
  // The report so far: what run() returns, for everything since open. A handle's index is its
  // row in report().bodies / report().devices.
  RunResult report() const;
  // Writes report.json, the CSV records and plots for everything since open into `dir`.
  std::vector<std::string> write_outputs(const std::string& dir);
  // Writes only report.json (no CSV records, no plots) into `dir`; returns its path.
  std::string write_report(const std::string& dir);
  // Frame observers for stepping (a window, a frame writer): told at each 1/render_rate of
  // simulated time. Not owned; detach before destroying them. run() takes its own in RunOptions.
  void attach(FrameObserver* observer);
  void detach(FrameObserver* observer);

  // ---- Checkpoint and restore (docs/ARCHITECTURE.md "Checkpoint and restore") ---------------
  // The run's evolving state between steps (never during run()): time, every body's nodes,
  // loads, model in use with its parameters and own state, faults, boundary motion; devices'
  // samples, contact, couplings and plugin state; records and counters so far. A fresh
  // Simulation of the same scene that restores it continues bit for bit. save_state throws
  // InputError naming the body when a model cannot be saved; restore_state throws InputError
  // saying what does not match (another scene, a body's node count, a newer version, damage).
  std::vector<uint8_t> save_state() const;
  void restore_state(std::span<const uint8_t> bytes);
  void save_state(const std::string& path) const;
  void restore_state(const std::string& path);
  // What the last save or restore could not carry (live devices reconnect), one line each.
  const std::vector<std::string>& checkpoint_notes() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// FNV-1a 64 over the bytes of the given doubles, as 16 hex digits.
std::string hash_positions(const std::vector<const std::vector<double>*>& arrays);

}  // namespace tacta
