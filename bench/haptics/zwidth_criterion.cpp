#include "zwidth_criterion.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace tacta::bench {
namespace {

double magnitude(const std::array<double, 3>& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// RMS of y about its least-squares line in t (N); the mean of y in *mean.
double detrended_rms(const std::vector<double>& t, const std::vector<double>& y, double* mean) {
  const auto n = static_cast<double>(y.size());
  double st = 0, sy = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    st += t[i];
    sy += y[i];
  }
  const double tm = st / n, ym = sy / n;
  double stt = 0, sty = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    stt += (t[i] - tm) * (t[i] - tm);
    sty += (t[i] - tm) * (y[i] - ym);
  }
  const double slope = stt > 0 ? sty / stt : 0.0;
  double ss = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    const double r = y[i] - (ym + slope * (t[i] - tm));
    ss += r * r;
  }
  *mean = ym;
  return std::sqrt(ss / n);
}

}  // namespace

StabilityVerdict judge_stability(std::span<const TraceSample> trace, const StabilityCriterion& c,
                                 bool body_fault) {
  StabilityVerdict v;
  double energy = 0.0;  // J, port energy: work of the held force on the environment
  std::vector<double> t, f, t_early, f_early;
  double stretch_sum = 0.0;  // m
  bool non_finite = false;
  for (size_t i = 0; i < trace.size(); ++i) {
    const TraceSample& s = trace[i];
    const double magnitude_now = magnitude(s.force);
    if (!std::isfinite(magnitude_now)) non_finite = true;
    v.peak_force = std::max(v.peak_force, magnitude_now);
    if (i > 0) {
      const TraceSample& p = trace[i - 1];
      for (size_t a = 0; a < 3; ++a) energy -= p.force[a] * (s.device[a] - p.device[a]);
      v.min_port_energy = std::min(v.min_port_energy, energy);
    }
    if (s.time >= c.hold_start && s.time <= c.hold_end && !s.contact) ++v.contact_lost;
    if (s.time >= c.hold_start && s.time <= c.hold_start + c.settle_window) {
      t_early.push_back(s.time);
      f_early.push_back(magnitude_now);
    }
    if (s.time >= c.hold_end - c.settle_window && s.time <= c.hold_end) {
      t.push_back(s.time);
      f.push_back(magnitude_now);
      stretch_sum +=
          magnitude({s.proxy[0] - s.device[0], s.proxy[1] - s.device[1], s.proxy[2] - s.device[2]});
    }
  }
  if (body_fault || non_finite) {
    v.reason = "body fault";
    return v;
  }
  if (t.size() < 3 || t_early.size() < 3) {
    v.reason = "trace too short for the settle window";
    return v;
  }
  v.oscillation_rms = detrended_rms(t, f, &v.mean_force);
  double early_mean = 0.0;
  v.early_oscillation_rms = detrended_rms(t_early, f_early, &early_mean);
  const double mean_stretch = stretch_sum / static_cast<double>(t.size());
  if (mean_stretch > 0.0) v.rendered_stiffness = v.mean_force / mean_stretch;
  if (v.contact_lost > 0) {
    v.reason = "contact lost during the hold";
    return v;
  }
  const double tolerance = std::max(c.abs_tolerance, c.rel_tolerance * v.mean_force);
  const bool settled = v.oscillation_rms <= tolerance;
  const bool decaying = v.oscillation_rms <= c.decay_ratio * v.early_oscillation_rms;
  if (!settled && !decaying) {
    v.reason = "force oscillation persists or grows over the hold";
    return v;
  }
  v.stable = true;
  v.reason = "ok";
  return v;
}

std::vector<TraceSample> read_trace_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the trace");
  std::string line;
  if (!std::getline(in, line))
    throw std::runtime_error(path + ":1: empty trace, expected a header");
  std::vector<std::string> header;
  {
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) header.push_back(cell);
  }
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw std::runtime_error(path + ":1: no column '" + name + "' in the trace header");
    return static_cast<size_t>(it - header.begin());
  };
  const size_t time = column("time_s"), device = column("device"), contact = column("contact");
  const std::array<size_t, 3> pos{column("device_x_m"), column("device_y_m"), column("device_z_m")};
  const std::array<size_t, 3> proxy{column("proxy_x_m"), column("proxy_y_m"), column("proxy_z_m")};
  const std::array<size_t, 3> force{column("force_x_N"), column("force_y_N"), column("force_z_N")};
  std::vector<TraceSample> out;
  std::vector<double> cells;
  for (size_t number = 2; std::getline(in, line); ++number) {
    cells.clear();
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
      char* end = nullptr;
      cells.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str())
        throw std::runtime_error(path + ":" + std::to_string(number) + ": not a number: " + cell);
    }
    if (cells.size() != header.size())
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected " +
                               std::to_string(header.size()) + " columns");
    if (cells[device] != 0.0) continue;
    TraceSample s;
    s.time = cells[time];
    for (size_t a = 0; a < 3; ++a) {
      s.device[a] = cells[pos[a]];
      s.proxy[a] = cells[proxy[a]];
      s.force[a] = cells[force[a]];
    }
    s.contact = cells[contact] != 0.0;
    out.push_back(s);
  }
  return out;
}

}  // namespace tacta::bench
