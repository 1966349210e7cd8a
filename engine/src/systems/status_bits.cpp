#include "systems/status_bits.hpp"

#include <string>

#include "tacta/collision_api.h"
#include "tacta/model_api.h"

namespace tacta {

namespace {

using S = StatusSource;
using V = StatusSeverity;

constexpr StatusBitInfo kTable[] = {
    {S::Model, TACTA_STEP_NOT_FINITE, "not_finite", V::Error,
     "NaN or infinity in the state: lower the time step (clock.haptic_rate_hz up) or stiffen less; "
     "the body was frozen"},
    {S::Model, TACTA_STEP_DIVERGED, "diverged", V::Error,
     "the step blew up: raise the haptic rate, add damping or use an implicit model; the body was "
     "frozen"},
    {S::Model, TACTA_STEP_SOLVER_NOT_CONVERGED, "solver_not_converged", V::Warning,
     "the iterative solver hit its limit: raise the model's iteration count or tolerance, or lower "
     "the time step"},
    {S::Model, TACTA_STEP_INVERTED_ELEMENT, "inverted_element", V::Warning,
     "an element turned inside out: refine the mesh where it deforms most, or use a model that "
     "handles inversion"},
    {S::Collision, TACTA_COLLIDE_OVERFLOW, "overflow", V::Warning,
     "a pair or contact buffer was full and contacts were missed: see collision.capacity in "
     "report.json; "
     "thin collision.thickness or coarsen the surfaces"},
    {S::Collision, TACTA_COLLIDE_NOT_FINITE, "not_finite", V::Error,
     "NaN or infinity in a surface or shape: a body diverged or a device sent a bad pose"},
    {S::Collision, TACTA_COLLIDE_DEGENERATE, "degenerate", V::Warning,
     "degenerate triangles were skipped: clean the surface mesh (zero-area or out-of-range "
     "triangles)"},
    {S::Collision, TACTA_COLLIDE_UNPREPARED, "unprepared", V::Error,
     "the collision world no longer matches what the plugin prepared: a plugin or engine bug, "
     "report it"},
    {S::Collision, TACTA_COLLIDE_REBUILT, "rebuilt", V::Info,
     "information: a hierarchy was rebuilt rather than refitted (large deformation); nothing to "
     "do"},
    {S::Collision, TACTA_COLLIDE_UNRESOLVED, "unresolved", V::Warning,
     "some contacts stayed penetrating: raise the haptic rate, or thicken collision.thickness"},
    {S::Device, kDeviceDisconnected, "disconnected", V::Warning,
     "the device sent nothing on these ticks: check its link (cable, network, peer process)"},
    {S::Device, kDeviceFault, "fault", V::Error,
     "the device faulted or sent a non-finite pose: see its status_reason; it rendered no force "
     "after"},
    {S::Device, kDeviceClamped, "clamped", V::Warning,
     "the force asked for exceeded the device's peak: lower devices[].coupling.stiffness"},
    {S::Device, kDeviceSilenced, "silenced", V::Warning,
     "the force was zeroed because a body faulted or froze: see that body's status"},
};

}  // namespace

std::span<const StatusBitInfo> status_bit_table() noexcept { return kTable; }

const StatusBitInfo* status_bit_info(StatusSource source, uint32_t bit) noexcept {
  for (const StatusBitInfo& e : kTable)
    if (e.source == source && e.bit == bit) return &e;
  return nullptr;
}

bool has_error_bit(StatusSource source, uint32_t bits) noexcept {
  for (uint32_t rest = bits; rest != 0; rest &= rest - 1) {
    const StatusBitInfo* e = status_bit_info(source, 1u << __builtin_ctz(rest));
    if (e != nullptr && e->severity == StatusSeverity::Error) return true;
  }
  return false;
}

std::vector<StatusBitCount> describe(const StatusCounter& counter, StatusSource source) {
  std::vector<StatusBitCount> out;
  for (uint32_t b = 0; b < 32; ++b) {
    if (counter.ticks[b] == 0) continue;
    const StatusBitInfo* e = status_bit_info(source, 1u << b);
    StatusBitCount c;
    c.name = e != nullptr ? e->name : "bit_" + std::to_string(b);
    c.bit = 1u << b;
    c.severity = e != nullptr ? e->severity : StatusSeverity::Warning;
    c.ticks = counter.ticks[b];
    c.first_time_s = counter.first_time_s[b];
    c.remedy = e != nullptr ? e->remedy
                            : "a bit this engine does not know: see the plugin's documentation";
    out.push_back(std::move(c));
  }
  return out;
}

const char* severity_name(StatusSeverity s) noexcept {
  switch (s) {
    case StatusSeverity::Info: return "info";
    case StatusSeverity::Warning: return "warning";
    case StatusSeverity::Error: return "error";
  }
  return "?";
}

}  // namespace tacta
