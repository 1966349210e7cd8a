// A scene as loaded and checked from YAML: every value here is validated (types, ranges, units,
// plugin parameter schemas), so building the world from it cannot fail on input. SI units.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tacta/error.hpp"
#include "tacta/param_set.hpp"
#include "tacta/plugin.h"
#include "tacta/sim/cut.hpp"

namespace tacta {

using Vec3 = std::array<double, 3>;

struct MaterialDesc {
  double youngs_modulus = 0;      // E, Pa
  double poisson_ratio = 0;       // nu
  double density = 1000;          // rho, kg/m^3
  double lame_lambda = 0;         // Pa (derived from E, nu when those are given, and vice versa)
  double lame_mu = 0;             // Pa
  double rayleigh_mass = 0;       // alpha, 1/s
  double rayleigh_stiffness = 0;  // beta, s
};

// A closed surface filled with conforming quality tetrahedra by Gmsh (mesh.tetrahedralize).
struct TetrahedralizeDesc {
  double max_volume = 0;        // m^3, largest tet (0: sized from the surface triangles)
  double min_dihedral_deg = 0;  // degrees: the worst tet's smallest dihedral angle must reach this
  double min_radius_ratio = 0;  // 3 r_in / r_circ (1 regular): the worst tet must reach this
  bool optimize = true;         // Gmsh's tet optimiser after meshing
};

// Where the body's mesh comes from: a file or a built-in primitive.
struct MeshSourceDesc {
  enum class Kind { File, BoxGrid, BeamGrid, QuadGrid, Sphere } kind = Kind::File;
  std::string path;                   // File: absolute, resolved against the scene folder
  Vec3 size{1, 1, 1};                 // BoxGrid/BeamGrid: edge lengths, m; QuadGrid: x, y used
  std::array<int, 3> cells{1, 1, 1};  // grid cells along x, y, z (QuadGrid: x, y)
  Vec3 origin{0, 0, 0};               // corner with the smallest coordinates, m (Sphere: centre)
  double radius = 0.05;               // Sphere, m
  int subdivisions = 2;               // Sphere resolution
  double voxel_size = 0;              // File with a surface only: tet grid cell, m (0 = automatic)
  // File with a surface only, automatic voxels or tetrahedralize without max_volume: the most
  // tets the body may have (0: kDefaultMaxTets, mesh_build.hpp), so that it steps at 1 kHz.
  int64_t max_tets = 0;
  std::optional<TetrahedralizeDesc>
      tetrahedralize;       // File with a surface only: Gmsh instead of voxels
  Vec3 scale{1, 1, 1};      // applied to file coordinates (e.g. mm -> m: 0.001)
  Vec3 translate{0, 0, 0};  // applied after scale, m
  // `surface:` a finer surface file bound to the tets (scale and translate apply to it too);
  // empty: a voxelised surface file is its own embedded surface, other meshes show their tets.
  std::string surface_path;
  bool surface_tet_boundary = false;  // `surface: tet_boundary`: draw and touch the tets' boundary
  SourceLocation surface_where;       // the scene's `surface` key, for messages
  SourceLocation where;               // the scene's `file` key (or the primitive's), for messages
};

struct FixedRegionDesc {
  std::optional<std::array<Vec3, 2>> box;  // nodes inside [min, max], m, are fixed
  std::vector<uint32_t> indices;           // explicit node indices
};

// A vector as a function of time, piecewise linear through (time, value) points and held at the
// first and last value outside them; a single point is a constant. Units of the quantity (m).
struct TimeSeriesDesc {
  std::vector<double> times_s;  // strictly increasing
  std::vector<Vec3> values;     // one per time
};

// Prescribed displacement (from rest) of the nodes of a region, on some or all world axes; the
// other axes stay free (sliding on a plane: prescribe 0 along its normal axis only).
struct PrescribedDesc {
  FixedRegionDesc region;
  std::array<bool, 3> axes{true, true, true};  // x, y, z: which components are prescribed
  TimeSeriesDesc displacement;                 // m, added to the rest position
  SourceLocation where;
};

// A rigid plate (a moving plane) that presses the nodes of a region when they reach it.
struct PlateDesc {
  std::string name;
  FixedRegionDesc region;  // nodes the plate may touch
  Vec3 point{0, 0, 0};     // a point of the plate at rest, m
  Vec3 normal{0, 1, 0};    // unit, from the plate into the body
  TimeSeriesDesc motion;   // m, translation of the plate from its rest place
  bool stuck = false;      // true: a node that touches sticks; false: frictionless
  SourceLocation where;
};

// A point of a body given in rest coordinates, followed through its element (probes.csv).
struct ProbeDesc {
  std::string name;
  Vec3 rest{0, 0, 0};  // m
};

struct BodyDesc {
  std::string name;
  MeshSourceDesc mesh;
  MaterialDesc material;
  std::string model;  // model plugin name
  ParamSet model_params;
  std::vector<FixedRegionDesc> fixed;
  SourceLocation fixed_where;  // the scene's `fixed` key, for messages
  // Initial state: per-node displacement/velocity overrides, and uniform ones.
  struct NodeVector {
    uint32_t node;
    Vec3 value;
  };
  std::vector<NodeVector> initial_displacement;  // m
  std::vector<NodeVector> initial_velocity;      // m/s
  Vec3 uniform_velocity{0, 0, 0};                // m/s, added to every free node
  std::optional<uint32_t> probe_node;            // node whose displacement compare/plots follow
  std::vector<PrescribedDesc> prescribed;        // boundary motion, engine-applied for any model
  std::vector<PlateDesc> plates;
  std::vector<ProbeDesc> probes;
  double step_rate_hz = 0;  // 0: step at the haptic rate; else at this rate
  bool own_thread = false;  // step_thread: own: step on a worker thread (needs step_rate_hz)
  // own_thread: the haptic loop renders its surface through the local spring model
  // (local_contact: yielding) or as the last refreshed state (local_contact: rigid).
  bool local_contact_yielding = true;
  bool collide = true;
  SourceLocation where;
};

// A device's tool as a blade (`tool.blade`): the edge, in the device's frame (m, from the sampled
// position, turned by the sampled orientation), cuts every body it sweeps through while button
// `button` is held; what it swept is cut every `interval_s` and when the button is let go.
struct BladeDesc {
  std::array<Vec3, 2> edge{Vec3{0, 0, 0}, Vec3{0, -0.02, 0}};
  uint32_t button = 0;  // bit of the device sample's buttons
  CutMode mode = CutMode::kSeparate;
  double interval_s = 0.01;  // s: the latency from the sweep to the cut, at most
  SourceLocation where;
};

// A rigid tool carried by a device (the stylus tip) or a static obstacle.
struct ShapeDesc {
  enum class Kind { Sphere, Capsule, Box, Plane, Mesh } kind = Kind::Sphere;
  double radius = 0.002;             // m (Sphere, Capsule)
  double half_length = 0.01;         // m (Capsule, along the tool axis)
  Vec3 half_extents{0.1, 0.1, 0.1};  // m (Box)
  Vec3 normal{0, 1, 0};              // Plane
  double offset = 0;                 // Plane: n . x = offset, m
  std::string path;                  // Mesh: convex hull of this file
  SourceLocation path_where;         // Mesh: the scene's `file` key, for messages
  Vec3 position{0, 0, 0};            // m
  std::optional<BladeDesc> blade;    // a device's tool only: it cuts (tool.blade)
};

struct DeviceDesc {
  std::string name;
  std::string plugin;  // device plugin name
  ParamSet params;
  ShapeDesc tool;                   // what the device holds (its collision shape)
  double coupling_stiffness = 500;  // N/m, virtual coupling device <-> proxy
  double coupling_damping = 1.0;    // N s/m
  bool coupling_passivity = true;   // passivity controller acts; false: observe only (Z-width runs)
  bool coupling_first_contact =
      true;             // first-contact stretch limit; false: the coupling alone (Z-width)
  std::string touches;  // body name, empty = all bodies
  // `stream_surface`: the surface a device that takes one (OpenIGTLink POLYDATA) is sent: the
  // body's embedded surface when it has one (false, `embedded`), or the boundary of its
  // simulation tets (true, `simulation`).
  bool stream_simulation_surface = false;
  SourceLocation where;
};

struct ObstacleDesc {
  std::string name;
  ShapeDesc shape;  // contact friction: collision.friction
};

struct CollisionDesc {
  bool enabled = false;
  std::string broad_phase = "bvh";  // collision plugin names
  std::string narrow_phase = "ccd";
  std::string convex = "convex";
  ParamSet broad_params, narrow_params, convex_params;
  // collision.plugins: the plugin serving each role, by TACTA_COLLISION_ROLE_* bit index
  // (broad_phase, proxy, narrow_phase, response); empty = the first loaded plugin declaring it.
  std::array<std::string, 4> role_plugins;
  std::array<ParamSet, 4> role_params;
  std::array<SourceLocation, 4> role_where;
  double friction = 0.3;  // Coulomb coefficient, body-body and body-obstacle
  bool self_collision = false;
  double thickness = 1e-4;  // m, contact margin
  // collision.proxy_refit: how the hierarchies the haptic proxy queries follow the bodies each
  // tick: a slice of elements refit per tick with the queries widened by what the rest may have
  // moved (true, `sliced`), or every element refit every tick (`every_tick`). Same answers.
  bool proxy_refit_sliced = true;
  SourceLocation
      thickness_where;  // the scene's `thickness` key, for the bound checked on the meshes
};

struct SwapDesc {
  double time = 0;   // s
  std::string body;  // body name, "*" = every body
  std::string model;
  ParamSet params;
};

// A device's tool replaced while the scene runs (an event's `change_tool`, or the stepping API).
struct ToolChangeDesc {
  std::string device;  // the device's name
  ShapeDesc tool;
};

// A cut a scene makes at an event's time (tacta/sim/cut.hpp): the blade's swept surface.
struct CutEventDesc {
  std::string body;
  CutMode mode = CutMode::kSeparate;
  std::vector<double> triangles;  // 9 per triangle: three corners, m, world frame
  SourceLocation where;
};

// Something that changes the scene while it runs (scene key `events`): exactly one of `add` (a
// whole body, as under `bodies`), `remove` (a body's name), `change_tool` and `cut`.
struct BodyEventDesc {
  double time = 0;  // s, simulated
  std::optional<BodyDesc> add;
  std::string remove;
  std::optional<ToolChangeDesc> change_tool;
  std::optional<CutEventDesc> cut;
  SourceLocation where;
};

// The longest run, in haptic ticks (1 h at 1 kHz): per-tick records (trace rows, tick timings,
// ~150 bytes a tick) are reserved before the run so the haptic path never allocates.
constexpr uint64_t kMaxRunTicks = 3'600'000;

struct ClockDesc {
  enum class Mode { Lockstep, Realtime } mode = Mode::Lockstep;
  double haptic_rate_hz = 1000;
  double render_rate_hz = 60;
  double duration_s = 1.0;
  // Realtime only (docs/SCENES.md, clock): the haptic thread's scheduling and placement.
  int haptic_priority = 80;  // SCHED_FIFO priority 1..99; 0: stay SCHED_OTHER
  int haptic_cpu = -1;       // pin the haptic thread to this CPU, others off it; -1: no pinning
  bool lock_memory = true;   // mlockall for the run
  bool shallow_idle = true;  // realtime: PM QoS keeps the CPUs out of deep idle states
  bool poll_idle = true;     // realtime, pinned: a SCHED_IDLE spinner keeps the haptic CPU busy
  double spin_us = 50;       // us before each deadline spun instead of slept
  // A checkpoint of this scene to continue from (Simulation::save_state, `--checkpoint-at`): the
  // Simulation opens at its time. Absolute; empty: start at t = 0.
  std::string resume;
};

// Empty when `duration_s` at `haptic_rate_hz` fits kMaxRunTicks trace rows (one a tick per
// device, at least one), else why not (for messages).
std::string duration_limit_problem(double duration_s, double haptic_rate_hz, size_t devices = 1);

// The largest picture side, pixels: the off-screen renderer's framebuffer limit (llvmpipe's), and
// an 8192 x 8192 RGBA picture is already 256 MB.
constexpr int kMaxFrameSide = 8192;

struct OutputDesc {
  bool frames = false;              // PNG frames from the render task
  std::vector<double> frame_times;  // s; empty with frames=true: every frame
  int frame_width = 800, frame_height = 600;
  bool vtk = false;                  // .vtu series + .pvd
  double vtk_interval_s = 1.0 / 60;  // s between VTK frames
  bool trace = true;                 // trace.csv
  bool trajectory = false;           // trajectory.csv: every node, every record interval
  double record_interval_s = 0;      // s; 0 = every tick
  std::vector<std::string> plots;    // "phase_portrait", "force", "energy", "displacement"
  std::vector<uint32_t> plot_nodes;  // nodes the phase portrait follows (default: corners)
};

struct SceneDesc {
  std::string path;       // the scene file
  std::string directory;  // its folder; relative paths resolve against it
  std::string name;
  Vec3 gravity{0, -9.81, 0};  // m/s^2
  ClockDesc clock;
  std::vector<BodyDesc> bodies;
  std::vector<DeviceDesc> devices;
  std::vector<ObstacleDesc> obstacles;
  CollisionDesc collision;
  std::vector<SwapDesc> swaps;
  OutputDesc output;
  uint64_t seed = 1;
  // Threads a model's parallel_for runs on (the stepping thread included); 1: serial. The
  // result then depends on the ordering a model picks for parallel work, not on this number.
  uint32_t threads = 1;
  std::vector<BodyEventDesc> events;  // sorted by time
  // Body slots reserved at load (scene key capacity.bodies): the scene's bodies, its events'
  // and those added through the API. 0: the scene's and its events' plus kSpareBodySlots.
  uint32_t body_capacity = 0;
};

constexpr uint32_t kSpareBodySlots = 16;

}  // namespace tacta
