// The run's CSV records: per-tick device data, node trajectories, per-frame energies.
#include <cmath>
#include <cstdio>
#include <memory>

#include "run_outputs.hpp"

namespace tacta {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_or_throw(const std::string& path) {
  File f(std::fopen(path.c_str(), "w"));
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

}  // namespace

void write_csv_records(const std::string& dir, const HapticLoop& loop, const World& world,
                       RunResult& result) {
  if (world.device_count() > 0 && world.scene().output.trace) {
    const std::string path = dir + "/trace.csv";
    File f = open_or_throw(path);
    std::fprintf(f.get(),
                 "time_s,device,device_x_m,device_y_m,device_z_m,proxy_x_m,proxy_y_m,proxy_z_m,"
                 "force_x_N,force_y_N,force_z_N,force_N,contact,tick_ms\n");
    for (const TraceRow& r : loop.trace().rows()) {
      const double magnitude =
          std::sqrt(r.force[0] * r.force[0] + r.force[1] * r.force[1] + r.force[2] * r.force[2]);
      std::fprintf(f.get(), "%.6f,%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%u,%.6f\n",
                   r.time_s, r.device, r.position[0], r.position[1], r.position[2], r.proxy[0],
                   r.proxy[1], r.proxy[2], r.force[0], r.force[1], r.force[2], magnitude, r.contact,
                   r.tick_ms);
    }
    result.outputs.push_back(path);
  }
  if (!loop.trajectory().rows().empty()) {
    const std::string path = dir + "/trajectory.csv";
    File f = open_or_throw(path);
    std::fprintf(f.get(), "time_s,body,node,x,y,z,vx,vy,vz\n");
    for (const TrajectoryRow& r : loop.trajectory().rows())
      std::fprintf(f.get(), "%.6f,%s,%u,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", r.time_s,
                   world.body(r.body).info.name.c_str(), r.node, r.x[0], r.x[1], r.x[2], r.v[0],
                   r.v[1], r.v[2]);
    result.outputs.push_back(path);
  }
  if (!loop.probes().rows().empty()) {
    const std::string path = dir + "/probes.csv";
    File f = open_or_throw(path);
    std::fprintf(f.get(), "time_s,body,probe,x,y,z,ux,uy,uz\n");
    for (const ProbeRow& r : loop.probes().rows()) {
      const Vec3& rest = world.body(r.body).recording.probes[r.probe].rest;
      std::fprintf(f.get(), "%.6f,%s,%s,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", r.time_s,
                   world.body(r.body).info.name.c_str(),
                   world.body(r.body).recording.probes[r.probe].name.c_str(), r.x[0], r.x[1],
                   r.x[2], r.x[0] - rest[0], r.x[1] - rest[1], r.x[2] - rest[2]);
    }
    result.outputs.push_back(path);
  }
  if (!loop.energy().rows().empty()) {
    const std::string path = dir + "/energy.csv";
    File f = open_or_throw(path);
    std::fprintf(f.get(), "time_s,body,kinetic_J,elastic_J,total_J,max_displacement_m\n");
    for (const EnergyRow& r : loop.energy().rows())
      std::fprintf(f.get(), "%.6f,%s,%.12g,%.12g,%.12g,%.9g\n", r.time_s,
                   world.body(r.body).info.name.c_str(), r.kinetic_J, r.elastic_J,
                   r.kinetic_J + r.elastic_J, r.max_displacement_m);
    result.outputs.push_back(path);
  }
}

}  // namespace tacta
