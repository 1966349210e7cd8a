// The touched body's surface as the OpenIGTLink device streams it: the vertices the triangles
// use (compacted, in the order first used) and the triangles over them. The render thread fills
// frames (SurfaceFeed::offer) and the network thread takes the newest (SurfaceFeed::take)
// through a triple buffer: no lock between them, no allocation after the first frame.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "tacta/device_api.h"
#include "tacta/sim/triple_buffer.hpp"

namespace tacta::igtl_device {

struct SurfaceFrame {
  double time = -1;            // s, simulated time; -1: nothing yet
  std::vector<double> points;  // 3 per vertex, m
};

struct SurfaceShape {
  std::string body;
  std::vector<uint32_t> node_of_vertex;  // the body's node each streamed vertex is
  std::vector<uint32_t> triangles;       // 3 per triangle, indices into the streamed vertices
};

class SurfaceFeed {
 public:
  // Render thread. The first call (and a body of another shape) builds the shape and the buffers.
  void offer(const tacta_device_surface& s) {
    if (!shape_ || shape_->body != s.body || shape_nodes_ != s.node_count) build(s);
    SurfaceFrame& frame = buffer_->write_slot();
    frame.time = s.time;
    const std::vector<uint32_t>& nodes = shape_->node_of_vertex;
    for (size_t v = 0; v < nodes.size(); ++v)
      for (size_t a = 0; a < 3; ++a) frame.points[3 * v + a] = s.positions[3 * nodes[v] + a];
    buffer_->publish();
  }

  // Network thread: the newest frame since the last take, with its shape; false when none.
  bool take(const SurfaceFrame*& frame, const SurfaceShape*& shape) noexcept {
    Published* p = published_.load(std::memory_order_acquire);
    if (p == nullptr || !p->buffer->acquire()) return false;
    frame = &p->buffer->read_slot();
    shape = p->shape.get();
    return true;
  }

 private:
  struct Published {
    std::unique_ptr<SurfaceShape> shape;
    std::unique_ptr<TripleBuffer<SurfaceFrame>> buffer;
  };

  void build(const tacta_device_surface& s) {
    auto shape = std::make_unique<SurfaceShape>();
    shape->body = s.body != nullptr ? s.body : "";
    std::vector<int64_t> vertex_of_node(s.node_count, -1);
    for (uint32_t i = 0; i < 3 * s.triangle_count; ++i) {
      const uint32_t node = s.triangles[i];
      if (node >= s.node_count) continue;
      if (vertex_of_node[node] < 0) {
        vertex_of_node[node] = static_cast<int64_t>(shape->node_of_vertex.size());
        shape->node_of_vertex.push_back(node);
      }
      shape->triangles.push_back(static_cast<uint32_t>(vertex_of_node[node]));
    }
    SurfaceFrame prototype;
    prototype.points.assign(3 * shape->node_of_vertex.size(), 0.0);
    // A body change is rare (the device touched another body): the old generation is kept alive
    // for the network thread that may still read it, and freed with the feed.
    retired_.push_back(std::make_unique<Published>(
        Published{std::move(shape), std::make_unique<TripleBuffer<SurfaceFrame>>(prototype)}));
    shape_ = retired_.back()->shape.get();
    buffer_ = retired_.back()->buffer.get();
    shape_nodes_ = s.node_count;
    published_.store(retired_.back().get(), std::memory_order_release);
  }

  const SurfaceShape* shape_ = nullptr;
  TripleBuffer<SurfaceFrame>* buffer_ = nullptr;
  uint32_t shape_nodes_ = 0;
  std::vector<std::unique_ptr<Published>> retired_;  // every generation built, newest last
  std::atomic<Published*> published_{nullptr};
};

}  // namespace tacta::igtl_device
